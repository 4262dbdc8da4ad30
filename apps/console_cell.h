/* SPDX-License-Identifier: MIT */
/* console_cell.h - the operator console's work cell (SCREEN_CELL) and TEACH. */
#ifndef FBRLMON_CONSOLE_CELL_H
#define FBRLMON_CONSOLE_CELL_H

#include "console_state.h"

/* F6: the work cell (the level allowing), from the screen shown now. */
void con_cell_open(console *c);
void con_cell_draw(console *c);
/* Up/Down choose, t or Enter TEACH the place, Esc back. */
void con_cell_key(console *c, int ch);

#endif
