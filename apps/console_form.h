/* SPDX-License-Identifier: MIT */
/* console_form.h - the operator console's parameter form (SCREEN_FORM). */
#ifndef FBRLMON_CONSOLE_FORM_H
#define FBRLMON_CONSOLE_FORM_H

#include "console_state.h"

/* The fields from the method's parameters as set now; the first selected. */
void con_form_fill(console *c);
/* Every field checked; the first bad one selected and named. 0 and the values in v if all
 * are good (the run sets them). */
int con_form_commit(console *c, long *v);
void con_form_draw(console *c);
/* A key on the form: 1 for F5 (start the run), else 0. */
int con_form_key(console *c, int ch);

#endif
