/* SPDX-License-Identifier: MIT */
/* console_compose.h - the operator console's composer (SCREEN_COMPOSE). */
#ifndef FBRLMON_CONSOLE_COMPOSE_H
#define FBRLMON_CONSOLE_COMPOSE_H

#include "console_state.h"

/* F4: the composer (the level allowing). */
void con_compose_open(console *c);
void con_compose_draw(console *c);
/* A key in the composer: 1 for F5 (ask for the new method's name), else 0. */
int con_compose_key(console *c, int ch);
/* Save the picked steps as method NAME in the library; nothing is written when anything
 * is wrong (the hint says what). */
void con_compose_save(console *c, const char *name);

#endif
