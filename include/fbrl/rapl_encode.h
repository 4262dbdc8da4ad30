/* SPDX-License-Identifier: MIT */
/* rapl_encode.h - RAPL-II command lines for the CRS controller, from one command table.
 *
 * fbrl_rapl_encode() writes one command line (without the CR) into a caller's buffer,
 * either with the command's keyword ("APPRO P1,2,S") or its /NNN token
 * ("/002 P1,2,S"). Keyword text is the default: no public client shows a real
 * controller accepting tokens (DESIGN 5). Commands without a known token are written
 * as keywords in both forms.
 *
 * Arguments are checked against the command's signature before a byte is written:
 * names (locations, variables, programs) are 1-8 letters/digits/'_' starting with a letter,
 * a location name may carry a '#' prefix (precision point); reals are rounded to the
 * controller's four decimals and written as the shortest text of that value ("2.5",
 * "90", never an exponent), independent of the C locale.
 * The module includes no OS header. */
#ifndef FBRL_RAPL_ENCODE_H
#define FBRL_RAPL_ENCODE_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every command the FBRL robot instruction set (thesis 5.3, appendix I-5) sends, and the
 * controller's other commands fbrlsim knows (from DLOCN on). The values are part of the
 * ABI (bindings store them): never renumber, append new commands before NCMDS. */
typedef enum fbrl_rapl_cmd {
    FBRL_RAPL_ACTUAL = 0,
    FBRL_RAPL_ALIGN = 1,
    FBRL_RAPL_APPRO = 2,
    FBRL_RAPL_ARM = 3,
    FBRL_RAPL_CLOSE = 4,
    FBRL_RAPL_CONFIG = 5,
    FBRL_RAPL_DEPART = 6,
    FBRL_RAPL_FINISH = 7,
    FBRL_RAPL_FLASH = 8,
    FBRL_RAPL_GAIN = 9,
    FBRL_RAPL_GRIP = 10,
    FBRL_RAPL_HALT = 11,
    FBRL_RAPL_HERE = 12,
    FBRL_RAPL_HOME = 13,
    FBRL_RAPL_JOG = 14,
    FBRL_RAPL_JOINT = 15,
    FBRL_RAPL_LIMP = 16,
    FBRL_RAPL_LOCK = 17,
    FBRL_RAPL_MA = 18,
    FBRL_RAPL_MANUAL = 19,
    FBRL_RAPL_MI = 20,
    FBRL_RAPL_MOTOR = 21,
    FBRL_RAPL_MOVE = 22,
    FBRL_RAPL_NOFLASH = 23,
    FBRL_RAPL_NOHELP = 24,
    FBRL_RAPL_NOLIMP = 25,
    FBRL_RAPL_NOMANUAL = 26,
    FBRL_RAPL_NOTEACH = 27,
    FBRL_RAPL_OPEN = 28,
    FBRL_RAPL_OUTPUT = 29,
    FBRL_RAPL_POINT = 30,
    FBRL_RAPL_READY = 31,
    FBRL_RAPL_RUN = 32,
    FBRL_RAPL_SERIAL = 33,
    FBRL_RAPL_SET = 34,
    FBRL_RAPL_SHIFTA = 35,
    FBRL_RAPL_SPEED = 36,
    FBRL_RAPL_STATUS = 37,
    FBRL_RAPL_TEACH = 38,
    FBRL_RAPL_TOOL = 39,
    FBRL_RAPL_TYPEI = 40,
    FBRL_RAPL_TYPEV = 41,
    FBRL_RAPL_UNLOCK = 42,
    FBRL_RAPL_W0 = 43,
    FBRL_RAPL_W1 = 44,
    FBRL_RAPL_W2 = 45,
    FBRL_RAPL_W3 = 46,
    FBRL_RAPL_W4 = 47,
    FBRL_RAPL_W5 = 48,
    FBRL_RAPL_WAIT = 49,
    FBRL_RAPL_WE1 = 50,
    FBRL_RAPL_WE3 = 51,
    FBRL_RAPL_WE5 = 52,
    FBRL_RAPL_XCAL = 53,
    FBRL_RAPL_XHOME = 54,
    FBRL_RAPL_XZERO = 55,
    FBRL_RAPL_ASSIGN = 56, /* variable assignment: NAME=value */
    FBRL_RAPL_DLOCN = 57,
    FBRL_RAPL_DVAR = 58,
    FBRL_RAPL_HELP = 59,
    FBRL_RAPL_LISTL = 60,
    FBRL_RAPL_LISTV = 61,
    FBRL_RAPL_SHIFT = 62,
    FBRL_RAPL_TYPE = 63,
    FBRL_RAPL_ENABLE = 64,   /* ENABLE ARM: arm power on */
    FBRL_RAPL_DISABLE = 65,  /* DISABLE ARM: arm power off */
    FBRL_RAPL_ONPOWER = 66,  /* waits until arm power is on */
    FBRL_RAPL_METRIC = 67,   /* lengths in mm from now on */
    FBRL_RAPL_NOMETRIC = 68, /* lengths in inches from now on */
    FBRL_RAPL_NCMDS = 69
} fbrl_rapl_cmd;

typedef enum fbrl_rapl_form {
    FBRL_RAPL_KEYWORD = 0, /* "APPRO P1,2.0000" (default) */
    FBRL_RAPL_TOKEN = 1    /* "/002 P1,2.0000" (the thesis's tokenised form) */
} fbrl_rapl_form;

/* What a command prints after its CR and how a client reads it (fbrl_rapl_cmdinfo.reply;
 * the link's fbrl_link_reply is the same type). Values are stable. */
typedef enum fbrl_rapl_reply {
    FBRL_RAPL_REPLY_NONE = 0,   /* nothing but an error line, if any */
    FBRL_RAPL_REPLY_POS = 1,    /* W0 W2 W4 block */
    FBRL_RAPL_REPLY_STATUS = 2, /* STATUS block */
    FBRL_RAPL_REPLY_INT = 3,    /* one integer line (TYPEI) */
    FBRL_RAPL_REPLY_REAL = 4,   /* one real line (TYPEV) */
    FBRL_RAPL_REPLY_LINES = 5,  /* any lines (SERIAL, GAIN, LISTL ...) */
    FBRL_RAPL_REPLY_STREAM = 6  /* W1 W3 W5 WE*: value lines until stopped */
} fbrl_rapl_reply;

/* Command properties (fbrl_rapl_cmdinfo.flags). */
#define FBRL_RAPL_F_STRAIGHT 0x1u /* accepts the ",S" straight-line suffix */
#define FBRL_RAPL_F_MOTION   0x2u /* starts a motion: the prompt returns when it starts */
#define FBRL_RAPL_F_STREAM   0x4u /* prints until the host sends a bare CR (W1 W3 W5 WE*) */
#define FBRL_RAPL_F_WAITS \
    0x8u /* its prompt may come late: it waits for a motion, an
                                    * input or a program (motions, FINISH, WAIT, RUN) */
#define FBRL_RAPL_F_SAFE \
    0x10u /* safe to repeat: running it twice ends as running it
                                    * once (absolute moves and settings, read-only queries).
                                    * Relative motions, counters, deletions, program runs,
                                    * HERE ACTUAL XCAL XZERO (they store where the arm is)
                                    * and WAIT are not: the link never types those twice
                                    * (docs/link.md 3.9) */

/* One table entry. The signature has one character per argument:
 *   L location name ('#' prefix allowed)   V variable name   N program name
 *   I integer   R real (an integer argument is accepted)
 *   W one of `words` ('|'-separated; ';' starts the list of the next W slot)
 *   T free text (printable, the rest of the line; TYPE)
 *   [ the arguments after it are optional   * the previous kind repeats (1..8 in all)
 *   = the next argument follows '=' instead of ',' (assignment)
 * POINT is special: after a cartesian name come 6 reals (x y z yaw pitch roll), after a
 * '#' name 5 integers (motor pulses). */
typedef struct fbrl_rapl_cmdinfo {
    const char *keyword; /* "APPRO"; "" for the assignment */
    uint16_t token;      /* 2 for /002; 0 = no token (keyword in both forms) */
    const char *sig;
    const char *words; /* for 'W': allowed words separated by '|', else NULL */
    unsigned flags;
    fbrl_rapl_reply reply; /* what it prints */
} fbrl_rapl_cmdinfo;

/* The table entry of cmd, or NULL when cmd is out of range. */
FBRL_API const fbrl_rapl_cmdinfo *fbrl_rapl_cmd_info(fbrl_rapl_cmd cmd);

/* Look a keyword up (case-insensitive, whole word). FBRL_ENOENT when unknown. */
FBRL_API fbrl_status fbrl_rapl_cmd_find(const char *keyword, fbrl_rapl_cmd *cmd);

/* Which command a line starts with: its first word (up to a space, ',' or '=', leading
 * spaces skipped) as a keyword or a /NNN token, or FBRL_RAPL_ASSIGN when a '=' follows it
 * (NAME=value: checked first, so GRIP=2 sets a variable, as the controller reads it).
 * *args (may be NULL) = where the rest begins, spaces skipped (an assignment's '=').
 * FBRL_ENOENT when the line starts with no command of the table (text the library cannot
 * name), FBRL_EINVAL for NULL. The one place every part of the library asks this. */
FBRL_API fbrl_status fbrl_rapl_line_cmd(const char *line, fbrl_rapl_cmd *cmd, const char **args);

/* Is this line safe to type twice (docs/link.md 3.9)? A table command says it in the table
 * (FBRL_RAPL_F_SAFE); an assignment is safe unless its value reads its own target
 * (V1=V1+1, a counter); anything the table cannot name is not. */
FBRL_API int fbrl_rapl_line_safe(const char *line);

typedef enum fbrl_rapl_argkind { FBRL_RAPL_ARG_INT, FBRL_RAPL_ARG_REAL, FBRL_RAPL_ARG_STR } fbrl_rapl_argkind;

/* One argument. Use the helpers below to build them. */
typedef struct fbrl_rapl_arg {
    fbrl_rapl_argkind kind;
    long i;        /* FBRL_RAPL_ARG_INT */
    double r;      /* FBRL_RAPL_ARG_REAL */
    const char *s; /* FBRL_RAPL_ARG_STR: a name or a word, NUL-terminated */
} fbrl_rapl_arg;

static inline fbrl_rapl_arg fbrl_rapl_int(long v)
{
    fbrl_rapl_arg a = {FBRL_RAPL_ARG_INT, v, 0.0, 0};
    return a;
}
static inline fbrl_rapl_arg fbrl_rapl_real(double v)
{
    fbrl_rapl_arg a = {FBRL_RAPL_ARG_REAL, 0, v, 0};
    return a;
}
static inline fbrl_rapl_arg fbrl_rapl_str(const char *s)
{
    fbrl_rapl_arg a = {FBRL_RAPL_ARG_STR, 0, 0.0, s};
    return a;
}

/* Decimals the controller keeps of a real (it prints them with %+09.4f): the encoder
 * rounds to this precision, so the shorter text reads back to the same value. */
/* The arms a RAPL-II controller drives: the A255 has 5 axes, the A465 6. MA, MI and a
 * precision point (POINT #name,...) carry one value per axis. */
#define FBRL_RAPL_ARM_AXES_MIN 5
#define FBRL_RAPL_ARM_AXES_MAX 6

#define FBRL_RAPL_REAL_DECIMALS 4

/* Largest magnitude of a real and an integer argument. A real is sent with at most four
 * decimals; 999999.9999 keeps it exact as a fixed-point number and far beyond any
 * distance, angle or gain the controller handles. Integers cover 10-digit pulses
 * within 32 bits. */
#define FBRL_RAPL_REAL_MAX 999999.9999
#define FBRL_RAPL_INT_MAX  2147483647L

/* Longest line the encoder produces (POINT with 6 reals); buffers of this size never
 * give FBRL_ENOSPC. The controller's own line limit (error 025) is larger. */
#define FBRL_RAPL_LINE_MAX 96

/* Encode one command line into buf (NUL-terminated; *len = bytes without the NUL; no CR).
 * straight != 0 appends ",S" (only for commands with FBRL_RAPL_F_STRAIGHT).
 * Errors: FBRL_EINVAL (null pointer, unknown cmd, wrong argument count or kind, ",S" not
 * allowed), FBRL_ENAME (bad name), FBRL_ENONFINITE, FBRL_ERANGE (magnitude too large or
 * word not allowed), FBRL_ENOSPC (buf too small; buf then holds ""). */
FBRL_API fbrl_status fbrl_rapl_encode(char *buf, size_t cap, size_t *len, fbrl_rapl_form form,
                                      fbrl_rapl_cmd cmd, const fbrl_rapl_arg *args, size_t nargs,
                                      int straight);

/* Check a name: 1-8 characters, a letter then letters, digits or '_' (either case); a
 * leading '#' (precision point) only when hash_ok. FBRL_ENAME otherwise. */
FBRL_API fbrl_status fbrl_rapl_name_check(const char *name, int hash_ok);

/* Write a real rounded to FBRL_RAPL_REAL_DECIMALS as the shortest text of that value:
 * [-]digits[.d..d] without trailing zeros ("2.5", "-90", "0.0001"; "-0" never appears).
 * FBRL_ENONFINITE, FBRL_ERANGE (|v| > FBRL_RAPL_REAL_MAX), FBRL_ENOSPC. */
FBRL_API fbrl_status fbrl_rapl_format_real(char *buf, size_t cap, size_t *len, double v);

#ifdef __cplusplus
}
#endif
#endif
