/* SPDX-License-Identifier: MIT */
/* rapl_reply.h - understanding what the RAPL controller prints (docs/rapl-commands.md 1, 4, 5).
 *
 * Two layers, both bounded and safe on any input (they never read past the given length):
 *  - fbrl_rapl_reader: fed received bytes one at a time, it cuts them into lines (CR, LF
 *    and CRLF end a line), recognises the prompt ">>" at the start of a line, and keeps the
 *    framing of everything fed since it was initialised (a reply, read from its CR on): did
 *    it begin with CR LF, did every CR have its LF, was a byte lost or a line damaged.
 *  - line parsers: an error line "NNN-TEXT.", position blocks (W0 W2 W4), STATUS blocks,
 *    TYPEI/TYPEV values and the lines of the continuous readouts (W1 W3 W5 WE*).
 * Numbers are parsed without the C library (no locale), with the exact layouts the
 * controller prints, so a corrupted byte rarely passes as a number. No OS header. */
#ifndef FBRL_RAPL_REPLY_H
#define FBRL_RAPL_REPLY_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Longest line kept; longer lines are cut and flagged (the STATUS lines are < 60). */
#define FBRL_RAPL_REPLY_LINE_MAX 128

typedef enum fbrl_rapl_event {
    FBRL_RAPL_EV_NONE = 0, /* byte taken, nothing complete yet */
    FBRL_RAPL_EV_LINE,     /* a non-empty line is complete: fbrl_rapl_reader_line() */
    FBRL_RAPL_EV_PROMPT    /* ">>" at the start of a line: the controller waits for input */
} fbrl_rapl_event;

/* Line ends seen (fbrl_rapl_reader.ends). */
#define FBRL_RAPL_END_CR   0x1u /* a CR */
#define FBRL_RAPL_END_CRLF 0x2u /* an LF right after a CR */
#define FBRL_RAPL_END_LF   0x4u /* an LF without a CR before it */

typedef struct fbrl_rapl_reader {
    char line[FBRL_RAPL_REPLY_LINE_MAX + 1]; /* NUL-terminated */
    size_t len;
    unsigned char cr;     /* last byte was CR (a following LF is part of the same end) */
    unsigned char flawed; /* the line held a control byte or was cut: do not trust it */
    unsigned char done;   /* the previous call completed a line: start a new one */
    /* the framing of everything fed since init (read only) */
    size_t bytes;          /* bytes fed, and bytes lost (fbrl_rapl_reader_lost) */
    unsigned eols;         /* LFs */
    unsigned lines;        /* lines completed (FBRL_RAPL_EV_LINE) */
    unsigned char last;    /* the byte fed before */
    unsigned char began;   /* the bytes began with CR LF (so far) */
    unsigned char broken;  /* a CR without its LF, an LF without its CR, or a byte lost */
    unsigned char damaged; /* a completed line was flawed */
    unsigned char ends;    /* FBRL_RAPL_END_* seen */
    unsigned char gtgt;    /* ">>" anywhere */
    unsigned char prompt;  /* the prompt came (FBRL_RAPL_EV_PROMPT) */
} fbrl_rapl_reader;

FBRL_API void fbrl_rapl_reader_init(fbrl_rapl_reader *r);

/* A byte was lost here (a parity error the UART dropped): it counts as a byte and
 * breaks the framing. */
FBRL_API void fbrl_rapl_reader_lost(fbrl_rapl_reader *r);

/* Everything fed since init is a whole reply: it began with CR LF, every CR had its LF
 * and every LF its CR, no byte was lost, no line was damaged, and the prompt ended it. */
FBRL_API int fbrl_rapl_reader_whole(const fbrl_rapl_reader *r);

/* Take one byte. Printable bytes (0x20-0x7E) are collected; other bytes except CR and
 * LF are dropped and mark the line flawed. */
FBRL_API fbrl_rapl_event fbrl_rapl_reader_feed(fbrl_rapl_reader *r, uint8_t byte);

/* The line completed by the last EV_LINE (valid until the next feed). *flawed (may be
 * NULL) tells whether a control byte was dropped from it or it was cut. */
FBRL_API const char *fbrl_rapl_reader_line(const fbrl_rapl_reader *r, size_t *len, int *flawed);

/* ---- error lines ---- */

/* What kind of trouble an error code is, for corrective actions (recover.h). */
typedef enum fbrl_rapl_errc {
    FBRL_RAPL_ERRC_OTHER = 0,
    FBRL_RAPL_ERRC_REACH,       /* no arm configuration reaches the place, or the straight path */
    FBRL_RAPL_ERRC_JOINT_LIMIT, /* a joint would pass its range */
    FBRL_RAPL_ERRC_COLLISION    /* the motion hit something (an emulator with a work cell) */
} fbrl_rapl_errc;
FBRL_API fbrl_rapl_errc fbrl_rapl_error_class(int code);

/* The controller's text for an error code ("TRANSFORM ILLEGAL"), or NULL if unknown. */
FBRL_API const char *fbrl_rapl_error_text(int code);
/* What the error means for the user, in plain words, and what to do ("the position is
 * out of the arm's reach ... - choose a point closer ..."), or NULL if unknown. Every
 * code with a text has one, but for a library built with FBRL_NO_HELP (NULL always). */
FBRL_API const char *fbrl_rapl_error_help(int code);

/* Parse "NNN-TEXT." (exactly three digits, '-', upper-case text, final '.').
 * FBRL_OK: *code and text (NUL-terminated, without the '.'; may be NULL) are set and the
 * text is the one the controller uses for that code. FBRL_ECHECKSUM: the line has the
 * shape of an error line but code and text disagree (a byte was corrupted; *code and
 * text are still set). FBRL_ESYNTAX: not an error line. FBRL_ENOSPC: text too small. */
FBRL_API fbrl_status fbrl_rapl_parse_error(const char *line, size_t len, int *code, char *text, size_t cap);

/* ---- numbers ---- */

/* The whole line (leading/trailing spaces allowed) is one number: [+-]digits[.digits].
 * TYPEI prints "%ld", TYPEV "%+.6f". FBRL_ESYNTAX otherwise, FBRL_ERANGE if too large. */
FBRL_API fbrl_status fbrl_rapl_parse_real(const char *line, size_t len, double *v);
FBRL_API fbrl_status fbrl_rapl_parse_int(const char *line, size_t len, long *v);

/* A line of up to max integers separated by spaces (W1 W3 W5 WE* stream lines,
 * "%+011ld"). *n = how many. FBRL_ESYNTAX if anything else is on the line. */
FBRL_API fbrl_status fbrl_rapl_parse_ints(const char *line, size_t len, long *vals, size_t max, size_t *n);

/* ---- position blocks: W0 W2 W4 ---- */

#define FBRL_RAPL_MAX_AXES 8

typedef struct fbrl_rapl_pos {
    char kind; /* 'A' actual (W2), 'C' command (W0), 'E' end of path (W4) */
    long pulses[FBRL_RAPL_MAX_AXES];
    double joints[FBRL_RAPL_MAX_AXES]; /* degrees */
    double world[6];                   /* x y z (in), yaw pitch roll (deg) */
    unsigned char npulses, njoints, nworld;
    unsigned char part; /* the section the last line belonged to */
} fbrl_rapl_pos;

FBRL_API void fbrl_rapl_pos_init(fbrl_rapl_pos *p);

/* Feed one output line of a position block. FBRL_OK if it belongs to the block (title,
 * NAME headers, PULSES, JOINTS, WORLD and their continuation lines), FBRL_ESYNTAX if the
 * line does not fit the layout (the block is then not to be trusted). */
FBRL_API fbrl_status fbrl_rapl_pos_line(fbrl_rapl_pos *p, const char *line, size_t len);

/* Non-zero when title, naxes pulses, naxes joints and 6 world values were seen. */
FBRL_API int fbrl_rapl_pos_complete(const fbrl_rapl_pos *p, unsigned naxes);

/* ---- STATUS block ---- */

typedef struct fbrl_rapl_status_info {
    int last_error; /* -1 = NONE, else the code */
    double speed;   /* percent */
    int homed;      /* CONTROLLER IS HOMED */
    unsigned naxes;
    char lock[FBRL_RAPL_MAX_AXES], done[FBRL_RAPL_MAX_AXES];
    char limp[FBRL_RAPL_MAX_AXES], axis_homed[FBRL_RAPL_MAX_AXES]; /* 1 = Y */
    uint32_t inputs, outputs;                                      /* bit n-1 = input/output n */
    unsigned have;                                                 /* FBRL_RAPL_ST_* bits of the lines seen */
    int metric; /* the last line: 1 "METRIC UNITS." (lengths in mm), 0 "INCH UNITS." */
} fbrl_rapl_status_info;

#define FBRL_RAPL_ST_ERROR   0x01u
#define FBRL_RAPL_ST_SPEED   0x02u
#define FBRL_RAPL_ST_HOMED   0x04u
#define FBRL_RAPL_ST_LOCK    0x08u
#define FBRL_RAPL_ST_DONE    0x10u
#define FBRL_RAPL_ST_LIMP    0x20u
#define FBRL_RAPL_ST_AXHOMED 0x40u
#define FBRL_RAPL_ST_INPUTS  0x80u
#define FBRL_RAPL_ST_OUTPUTS 0x100u
#define FBRL_RAPL_ST_UNITS   0x200u

FBRL_API void fbrl_rapl_status_init(fbrl_rapl_status_info *s);

/* Feed one STATUS line. FBRL_OK when understood (or a known line without data),
 * FBRL_ESYNTAX when a line with a known label has a malformed value, FBRL_ENOENT when
 * the label is not one this parser reads (such lines are simply skipped). */
FBRL_API fbrl_status fbrl_rapl_status_line(fbrl_rapl_status_info *s, const char *line, size_t len);

#ifdef __cplusplus
}
#endif
#endif
