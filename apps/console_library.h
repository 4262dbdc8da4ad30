/* SPDX-License-Identifier: MIT */
/* console_library.h - the operator console's method library (SCREEN_LIBRARY). */
#ifndef FBRLMON_CONSOLE_LIBRARY_H
#define FBRLMON_CONSOLE_LIBRARY_H

#include "console_state.h"

/* The library (again) from its folder; the hint says what was left out. */
void con_library_scan(console *c);
/* F2: the library, read again. */
void con_library_open(console *c);
void con_library_draw(console *c);
/* Up/Down choose, Enter opens the method (loads its file): its form. */
void con_library_key(console *c, int ch);

#endif
