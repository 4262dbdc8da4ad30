/* SPDX-License-Identifier: MIT */
/* link_modes.c - the modes a session set (docs/link.md 1, "Modes"): what the controller
 * keeps until it is changed and loses when it restarts, noted as the lines ran, so that a
 * reconnect can send them again before the first motion (fbrl_link_modes_resend). Pure
 * text work on the caller's storage: no link, no OS. */
#include "link_internal.h"

/* The slots, in the order the modes are sent again: the units first (the tool's location
 * is typed in them), the tool's location and the tool, the speed, the pendant lamp, then
 * one slot per motor gain (GAIN 0,v sets every motor: it is sent before the others). */
enum { SLOT_UNITS, SLOT_TOOL_POINT, SLOT_TOOL, SLOT_SPEED, SLOT_LAMP, SLOT_GAIN };
#define GAIN_MOTORS 9 /* GAIN's motor 0 (all) .. 8 */

typedef char check_slots[SLOT_GAIN + GAIN_MOTORS == FBRL_LINK_MODES_MAX ? 1 : -1];

/* The controller's line limit bounds every line kept (dst and src may be the same). */
static void put(char *dst, const char *src)
{
    size_t k = 0;
    for (; src[k] && k < FBRL_LINK_LINE_MAX; k++)
        dst[k] = src[k];
    dst[k] = '\0';
}

void fbrl_link_modes_init(fbrl_link_modes *m)
{
    if (!m)
        return;
    for (unsigned k = 0; k < FBRL_LINK_MODES_MAX; k++)
        m->line[k][0] = '\0';
    m->point[0] = '\0';
    m->point_units = m->tool_units = FBRL_LINK_UNITS_UNKNOWN;
}

/* The same location name at the start of both argument lists ("P1" of "P1,14,2...";
 * the link keeps its lines upper-cased). */
static int same_name(const char *a, const char *b)
{
    size_t n = 0;
    for (; a[n] && a[n] != ',' && a[n] != ' '; n++)
        if (a[n] != b[n])
            return 0;
    return n > 0 && (b[n] == ',' || b[n] == ' ' || !b[n]);
}

void fbrli_link_modes_note(fbrl_link_modes *m, const char *line, int units)
{
    fbrl_rapl_cmd c;
    const char *args, *pargs;
    if (!m || fbrl_rapl_line_cmd(line, &c, &args) != FBRL_OK)
        return;
    switch (c) {
    case FBRL_RAPL_POINT: /* not a mode: the tool that names it takes it along */
        put(m->point, line);
        m->point_units = units;
        return;
    case FBRL_RAPL_METRIC:
    case FBRL_RAPL_NOMETRIC: put(m->line[SLOT_UNITS], line); return;
    case FBRL_RAPL_SPEED: put(m->line[SLOT_SPEED], line); return;
    case FBRL_RAPL_FLASH:
    case FBRL_RAPL_NOFLASH: put(m->line[SLOT_LAMP], line); return;
    case FBRL_RAPL_TOOL:
        /* TOOL copies its location's values: that location, as the last POINT defined it,
         * goes with it (the robot words' scratch points are redefined for every move) */
        put(m->line[SLOT_TOOL], line);
        m->line[SLOT_TOOL_POINT][0] = '\0';
        m->tool_units = FBRL_LINK_UNITS_UNKNOWN;
        if (*args && fbrl_rapl_line_cmd(m->point, &c, &pargs) == FBRL_OK && same_name(args, pargs)) {
            put(m->line[SLOT_TOOL_POINT], m->point);
            m->tool_units = m->point_units;
        }
        return;
    case FBRL_RAPL_GAIN: {
        /* GAIN n,value sets motor n (0: every motor); GAIN n alone only prints it */
        unsigned motor = 0, digits = 0;
        for (; *args >= '0' && *args <= '9' && digits < 2; args++, digits++)
            motor = motor * 10u + (unsigned)(*args - '0');
        while (*args == ' ')
            args++;
        if (digits == 0 || motor >= GAIN_MOTORS || *args != ',')
            return;
        for (unsigned k = 1; motor == 0 && k < GAIN_MOTORS; k++)
            m->line[SLOT_GAIN + k][0] = '\0';
        put(m->line[SLOT_GAIN + motor], line);
        return;
    }
    default: return;
    }
}

const char *fbrl_link_modes_line(const fbrl_link_modes *m, size_t i)
{
    for (unsigned k = 0; m && k < FBRL_LINK_MODES_MAX; k++)
        if (m->line[k][0] && i-- == 0)
            return m->line[k];
    return 0;
}

int fbrli_link_modes_units(const fbrl_link_modes *m, size_t i)
{
    const char *line = fbrl_link_modes_line(m, i);
    return line && line == m->line[SLOT_TOOL_POINT] ? m->tool_units : FBRLI_NO_LENGTHS;
}
