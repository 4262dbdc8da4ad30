/* SPDX-License-Identifier: MIT */
/* sim_errors.c - the texts of the RAPL-II error numbers (sim_errors.h), as the
 * controller prints them after NNN-. */
#include "sim_errors.h"

#include <stddef.h>

#define JOINTS_IN_TABLE 5 /* 042-046: joints 1-5 of the A255 table */

int sim_error_joint(int i) { return i < JOINTS_IN_TABLE ? SIM_E_JOINT_RANGE + i : SIM_E_JOINT6_RANGE; }

const char *sim_error_text(int code)
{
    static const struct {
        int code;
        const char *text;
    } t[] = {
        {SIM_E_ILLEGAL_OPERAND, "ILLEGAL OPERAND"},
        {SIM_E_END_OF_LINE, "END OF LINE NOT FOUND"},
        {SIM_E_SYMBOL_UNDEFINED, "SYMBOL UNDEFINED"},
        {SIM_E_LOCATION_UNDEFINED, "LOCATION UNDEFINED"},
        {SIM_E_COMMAND, "COMMAND ERROR"},
        {SIM_E_ARG_MISSING, "ARGUMENT MISSING"},
        {SIM_E_BAD_SYNTAX, "BAD SYNTAX"},
        {SIM_E_PRECISION_POINT, "PRECISION POINT NOT LEGAL"},
        {SIM_E_IO_ADDRESS, "I/O ADDRESS ERROR"},
        {SIM_E_PROGRAM_NOT_FOUND, "PROGRAM NOT FOUND"},
        {SIM_E_ILLEGAL_ARG, "ILLEGAL ARGUMENT"},
        {SIM_E_ARG_TOO_BIG, "ARGUMENT TOO BIG"},
        {SIM_E_NO_ROOM, "NO ROOM LEFT"},
        {SIM_E_TABLE_FULL, "TABLE FULL"},
        {SIM_E_AD_CHANNEL, "ILLEGAL A/D CHANNEL"},
        {SIM_E_LINE_TOO_LONG, "LINE TOO LONG"},
        {SIM_E_TRANSFORM, "TRANSFORM ILLEGAL"},
        {SIM_E_POWER_OFF, "ARM POWER HAS BEEN SWITCHED OFF"},
        {SIM_E_NOT_HOMED, "ROBOT HAS NOT BEEN HOMED"},
        {SIM_E_JOINT_RANGE + 0, "JOINT #1 OUT OF RANGE"},
        {SIM_E_JOINT_RANGE + 1, "JOINT #2 OUT OF RANGE"},
        {SIM_E_JOINT_RANGE + 2, "JOINT #3 OUT OF RANGE"},
        {SIM_E_JOINT_RANGE + 3, "JOINT #4 OUT OF RANGE"},
        {SIM_E_JOINT_RANGE + 4, "JOINT #5 OUT OF RANGE"},
        {SIM_E_CHECKSUM, "CHECKSUM FAILURE"},
        {SIM_E_JOINT6_RANGE, "JOINT #6 OUT OF RANGE"},
        {SIM_E_AMBIGUOUS, "AMBIGUOUS COMMAND"},
        {SIM_E_ILLEGAL_CHANNEL, "ILLEGAL CHANNEL"},
        {SIM_E_BAD_AXIS, "BAD AXIS NUMBER"},
        {SIM_E_NOT_AVAILABLE, "NOT AVAILABLE"},
        {SIM_E_STRAIGHT_LINE, "STRAIGHT LINE ERROR"},
        {SIM_E_COLLISION, "COLLISION"},
    };
    size_t i;
    for (i = 0; i < sizeof t / sizeof t[0]; i++)
        if (t[i].code == code)
            return t[i].text;
    return "ERROR";
}
