/* SPDX-License-Identifier: MIT */
/* sim_errors.h - the RAPL-II error numbers the emulator reports (NNN-TEXT.),
 * named once; their texts are in sim_errors.c. docs/rapl-commands.md lists them. */
#ifndef FBRL_SIM_ERRORS_H
#define FBRL_SIM_ERRORS_H

enum sim_rapl_error {
    SIM_E_ILLEGAL_OPERAND = 8,
    SIM_E_END_OF_LINE = 9,
    SIM_E_SYMBOL_UNDEFINED = 10,
    SIM_E_LOCATION_UNDEFINED = 11,
    SIM_E_COMMAND = 12,
    SIM_E_ARG_MISSING = 13,
    SIM_E_BAD_SYNTAX = 14,
    SIM_E_PRECISION_POINT = 15, /* a precision point where a cartesian one is needed */
    SIM_E_IO_ADDRESS = 16,
    SIM_E_PROGRAM_NOT_FOUND = 17,
    SIM_E_ILLEGAL_ARG = 18,
    SIM_E_ARG_TOO_BIG = 20,
    SIM_E_NO_ROOM = 21,
    SIM_E_TABLE_FULL = 22,
    SIM_E_AD_CHANNEL = 24,
    SIM_E_LINE_TOO_LONG = 25,
    SIM_E_TRANSFORM = 29, /* no arm configuration reaches the pose */
    SIM_E_POWER_OFF = 40,
    SIM_E_NOT_HOMED = 41,
    SIM_E_JOINT_RANGE = 42, /* joint n = 1..5 out of range: SIM_E_JOINT_RANGE + n - 1 */
    SIM_E_CHECKSUM = 47,
    SIM_E_JOINT6_RANGE = 48, /* [D] joint 6 (A465): 048, reserved in the A255 table */
    SIM_E_AMBIGUOUS = 50,
    SIM_E_ILLEGAL_CHANNEL = 61,
    SIM_E_BAD_AXIS = 65,
    SIM_E_NOT_AVAILABLE = 66,
    SIM_E_STRAIGHT_LINE = 68,
    /* [D] fbrlsim's own: the arm met the work cell (--cell). RAPL-II's table ends before 100
     * (75 entries, reference/rapl-research.md), so no real code is taken. */
    SIM_E_COLLISION = 190
};

/* The code for joint index i (0-based) out of range. */
int sim_error_joint(int i);

/* The text after NNN- ("TRANSFORM ILLEGAL"); "ERROR" for a code without one. */
const char *sim_error_text(int code);

#endif
