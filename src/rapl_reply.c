/* SPDX-License-Identifier: MIT */
/* rapl_reply.c - line assembly and parsers for the controller's output (no OS header). */
#include "fbrl/rapl_reply.h"

#include <string.h>

/* ---- reader ---- */

void fbrl_rapl_reader_init(fbrl_rapl_reader *r)
{
    if (!r)
        return;
    *r = (fbrl_rapl_reader){0};
    r->began = 1;
}

/* The framing of one byte (everything since init): the first two CR LF, every CR followed
 * by LF and every LF after a CR, the line ends, ">>" anywhere. */
static void frame(fbrl_rapl_reader *r, uint8_t b)
{
    if (r->bytes < 2 && b != (r->bytes == 0 ? '\r' : '\n'))
        r->began = 0;
    if ((r->last == '\r') != (b == '\n') && r->bytes > 0)
        r->broken = 1;
    if (b == '\r')
        r->ends |= FBRL_RAPL_END_CR;
    else if (b == '\n')
        r->ends |= r->last == '\r' ? FBRL_RAPL_END_CRLF : FBRL_RAPL_END_LF;
    r->eols += b == '\n';
    if (b == '>' && r->last == '>')
        r->gtgt = 1;
    r->last = b;
    r->bytes++;
}

void fbrl_rapl_reader_lost(fbrl_rapl_reader *r)
{
    if (!r)
        return;
    r->bytes++;
    r->broken = 1;
}

int fbrl_rapl_reader_whole(const fbrl_rapl_reader *r)
{
    return r && r->prompt && r->began && !r->broken && !r->damaged;
}

static fbrl_rapl_event end_line(fbrl_rapl_reader *r)
{
    if (r->len == 0) {
        r->flawed = 0; /* an empty line carries nothing, not even a flaw */
        return FBRL_RAPL_EV_NONE;
    }
    r->done = 1;
    r->lines++;
    r->damaged |= r->flawed;
    return FBRL_RAPL_EV_LINE;
}

fbrl_rapl_event fbrl_rapl_reader_feed(fbrl_rapl_reader *r, uint8_t byte)
{
    if (!r)
        return FBRL_RAPL_EV_NONE;
    frame(r, byte);
    if (r->done) {
        r->len = 0;
        r->line[0] = '\0';
        r->flawed = 0;
        r->done = 0;
    }
    if (byte == '\r' || byte == '\n') {
        int after_cr = r->cr;
        r->cr = byte == '\r';
        if (byte == '\n' && after_cr)
            return FBRL_RAPL_EV_NONE;
        return end_line(r);
    }
    r->cr = 0;
    if (byte < 0x20 || byte > 0x7e) {
        r->flawed = 1;
        return FBRL_RAPL_EV_NONE;
    }
    if (r->len >= FBRL_RAPL_REPLY_LINE_MAX) {
        r->flawed = 1;
        return FBRL_RAPL_EV_NONE;
    }
    r->line[r->len++] = (char)byte;
    r->line[r->len] = '\0';
    if (r->len == 2 && r->line[0] == '>' && r->line[1] == '>' && !r->flawed) {
        r->done = 1; /* the prompt is not a line: whatever follows starts a new one */
        r->prompt = 1;
        return FBRL_RAPL_EV_PROMPT;
    }
    return FBRL_RAPL_EV_NONE;
}

const char *fbrl_rapl_reader_line(const fbrl_rapl_reader *r, size_t *len, int *flawed)
{
    if (!r) {
        if (len)
            *len = 0;
        return "";
    }
    if (len)
        *len = r->len;
    if (flawed)
        *flawed = r->flawed;
    return r->line;
}

/* ---- errors ---- */

/* The controller's error texts by code: one list, from which the two tables below are made. */
#define RAPL_ERRORS(X)                                                                     \
    X(0, "AXIS #1 OUT OF RANGE")                                                           \
    X(1, "AXIS #2 OUT OF RANGE")                                                           \
    X(2, "AXIS #3 OUT OF RANGE")                                                           \
    X(3, "AXIS #4 OUT OF RANGE")                                                           \
    X(4, "AXIS #5 OUT OF RANGE")                                                           \
    X(5, "AXIS #6 OUT OF RANGE")                                                           \
    X(6, "AXIS #7 OUT OF RANGE")                                                           \
    X(7, "AXIS #8 OUT OF RANGE")                                                           \
    X(8, "ILLEGAL OPERAND")                                                                \
    X(9, "END OF LINE NOT FOUND")                                                          \
    X(10, "SYMBOL UNDEFINED")                                                              \
    X(11, "LOCATION UNDEFINED")                                                            \
    X(12, "COMMAND ERROR")                                                                 \
    X(13, "ARGUMENT MISSING")                                                              \
    X(14, "BAD SYNTAX")                                                                    \
    X(15, "PRECISION POINT NOT LEGAL")                                                     \
    X(16, "I/O ADDRESS ERROR")                                                             \
    X(17, "PROGRAM NOT FOUND")                                                             \
    X(18, "ILLEGAL ARGUMENT")                                                              \
    X(19, "LINE NOT FOUND")                                                                \
    X(20, "ARGUMENT TOO BIG")                                                              \
    X(21, "NO ROOM LEFT")                                                                  \
    X(22, "TABLE FULL")                                                                    \
    X(23, "BAD LINE NUMBER")                                                               \
    X(24, "ILLEGAL A/D CHANNEL")                                                           \
    X(25, "LINE TOO LONG")                                                                 \
    X(26, "END OF FILE NOT FOUND")                                                         \
    X(27, "PROGRAM EXISTS")                                                                \
    X(28, "LINE EXISTS")                                                                   \
    X(29, "TRANSFORM ILLEGAL")                                                             \
    X(32, "JOINT #1 HOME FAILED")                                                          \
    X(33, "JOINT #2 HOME FAILED")                                                          \
    X(34, "JOINT #3 HOME FAILED")                                                          \
    X(35, "JOINT #4 HOME FAILED")                                                          \
    X(36, "JOINT #5 HOME FAILED")                                                          \
    X(37, "JOINT #6 HOME FAILED")                                                          \
    X(38, "JOINT #7 HOME FAILED")                                                          \
    X(39, "JOINT #8 HOME FAILED")                                                          \
    X(40, "ARM POWER HAS BEEN SWITCHED OFF")                                               \
    X(41, "ROBOT HAS NOT BEEN HOMED")                                                      \
    X(42, "JOINT #1 OUT OF RANGE")                                                         \
    X(43, "JOINT #2 OUT OF RANGE")                                                         \
    X(44, "JOINT #3 OUT OF RANGE")                                                         \
    X(45, "JOINT #4 OUT OF RANGE")                                                         \
    X(46, "JOINT #5 OUT OF RANGE")                                                         \
    X(47, "CHECKSUM FAILURE")                                                              \
    X(49, "MEMORY NOT ALLOCATED")                                                          \
    X(50, "AMBIGUOUS COMMAND")                                                             \
    X(51, "SERIAL CHANNEL #0 TIMEOUT")                                                     \
    X(52, "SERIAL CHANNEL #0 CTS TIMEOUT")                                                 \
    X(53, "SERIAL CHANNEL #1 TIMEOUT")                                                     \
    X(54, "SERIAL CHANNEL #1 CTS TIMEOUT")                                                 \
    X(58, "CALIBRATION CHECKSUM ERROR")                                                    \
    X(60, "CANNOT USE PRIVILEGED COMMAND")                                                 \
    X(61, "ILLEGAL CHANNEL")                                                               \
    X(62, "REMOTE COMMUNICATION ERROR")                                                    \
    X(64, "NO RETURN LEVEL")                                                               \
    X(65, "BAD AXIS NUMBER")                                                               \
    X(66, "NOT AVAILABLE")                                                                 \
    X(67, "AXIS SLOT ALREADY USED")                                                        \
    X(68, "STRAIGHT LINE ERROR")                                                           \
    /* fbrlsim's own (docs/workcell.md): outside RAPL-II's table, which ends before 100 */ \
    X(190, "COLLISION")

/* The codes in the list's order (a byte each: -Woverflow refuses a larger one), and their
 * texts one after another, each ending in its NUL: a code's text is found by counting (an
 * error is rare), without a table of pointers as long as the highest code. */
#define ERROR_CODE(code, text) code,
#define ERROR_TEXT(code, text) text "\0"
static const uint8_t error_codes[] = {RAPL_ERRORS(ERROR_CODE)};
static const char error_texts[] = RAPL_ERRORS(ERROR_TEXT);

const char *fbrl_rapl_error_text(int code)
{
    const char *t = error_texts;
    for (size_t k = 0; k < sizeof error_codes; k++, t += strlen(t) + 1)
        if (error_codes[k] == code)
            return t;
    return 0;
}

/* Error numbers by what they mean for a corrective action (the texts above). */
#define ERR_TRANSFORM     29 /* TRANSFORM ILLEGAL */
#define ERR_JOINT1_RANGE  42 /* JOINT #1 OUT OF RANGE ... #5: 42 .. 46 */
#define ERR_JOINT5_RANGE  46
#define ERR_JOINT6_RANGE  48  /* the A465's sixth joint */
#define ERR_STRAIGHT_LINE 68  /* STRAIGHT LINE ERROR: the straight path leaves the reach */
#define ERR_COLLISION     190 /* COLLISION: an emulator with a work cell stopped the motion */

fbrl_rapl_errc fbrl_rapl_error_class(int code)
{
    if (code == ERR_TRANSFORM || code == ERR_STRAIGHT_LINE)
        return FBRL_RAPL_ERRC_REACH;
    if ((code >= ERR_JOINT1_RANGE && code <= ERR_JOINT5_RANGE) || code == ERR_JOINT6_RANGE)
        return FBRL_RAPL_ERRC_JOINT_LIMIT;
    if (code == ERR_COLLISION)
        return FBRL_RAPL_ERRC_COLLISION;
    return FBRL_RAPL_ERRC_OTHER;
}

/* What each error means for the user, in plain words, and what to do: the one table
 * every message uses (docs/rapl-commands.md shows it). Left out under FBRL_NO_HELP (a small
 * target's build option: no HELP texts), where every code has none; messages then give the
 * controller's text alone. */
#ifdef FBRL_NO_HELP
const char *fbrl_rapl_error_help(int code)
{
    (void)code;
    return 0;
}
#else
#define AXIS_RANGE  "that axis would pass its limit - choose a point or a motion that keeps it in range"
#define HOME_FAILED "homing that joint failed - check that nothing blocks it, then HOME again"
#define JOINT_RANGE                                                                                        \
    "the move would take that joint past its limit - choose a point the arm reaches another way (closer, " \
    "higher, another pitch)"
#define SERIAL_TIMEOUT "the controller's serial channel timed out - check the cable and the line settings"
static const char *const error_help[] = {
    [0] = AXIS_RANGE,
    [1] = AXIS_RANGE,
    [2] = AXIS_RANGE,
    [3] = AXIS_RANGE,
    [4] = AXIS_RANGE,
    [5] = AXIS_RANGE,
    [6] = AXIS_RANGE,
    [7] = AXIS_RANGE,
    [8] = "a value the command cannot take - check the numbers given to the word",
    [9] = "the command line ended too early - complete the command",
    [10] = "the controller has no variable of that name - set it first (SET-RAPL-INT, SET-RAPL-REAL)",
    [11] = "the controller has no location of that name - define it first (RAPL-POINT, RAPL-HERE)",
    [12] = "the controller does not know that command - check its spelling (docs/rapl-commands.md)",
    [13] = "the command needs more arguments - see HELP for the word",
    [14] = "the command's arguments are badly written - see HELP for the word",
    [15] = "a precision point (#name) cannot be used here - use a cartesian location",
    [16] = "no such input or output - use an I/O number 1..16",
    [17] = "the controller has no program of that name",
    [18] = "an argument is out of its allowed range - see HELP for the word",
    [19] = "the program has no line of that number",
    [20] = "a number is too large for the controller",
    [21] = "the controller's memory is full - delete locations or programs it no longer needs",
    [22] = "the controller's table of names is full - delete locations or variables it no longer needs",
    [23] = "that program line number cannot be used",
    [24] = "no such analog input - use a channel 1..8",
    [25] = "the command line is longer than the controller takes (80 characters)",
    [26] = "the end of the program was not found",
    [27] = "a program of that name exists already",
    [28] = "that program line exists already",
    [29] = "the position is out of the arm's reach, or not with that orientation: the arm did not move - "
           "choose a point closer to the base, or another pitch",
    [32] = HOME_FAILED,
    [33] = HOME_FAILED,
    [34] = HOME_FAILED,
    [35] = HOME_FAILED,
    [36] = HOME_FAILED,
    [37] = HOME_FAILED,
    [38] = HOME_FAILED,
    [39] = HOME_FAILED,
    [40] = "the arm's power is off - switch it on at the controller, then HOME",
    [41] = "the arm must find its zero first - HOME, then try again",
    [42] = JOINT_RANGE,
    [43] = JOINT_RANGE,
    [44] = JOINT_RANGE,
    [45] = JOINT_RANGE,
    [46] = JOINT_RANGE,
    [47] = "the controller's memory failed its check - its stored programs and locations may be lost",
    [49] = "the controller has no memory set aside for that",
    [50] = "the text is the beginning of several commands, so the controller ran none - write the command "
           "out in full",
    [51] = SERIAL_TIMEOUT,
    [52] = SERIAL_TIMEOUT,
    [53] = SERIAL_TIMEOUT,
    [54] = SERIAL_TIMEOUT,
    [58] = "the arm's calibration data failed its check - calibrate the controller again (XCAL)",
    [60] = "that command is not allowed from this line",
    [61] = "no such serial channel - use 0 or 1",
    [62] = "the controller's remote line failed",
    [64] = "RETURN without a subroutine call",
    [65] = "no such axis",
    [66] = "this controller does not have that",
    [67] = "that axis slot is taken already",
    [68] = "the straight line passes outside the arm's reach - move in steps, or joint-interpolated (without "
           "-STRT)",
    [190] = "the arm met the work cell and stopped there (fbrlsim --cell)",
};

const char *fbrl_rapl_error_help(int code)
{
    if (code < 0 || (size_t)code >= sizeof error_help / sizeof error_help[0])
        return 0;
    return error_help[code];
}
#endif

static int is_digit(char c) { return c >= '0' && c <= '9'; }
static int is_upper(char c) { return c >= 'A' && c <= 'Z'; }

fbrl_status fbrl_rapl_parse_error(const char *line, size_t len, int *code, char *text, size_t cap)
{
    if (!line || !code || (text && cap == 0))
        return FBRL_EINVAL;
    if (len < 6 || !is_digit(line[0]) || !is_digit(line[1]) || !is_digit(line[2]) || line[3] != '-' ||
        line[len - 1] != '.' || !is_upper(line[4]))
        return FBRL_ESYNTAX;
    for (size_t i = 4; i + 1 < len; i++) {
        char c = line[i];
        if (!(is_upper(c) || is_digit(c) || c == ' ' || c == '#' || c == '/' || c == '-'))
            return FBRL_ESYNTAX;
    }
    *code = (line[0] - '0') * 100 + (line[1] - '0') * 10 + (line[2] - '0');
    size_t tlen = len - 5;
    if (text) {
        if (tlen + 1 > cap)
            return FBRL_ENOSPC;
        for (size_t i = 0; i < tlen; i++)
            text[i] = line[4 + i];
        text[tlen] = '\0';
    }
    const char *known = fbrl_rapl_error_text(*code);
    if (!known)
        return FBRL_ECHECKSUM;
    size_t i = 0;
    for (; i < tlen && known[i] && known[i] == line[4 + i]; i++) {
    }
    return (i == tlen && !known[i]) ? FBRL_OK : FBRL_ECHECKSUM;
}

/* ---- numbers ---- */

/* One number at s[*i]: [+-]digits[.digits]. Shape reported so callers can insist on the
 * controller's exact layout. No exponent: the controller never prints one. */
typedef struct num {
    int sign; /* '+', '-' or 0 when absent */
    unsigned idig, fdig;
    int dot;
    double v;
    long iv; /* the value when it has no fraction and fits */
} num;

#define NUM_MAX_DIGITS 15 /* exact in a double */

static int scan_num(const char *s, size_t len, size_t *i, num *n)
{
    size_t k = *i;
    unsigned long long m = 0;
    double scale = 1.0;
    n->sign = 0;
    n->idig = n->fdig = 0;
    n->dot = 0;
    if (k < len && (s[k] == '+' || s[k] == '-'))
        n->sign = s[k++];
    while (k < len && is_digit(s[k])) {
        if (n->idig >= NUM_MAX_DIGITS)
            return 0;
        m = m * 10u + (unsigned)(s[k++] - '0');
        n->idig++;
    }
    if (k < len && s[k] == '.') {
        n->dot = 1;
        k++;
        while (k < len && is_digit(s[k])) {
            if (n->idig + n->fdig >= NUM_MAX_DIGITS)
                return 0;
            m = m * 10u + (unsigned)(s[k++] - '0');
            scale *= 10.0;
            n->fdig++;
        }
        if (n->fdig == 0)
            return 0;
    }
    if (n->idig == 0)
        return 0;
    n->v = (double)m / scale;
    n->iv = (long)(m & 0x7fffffffu);
    if (!n->dot && m > 0x7fffffffu)
        n->iv = -1; /* callers check idig; the value is too large for a long on 32 bits */
    if (n->sign == '-') {
        n->v = -n->v;
        n->iv = -n->iv;
    }
    *i = k;
    return 1;
}

static void skip_spaces(const char *s, size_t len, size_t *i)
{
    while (*i < len && s[*i] == ' ')
        (*i)++;
}

static fbrl_status whole_number(const char *line, size_t len, num *n)
{
    size_t i = 0;
    if (!line)
        return FBRL_EINVAL;
    skip_spaces(line, len, &i);
    if (!scan_num(line, len, &i, n))
        return FBRL_ESYNTAX;
    skip_spaces(line, len, &i);
    return i == len ? FBRL_OK : FBRL_ESYNTAX;
}

fbrl_status fbrl_rapl_parse_real(const char *line, size_t len, double *v)
{
    num n;
    if (!v)
        return FBRL_EINVAL;
    fbrl_status st = whole_number(line, len, &n);
    if (st == FBRL_OK)
        *v = n.v;
    return st;
}

fbrl_status fbrl_rapl_parse_int(const char *line, size_t len, long *v)
{
    num n;
    if (!v)
        return FBRL_EINVAL;
    fbrl_status st = whole_number(line, len, &n);
    if (st != FBRL_OK)
        return st;
    if (n.dot)
        return FBRL_ESYNTAX;
    if (n.v > 2147483647.0 || n.v < -2147483647.0)
        return FBRL_ERANGE;
    *v = n.iv;
    return FBRL_OK;
}

/* Integers in the "%+011ld" layout: sign and ten digits. */
static int pulse_num(const num *n)
{
    return n->sign && !n->dot && n->idig == 10 && n->v <= 2147483647.0 && n->v >= -2147483647.0;
}

/* Reals in the "%+09.4f" layout: sign, at least three digits, four decimals. */
static int fixed_num(const num *n) { return n->sign && n->dot && n->idig >= 3 && n->fdig == 4; }

fbrl_status fbrl_rapl_parse_ints(const char *line, size_t len, long *vals, size_t max, size_t *n)
{
    if (!line || !n || (max && !vals))
        return FBRL_EINVAL;
    size_t i = 0, k = 0;
    *n = 0;
    skip_spaces(line, len, &i);
    while (i < len) {
        num x;
        if (k >= max || !scan_num(line, len, &i, &x) || !pulse_num(&x))
            return FBRL_ESYNTAX;
        if (i < len && line[i] != ' ')
            return FBRL_ESYNTAX;
        vals[k++] = x.iv;
        skip_spaces(line, len, &i);
    }
    if (k == 0)
        return FBRL_ESYNTAX;
    *n = k;
    return FBRL_OK;
}

/* ---- position blocks ---- */

void fbrl_rapl_pos_init(fbrl_rapl_pos *p)
{
    if (!p)
        return;
    p->kind = 0;
    p->npulses = p->njoints = p->nworld = 0;
    p->part = 0;
}

/* Does line start with word (and then a space or the end)? */
static int starts(const char *line, size_t len, const char *word, size_t *after)
{
    size_t k = 0;
    while (word[k]) {
        if (k >= len || line[k] != word[k])
            return 0;
        k++;
    }
    if (k < len && line[k] != ' ')
        return 0;
    *after = k;
    return 1;
}

static int equals(const char *line, size_t len, const char *text)
{
    size_t k = 0;
    while (text[k] && k < len && line[k] == text[k])
        k++;
    return !text[k] && k == len;
}

/* Read numbers from line[i..] into the section's array, checking the layout. */
static fbrl_status pos_values(fbrl_rapl_pos *p, char part, const char *line, size_t len, size_t i)
{
    int any = 0;
    skip_spaces(line, len, &i);
    while (i < len) {
        num x;
        if (!scan_num(line, len, &i, &x) || (i < len && line[i] != ' '))
            return FBRL_ESYNTAX;
        if (part == 'P') {
            if (!pulse_num(&x) || p->npulses >= FBRL_RAPL_MAX_AXES)
                return FBRL_ESYNTAX;
            p->pulses[p->npulses++] = x.iv;
        } else if (part == 'J') {
            if (!fixed_num(&x) || p->njoints >= FBRL_RAPL_MAX_AXES)
                return FBRL_ESYNTAX;
            p->joints[p->njoints++] = x.v;
        } else {
            if (!fixed_num(&x) || p->nworld >= 6)
                return FBRL_ESYNTAX;
            p->world[p->nworld++] = x.v;
        }
        any = 1;
        skip_spaces(line, len, &i);
    }
    if (!any)
        return FBRL_ESYNTAX;
    p->part = (unsigned char)part;
    return FBRL_OK;
}

fbrl_status fbrl_rapl_pos_line(fbrl_rapl_pos *p, const char *line, size_t len)
{
    size_t i;
    if (!p || !line)
        return FBRL_EINVAL;
    if (equals(line, len, "CURRENT ACTUAL POSITION :")) {
        fbrl_rapl_pos_init(p);
        p->kind = 'A';
        return FBRL_OK;
    }
    if (equals(line, len, "CURRENT COMMAND POSITION :")) {
        fbrl_rapl_pos_init(p);
        p->kind = 'C';
        return FBRL_OK;
    }
    if (equals(line, len, "END OF PATH POSITION :")) {
        fbrl_rapl_pos_init(p);
        p->kind = 'E';
        return FBRL_OK;
    }
    if (!p->kind)
        return FBRL_ESYNTAX;
    if (starts(line, len, "NAME", &i)) {
        p->part = 0;
        return FBRL_OK;
    }
    if (starts(line, len, "PULSES", &i))
        return p->npulses ? FBRL_ESYNTAX : pos_values(p, 'P', line, len, i);
    if (starts(line, len, "JOINTS", &i))
        return p->njoints ? FBRL_ESYNTAX : pos_values(p, 'J', line, len, i);
    if (starts(line, len, "WORLD", &i))
        return p->nworld ? FBRL_ESYNTAX : pos_values(p, 'W', line, len, i);
    if (len > 0 && line[0] == ' ' && (p->part == 'P' || p->part == 'J'))
        return pos_values(p, (char)p->part, line, len, 0); /* axes 6.. wrap onto a new line */
    return FBRL_ESYNTAX;
}

int fbrl_rapl_pos_complete(const fbrl_rapl_pos *p, unsigned naxes)
{
    return p && p->kind && naxes <= FBRL_RAPL_MAX_AXES && p->npulses == naxes && p->njoints == naxes &&
           p->nworld == 6;
}

/* ---- STATUS ---- */

void fbrl_rapl_status_init(fbrl_rapl_status_info *s)
{
    if (!s)
        return;
    s->last_error = -1;
    s->speed = 0.0;
    s->homed = 0;
    s->naxes = 0;
    s->inputs = s->outputs = 0;
    s->metric = 0;
    s->have = 0;
}

/* "LOCK         N N N N N" -> flags; every row must have the same number of axes. */
static fbrl_status yn_row(fbrl_rapl_status_info *s, char *flags, unsigned bit, const char *line, size_t len,
                          size_t i)
{
    unsigned n = 0;
    skip_spaces(line, len, &i);
    while (i < len) {
        if ((line[i] != 'Y' && line[i] != 'N') || n >= FBRL_RAPL_MAX_AXES)
            return FBRL_ESYNTAX;
        flags[n++] = line[i] == 'Y';
        i++;
        if (i < len && line[i] != ' ')
            return FBRL_ESYNTAX;
        skip_spaces(line, len, &i);
    }
    if (n == 0 || (s->naxes && n != s->naxes))
        return FBRL_ESYNTAX;
    s->naxes = n;
    s->have |= bit;
    return FBRL_OK;
}

/* "INPUTS  1-16: 0101..." -> bit mask, 16 digits exactly. */
static fbrl_status io_row(uint32_t *mask, const char *line, size_t len, size_t i)
{
    uint32_t m = 0;
    skip_spaces(line, len, &i);
    if (len - i != 16)
        return FBRL_ESYNTAX;
    for (unsigned k = 0; k < 16; k++) {
        char c = line[i + k];
        if (c != '0' && c != '1')
            return FBRL_ESYNTAX;
        if (c == '1')
            m |= 1u << k;
    }
    *mask = m;
    return FBRL_OK;
}

fbrl_status fbrl_rapl_status_line(fbrl_rapl_status_info *s, const char *line, size_t len)
{
    size_t i;
    if (!s || !line)
        return FBRL_EINVAL;
    if (starts(line, len, "LAST ERROR CODE:", &i)) {
        skip_spaces(line, len, &i);
        if (equals(line + i, len - i, "NONE")) {
            s->last_error = -1;
        } else {
            int code;
            if (fbrl_rapl_parse_error(line + i, len - i, &code, 0, 0) != FBRL_OK)
                return FBRL_ESYNTAX;
            s->last_error = code;
        }
        s->have |= FBRL_RAPL_ST_ERROR;
        return FBRL_OK;
    }
    if (starts(line, len, "SPEED (% OF FULL) :", &i)) {
        num x;
        skip_spaces(line, len, &i);
        if (!scan_num(line, len, &i, &x) || !x.sign || i != len)
            return FBRL_ESYNTAX;
        s->speed = x.v;
        s->have |= FBRL_RAPL_ST_SPEED;
        return FBRL_OK;
    }
    if (equals(line, len, "CONTROLLER IS HOMED") || equals(line, len, "CONTROLLER IS NOT HOMED")) {
        s->homed = len == 19;
        s->have |= FBRL_RAPL_ST_HOMED;
        return FBRL_OK;
    }
    if (starts(line, len, "LOCK", &i))
        return yn_row(s, s->lock, FBRL_RAPL_ST_LOCK, line, len, i);
    if (starts(line, len, "DONE", &i))
        return yn_row(s, s->done, FBRL_RAPL_ST_DONE, line, len, i);
    if (starts(line, len, "LIMP", &i))
        return yn_row(s, s->limp, FBRL_RAPL_ST_LIMP, line, len, i);
    if (starts(line, len, "HOMED", &i))
        return yn_row(s, s->axis_homed, FBRL_RAPL_ST_AXHOMED, line, len, i);
    if (starts(line, len, "INPUTS  1-16:", &i)) {
        fbrl_status st = io_row(&s->inputs, line, len, i);
        if (st == FBRL_OK)
            s->have |= FBRL_RAPL_ST_INPUTS;
        return st;
    }
    if (equals(line, len, "METRIC UNITS.") || equals(line, len, "INCH UNITS.")) {
        s->metric = line[0] == 'M'; /* the units the controller's lengths are in */
        s->have |= FBRL_RAPL_ST_UNITS;
        return FBRL_OK;
    }
    if (starts(line, len, "OUTPUTS 1-16:", &i)) {
        fbrl_status st = io_row(&s->outputs, line, len, i);
        if (st == FBRL_OK)
            s->have |= FBRL_RAPL_ST_OUTPUTS;
        return st;
    }
    return FBRL_ENOENT;
}
