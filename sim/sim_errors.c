/* sim_errors.c - the texts of the RAPL-II error numbers (sim_errors.h). */
#include "sim_errors.h"

#include <stddef.h>

const char *sim_error_text(int code)
{
    static const struct { int code; const char *text; } t[] = {
        { 8, "ILLEGAL OPERAND" }, { 9, "END OF LINE NOT FOUND" }, { 10, "SYMBOL UNDEFINED" },
        { 11, "LOCATION UNDEFINED" }, { 12, "COMMAND ERROR" }, { 13, "ARGUMENT MISSING" },
        { 14, "BAD SYNTAX" }, { 15, "PRECISION POINT NOT LEGAL" }, { 16, "I/O ADDRESS ERROR" },
        { 17, "PROGRAM NOT FOUND" }, { 18, "ILLEGAL ARGUMENT" }, { 20, "ARGUMENT TOO BIG" },
        { 21, "NO ROOM LEFT" }, { 22, "TABLE FULL" }, { 24, "ILLEGAL A/D CHANNEL" },
        { 25, "LINE TOO LONG" },
        { 29, "TRANSFORM ILLEGAL" }, { 40, "ARM POWER HAS BEEN SWITCHED OFF" },
        { 41, "ROBOT HAS NOT BEEN HOMED" }, { 42, "JOINT #1 OUT OF RANGE" },
        { 43, "JOINT #2 OUT OF RANGE" }, { 44, "JOINT #3 OUT OF RANGE" },
        { 45, "JOINT #4 OUT OF RANGE" }, { 46, "JOINT #5 OUT OF RANGE" },
        { 47, "CHECKSUM FAILURE" }, { 50, "AMBIGUOUS COMMAND" }, { 61, "ILLEGAL CHANNEL" },
        { 65, "BAD AXIS NUMBER" }, { 66, "NOT AVAILABLE" }, { 68, "STRAIGHT LINE ERROR" },
    };
    size_t i;
    for (i = 0; i < sizeof t / sizeof t[0]; i++)
        if (t[i].code == code)
            return t[i].text;
    return "ERROR";
}
