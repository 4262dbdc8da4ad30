/* SPDX-License-Identifier: MIT */
/* link_internal.h - what the link's files share inside the library (not installed). */
#ifndef FBRL_LINK_INTERNAL_H
#define FBRL_LINK_INTERNAL_H

#include "fbrl/link.h"

/* ---- link_modes.c ---- */

/* A line ran (FBRL_OK) while the controller's units were `units`: keep it if it sets a
 * mode (or is a POINT a later TOOL may name). */
void fbrli_link_modes_note(fbrl_link_modes *m, const char *line, int units);
/* The units the lengths of mode line i were typed in (FBRL_LINK_UNITS_*), or
 * FBRLI_NO_LENGTHS for a line without lengths. */
#define FBRLI_NO_LENGTHS (-2)
int fbrli_link_modes_units(const fbrl_link_modes *m, size_t i);

#endif
