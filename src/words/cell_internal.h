/* SPDX-License-Identifier: MIT */
/* cell_internal.h - what the work cell's words (robot_cell.c) share with its picture
 * (cell_svg.c) (private). */
#ifndef FBRL_WORDS_CELL_INTERNAL_H
#define FBRL_WORDS_CELL_INTERNAL_H

#include "internal_names.h"
#include "fbrl/cell_words.h"

/* "12.3456" locale-free into buf ("?" if it does not fit); returns buf. */
const char *cw_num(char *buf, size_t cap, double v);
/* Carry every block's obstacles to where its calibration puts the block now. */
void cw_place_blocks(fbrl_cell_words *cw);

#endif
