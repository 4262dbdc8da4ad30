/* SPDX-License-Identifier: MIT */
/* link.h - a robot session: RAPL commands over an fbrl_uart with echo verification.
 *
 * The link types a command, checks the controller's echo of every character, and sends
 * the CR only when the whole line came back exactly; then it waits for the prompt and
 * reads the reply (errors, positions, STATUS, values). When anything is unclear it asks
 * the controller (probes that can never execute a line) instead of guessing, so a
 * command is never executed twice or altered by the host. docs/link.md describes the
 * protocol; docs/rapl-commands.md the controller's side.
 *
 * Every wait goes through fbrl_uart_read()'s timeout: the link never blocks otherwise.
 * fbrl_link_start() + fbrl_link_poll() run one command step by step, so one thread can
 * drive several links (several robots), see fbrl_link_poll_many(); the blocking calls
 * (fbrl_link_cmd(), fbrl_link_where(), ...) are start + poll until done.
 * No OS header: time comes from the uart backend's now_us or the config's clock. */
#ifndef FBRL_LINK_H
#define FBRL_LINK_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/arm.h"
#include "fbrl/uart.h"
#include "fbrl/rapl_encode.h"
#include "fbrl/rapl_reply.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The controller's line limit (longer lines fail with 025). */
#define FBRL_LINK_LINE_MAX 80

/* What a command prints and how the link reads it: the encoder's table says it for
 * every command (fbrl_rapl_cmdinfo.reply), so the type is the encoder's. */
typedef fbrl_rapl_reply fbrl_link_reply;
#define FBRL_LINK_REPLY_NONE   FBRL_RAPL_REPLY_NONE
#define FBRL_LINK_REPLY_POS    FBRL_RAPL_REPLY_POS
#define FBRL_LINK_REPLY_STATUS FBRL_RAPL_REPLY_STATUS
#define FBRL_LINK_REPLY_INT    FBRL_RAPL_REPLY_INT
#define FBRL_LINK_REPLY_REAL   FBRL_RAPL_REPLY_REAL
#define FBRL_LINK_REPLY_LINES  FBRL_RAPL_REPLY_LINES
#define FBRL_LINK_REPLY_STREAM FBRL_RAPL_REPLY_STREAM

/* What happened to a command (docs/link.md 3.9). Every result falls in exactly one:
 *  RAN          it ran and succeeded                          (FBRL_OK)
 *  REFUSED      it ran and the controller refused it: the code from fbrl_link_error(),
 *               -1 "code unknown" when the error line was damaged and STATUS could not
 *               be read                                         (FBRL_ECONTROLLER)
 *  NOT_RUN      proven not to have run: typing failed before any CR took effect, or the
 *               call was refused before anything was sent      (any other status)
 *  MAY_HAVE_RUN the link cannot prove either way (or it ran and its end is unknown): do
 *               not repeat it blindly; fbrl_link_outcome() says what the controller was
 *               last seen doing                                 (FBRL_EMAYBE)
 * The class follows from the status alone (fbrl_link_fate_of()). */
typedef enum fbrl_link_fate {
    FBRL_LINK_FATE_NONE = 0, /* no command has ended yet */
    FBRL_LINK_RAN = 1,
    FBRL_LINK_REFUSED = 2,
    FBRL_LINK_NOT_RUN = 3,
    FBRL_LINK_MAY_HAVE_RUN = 4
} fbrl_link_fate;

/* The modes a session set (docs/link.md 1, "Modes"): settings the controller keeps until
 * they change and loses when it restarts. The link notes every one that ran (FBRL_OK) into
 * cfg.modes, so that after a reconnect fbrl_link_modes_resend() sends them again before
 * the first motion: the units (METRIC, NOMETRIC), the tool (TOOL, with the POINT that last
 * defined its location), the speed (SPEED), the pendant lamp (FLASH, NOFLASH) and the
 * motors' gains (GAIN n,value). Not modes: LIMP (the arm's servos: a restarted controller
 * must be homed, which needs them), LOCK (READY clears it), MANUAL and TEACH (the
 * pendant's, an operator's), ARM, ENABLE, DISABLE (arm power: an operator's decision after
 * a restart), CONFIG (the serial line itself) and the outputs (they switch devices).
 * Caller-owned; every field is private. */
#define FBRL_LINK_MODES_MAX 14
typedef struct fbrl_link_modes {
    char line[FBRL_LINK_MODES_MAX][FBRL_LINK_LINE_MAX + 1]; /* by slot, "" = not set */
    char point[FBRL_LINK_LINE_MAX + 1];                     /* the last POINT that ran */
    int point_units, tool_units;                            /* the units their lengths were typed in */
} fbrl_link_modes;

/* Empty: no mode set yet. */
FBRL_API void fbrl_link_modes_init(fbrl_link_modes *m);
/* Mode line i (0, 1, ...) in the order fbrl_link_modes_resend() sends them; NULL past the
 * last. */
FBRL_API const char *fbrl_link_modes_line(const fbrl_link_modes *m, size_t i);

typedef struct fbrl_link_config {
    fbrl_rapl_form form;       /* keyword (default) or /NNN token form */
    int lower_case;            /* send letters in lower case (default 1; see docs/link.md) */
    uint32_t echo_timeout_ms;  /* silence after which an awaited byte counts as lost (100) */
    uint32_t reply_timeout_ms; /* prompt after CR for ordinary commands (5000) */
    uint32_t wait_timeout_ms;  /* prompt after CR for commands that may wait: motion, FINISH,
                                * WAIT, RUN and unknown raw lines (120000) */
    unsigned max_attempts;     /* typing attempts / query repeats per command (12); then
                                * FBRL_EECHO, or FBRL_ETIMEOUT if the controller sent nothing */
    unsigned query_reads;      /* identical consecutive replies a read-only query needs
                                * (1..3, default 2; see docs/link.md for the odds) */
    unsigned naxes;            /* axes in W0/W2/W4 and STATUS rows (5) */
    /* The arm a position block is checked against (fbrl/arm.h; NULL = the A255): its pulses
     * per degree and kinematics. A block whose pulses, joints and world agree is believed at
     * once, even while the arm moves; one that does not (another arm, a tool with an offset
     * across its axis) needs query_reads agreeing replies, as other queries do. */
    const fbrl_arm *arm;
    /* Clock; NULL = the uart backend's now_us. */
    uint64_t (*now_us)(void *ctx);
    void *clock_ctx;
    /* The run log: called once for every line the link knows the controller executed
     * (the user's commands and the link's own STATUS queries), with its result (FBRL_OK,
     * FBRL_ECONTROLLER, or FBRL_EPROTOCOL for a query whose reply was damaged and is
     * asked again), in the controller's order; and once for a command that may have run
     * (FBRL_EMAYBE: it may or may not be in the controller's log). Lines that did not
     * run are never reported. May be NULL. */
    void (*on_exec)(void *ctx, const char *line, size_t len, fbrl_status result);
    void *exec_ctx;
    /* Lines of FBRL_LINK_REPLY_LINES and STREAM replies (flawed = a byte was damaged).
     * fbrl_link_set_line_handler() changes it later. */
    void (*on_line)(void *ctx, const char *line, size_t len, int flawed);
    void *line_ctx;
    /* The controller may power up in ACI mode (default 0): fbrl_link_connect() first
     * sends the ACI switch to terminal mode (research notes 2.5; docs/link.md). A
     * controller already in terminal mode takes the switch's first bytes as typed
     * text; the link erases them again. */
    int aci;
    /* fbrl_link_connect() reads the controller's units (STATUS) and refuses millimetres
     * with FBRL_EUNITS (default 1; docs/link.md 1). 0 leaves them unknown until a STATUS
     * runs (a program that sends no lengths, a benchmark). */
    int check_units;
    /* Where the link notes the modes that ran (NULL = nowhere, the default). The storage
     * is the session's, not the connection's: a link initialised again after a reconnect
     * with the same cfg keeps noting into it, and fbrl_link_modes_resend() sends it. */
    fbrl_link_modes *modes;
} fbrl_link_config;

FBRL_API void fbrl_link_config_init(fbrl_link_config *c);

typedef struct fbrl_link_stats {
    uint64_t commands;       /* commands started */
    uint64_t executed;       /* lines the controller executed (incl. the link's queries) */
    uint64_t attempts;       /* lines typed (first tries and retypes) */
    uint64_t echo_mismatch;  /* an echoed byte differed */
    uint64_t echo_timeout;   /* an echoed byte never came */
    uint64_t probes;         /* erase/verify/idle probes sent */
    uint64_t cr_unconfirmed; /* CR sent but the line was found unexecuted: retyped */
    uint64_t prompt_lost;    /* executed, prompt damaged: confirmed by a probe */
    uint64_t requeries;      /* read-only queries repeated: damaged reply or confirmation */
    uint64_t error_queries;  /* STATUS read to learn a damaged error line's code */
    uint64_t failed;         /* commands that ended with an error other than ECONTROLLER */
    uint64_t parity_errors;  /* bytes the uart dropped with a parity error (line with E/O
                               * parity): in an echo a retype, in a reply a damaged reply */
    uint64_t settled;        /* damaged replies of commands settled by reading STATUS */
    uint64_t not_retyped;    /* commands not safe to repeat whose CR could not be proven
                               * ineffective: reported "may have run" instead of retyped */
    uint64_t may_have_run;   /* commands that ended FBRL_EMAYBE */
    uint64_t self_checked;   /* position blocks believed on their own consistency */
    uint64_t cleans;         /* probe markers erased by the command that left them (after
                               * a wait), so the next command starts on an empty line */
    uint64_t early_prompts;  /* commands finished on the first '>' of their prompt; the
                               * second is checked in front of the next echo (docs/link.md 3.10) */
} fbrl_link_stats;

/* The last command's outcome, for messages. */
typedef struct fbrl_link_outcome {
    fbrl_link_fate fate;
    fbrl_status status;  /* the command's result */
    fbrl_status cause;   /* why it did not end normally (FBRL_ETIMEOUT, FBRL_EDISCONNECTED,
                          * FBRL_EPROTOCOL ...); FBRL_OK when it did */
    int code;            /* REFUSED: the controller's code, -1 unknown */
    const char *seen;    /* what the controller was last seen doing, in plain words
                          * ("it had started the line; its reply was cut off"); never NULL */
    unsigned runs;       /* times the line ran on the controller, proven: 1, or more when the
                          * link typed it again (a safe command whose reply came damaged and
                          * whose STATUS could not tell; a query read until replies agree) */
    unsigned maybe_runs; /* further times it may have run: a CR whose effect the link could
                          * not prove either way (docs/link.md 3.9) */
} fbrl_link_outcome;

/* The link's probe (private, link_probe.c): its markers, the last bytes of its echo and
 * the parse of that echo. */
typedef struct fbrl_link_probe {
    char marker[3];
    unsigned next;
    unsigned char tail[7];
    int state;
    unsigned erased, sub;
} fbrl_link_probe;

/* The settling of a damaged reply (private, link_settle.c): the command while STATUS is
 * read for it, and those reads (ran, damaged, may have run). */
typedef struct fbrl_link_settle {
    char line[FBRL_LINK_LINE_MAX + 1];
    size_t len;
    fbrl_link_reply kind;
    unsigned attempts;
    int shaped;
    unsigned ok, bad, maybe;
} fbrl_link_settle;

/* A session. Caller-owned; every field is private. */
typedef struct fbrl_link {
    fbrl_uart *u;
    fbrl_link_config cfg;
    int xon_ok;           /* flow NONE: probes may carry an XON byte */
    uint64_t parity_seen; /* the uart's parity error count, last looked at */
    int parity;           /* the line has parity: damaged bytes are dropped */
    fbrl_link_probe probe;
    /* the command */
    char line[FBRL_LINK_LINE_MAX + 1]; /* canonical (upper-case) text */
    size_t len;
    fbrl_link_reply kind;
    uint32_t timeout_ms;
    int stage;             /* main command or error query */
    unsigned stream_lines; /* STREAM: value lines wanted */
    /* progress */
    int phase;
    int ctrl_len; /* characters on the controller's line, -1 unknown */
    size_t match, expect, triples;
    int owed; /* the last prompt's second '>' is still to come (docs/link.md 3.10) */
    int lead; /* this typing's echo starts with that '>' */
    unsigned attempts, probes_here;
    int heard; /* any byte from the controller this command */
    uint64_t t_last, t_deadline, t_probe;
    /* reply analysis */
    fbrl_rapl_reader rd; /* the reply, with its framing */
    int last_byte, prompt_seen, probe_out, probe_seen;
    int err_state, err_code, out_bad, nvalues;
    unsigned stream_got;
    int stop_sent;
    char err_text[48];
    /* results */
    fbrl_rapl_pos pos;
    fbrl_rapl_status_info st;
    long ival;
    double rval;
    int have_prev;   /* reads that agreed so far (0 = none yet) */
    size_t prev_len; /* reply bytes of those reads */
    fbrl_rapl_pos prev_pos;
    fbrl_rapl_status_info prev_st;
    long prev_i;
    double prev_r;
    uint32_t val_sum, prev_sum; /* CRC-32 of the value line (TYPEI/TYPEV): this read's, the reference's */
    size_t val_len, val_longest; /* its length; the longest well-formed value line of this query */
    fbrl_status result;
    int busy;
    fbrl_link_stats stats;
    /* fates (docs/link.md 3.9): the command may be typed again (safe); a CR of it took
     * effect (ran) or an earlier one may have (maybe); this attempt's CR is neither
     * reported nor disproven (cr_pending); the verify probe is the first since the CR */
    int safe, ran, maybe, cr_pending, first_probe;
    /* the controller's LAST ERROR as last proven (-1 NONE, -2 unknown); what it was last
     * seen doing; why the command did not end normally */
    int known_err, seen;
    fbrl_status cause;
    fbrl_link_settle settle;
    unsigned runs, maybe_runs; /* of the command (fbrl_link_outcome) */
    int own_report;            /* reporting the link's own STATUS reads to cfg.on_exec */
    int units;                 /* FBRL_LINK_UNITS_*: the controller's, as last learned */
    /* the gate every line passes before it is typed (fbrl_link_set_gate) */
    fbrl_status (*gate)(void *ctx, const char *line, size_t len, int unguarded);
    void *gate_ctx;
    int unguarded; /* fbrl_link_unguarded: the next line goes around the gate's refusal */
} fbrl_link;

/* The controller's units of length (fbrl_link_units): learned from a STATUS that the
 * link read whole (its last line, "INCH UNITS." or "METRIC UNITS."; a STATUS without that
 * line means inches, the controller's default) and from METRIC or NOMETRIC when they ran.
 * fbrl_link_connect reads them (cfg.check_units); unknown after fbrl_link_init. */
#define FBRL_LINK_UNITS_UNKNOWN (-1)
#define FBRL_LINK_UNITS_INCH    0
#define FBRL_LINK_UNITS_MM      1
FBRL_API int fbrl_link_units(const fbrl_link *l);

/* Bind a session to an open uart (its receive and transmit rings should hold at least
 * 2 * FBRL_LINK_LINE_MAX bytes). cfg NULL = defaults. */
FBRL_API fbrl_status fbrl_link_init(fbrl_link *l, fbrl_uart *u, const fbrl_link_config *cfg);

/* Start-up handshake: bring the controller's line to a known state (erasing whatever
 * was typed), send NOHELP and read the controller's units (STATUS, unless
 * cfg.check_units is 0). Blocking (through the uart's timeouts). FBRL_EUNITS: the
 * controller works in millimetres; the link is connected all the same (so a caller can
 * send NOMETRIC), fbrl_link_units() says FBRL_LINK_UNITS_MM. The link never switches the
 * controller itself: its units are the controller's state, which programs stored on it
 * and its pendant rely on (docs/link.md 1). */
FBRL_API fbrl_status fbrl_link_connect(fbrl_link *l);

/* ---- one command, step by step (several links from one thread) ---- */

/* Start a command line (printable ASCII, at most FBRL_LINK_LINE_MAX, no '?': the probes
 * use it). FBRL_ESTATE if a command is still running. */
FBRL_API fbrl_status fbrl_link_start(fbrl_link *l, const char *line, fbrl_link_reply kind);

/* The check fbrl_link_start() makes of a line, on len bytes: FBRL_OK for 1..FBRL_LINK_LINE_MAX
 * printable ASCII characters without '?', else FBRL_EINVAL. A NUL among the len bytes fails:
 * a caller holding counted strings (Python) learns that C would stop there. */
FBRL_API fbrl_status fbrl_link_line_check(const char *line, size_t len);

/* fbrl_link_cmd() and fbrl_link_raw() started, not run: fbrl_link_poll() runs them, so a
 * caller can look for Ctrl-C between two polls (the Python bindings do). */
FBRL_API fbrl_status fbrl_link_start_cmd(fbrl_link *l, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *args, size_t nargs,
                                         int straight);
FBRL_API fbrl_status fbrl_link_start_raw(fbrl_link *l, const char *line);

/* Make progress for at most timeout_ms (0 = only what is already there). *done = 1
 * when the command has ended; the return value is then its result. While it runs the
 * return value is FBRL_OK. */
FBRL_API fbrl_status fbrl_link_poll(fbrl_link *l, uint32_t timeout_ms, int *done);

/* Start a continuous readout (W1 W3 W5 WE1 WE3 WE5) that ends after `lines` value
 * lines (each passed to the line handler); fbrl_link_poll() runs it. */
FBRL_API fbrl_status fbrl_link_start_stream(fbrl_link *l, fbrl_rapl_cmd cmd, unsigned lines);

/* Non-zero while a command runs. */
FBRL_API int fbrl_link_busy(const fbrl_link *l);

/* Most links one fbrl_link_poll_many() call serves. */
#define FBRL_LINK_POLL_MANY_MAX FBRL_UART_WAIT_MAX

/* Serve several links from one thread for at most timeout_ms and return as soon as one
 * has finished: *index = that link, its result is returned. Fair: each pass serves
 * every link that has bytes or a timer due, the one idle longest first, so no link
 * starves whatever its place in the array (docs/link.md). It sleeps on all ports at
 * once (fbrl_uart_wait_any), and looks at a port only once the bytes its link awaits can
 * have crossed the line (the rest of an echo, the shortest reply), so the host wakes a
 * few times per command, not per byte. FBRL_ETIMEOUT (and *index = n) if none finished
 * in time, FBRL_EEMPTY if none was busy, FBRL_EINVAL for n > FBRL_LINK_POLL_MANY_MAX.
 * NULL entries are skipped. */
FBRL_API fbrl_status fbrl_link_poll_many(fbrl_link *const *links, size_t n, uint32_t timeout_ms,
                                         size_t *index);

/* ---- blocking calls ---- */

/* Encode and run one command from the table. W0/W2/W4, STATUS, TYPEI and TYPEV fill the
 * results below (fbrl_link_last_pos() ...); streams are run by fbrl_link_stream(). */
FBRL_API fbrl_status fbrl_link_cmd(fbrl_link *l, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *args, size_t nargs,
                                   int straight);

/* Run a raw line; its output lines go to cfg.on_line. */
FBRL_API fbrl_status fbrl_link_raw(fbrl_link *l, const char *line);

/* FINISH: wait until the current motion is done. */
FBRL_API fbrl_status fbrl_link_finish(fbrl_link *l);

/* W2 (or W0 / W4 with cmd): position read back; out may be NULL. */
FBRL_API fbrl_status fbrl_link_where(fbrl_link *l, fbrl_rapl_cmd cmd, fbrl_rapl_pos *out);

/* STATUS into out. */
FBRL_API fbrl_status fbrl_link_status(fbrl_link *l, fbrl_rapl_status_info *out);

/* TYPEI / TYPEV of a variable name (or any expression the controller understands,
 * e.g. "SIG(3)"). */
FBRL_API fbrl_status fbrl_link_typei(fbrl_link *l, const char *expr, long *value);
FBRL_API fbrl_status fbrl_link_typev(fbrl_link *l, const char *expr, double *value);

/* Digital input n (1..16): *on = 0 or 1, read with TYPEI SIG(n). */
FBRL_API fbrl_status fbrl_link_input(fbrl_link *l, int n, int *on);

/* Continuous readout (W1 W3 W5 WE1 WE3 WE5): read `lines` value lines, each passed to
 * cfg.on_line, then stop the stream. */
FBRL_API fbrl_status fbrl_link_stream(fbrl_link *l, fbrl_rapl_cmd cmd, unsigned lines);

/* After a reconnect, before the first motion: send every mode in cfg.modes again, in the
 * order of fbrl_link_modes_line(), each as it last ran (nothing without cfg.modes). Stops
 * at the first that does not succeed and returns its result; *sent (may be NULL) = how many
 * were sent before it, so fbrl_link_modes_line(modes, *sent) names the one that failed.
 * FBRL_EUNITS (nothing sent for it) when the tool's location was typed in other units than
 * the controller's now. Resending notes nothing new. */
FBRL_API fbrl_status fbrl_link_modes_resend(fbrl_link *l, size_t *sent);

/* ---- the safe stop ---- */

/* The controller's digital inputs and outputs are numbered 1..FBRL_LINK_IO_MAX. */
#define FBRL_LINK_IO_MAX 16

/* What fbrl_link_safe_stop() found and did (bit n-1 = output n).
 *  result        FBRL_OK: HALT ran; else why the stop is incomplete: FBRL_EBUSY (a command
 *                the controller was running did not end within drain_ms, so HALT could not
 *                be typed), FBRL_EDISCONNECTED, FBRL_ECONTROLLER (HALT refused), or the
 *                status of a HALT that did not run
 *  status_result the STATUS read after HALT (FBRL_ESTATE: none was sent); have_status:
 *                it was read, and homed is its; have_outputs: it showed the outputs (a
 *                RAPL-II STATUS has no OUTPUTS line; fbrlsim prints one with --status-extra)
 *  switched_off  outputs this stop switched off (their OUTPUT -n ran)
 *  off_failed    outputs it tried to switch off and could not (or may have)
 *  left_on       outputs known to be on after it (STATUS showed them on and the caller had
 *                not switched them on, or switching off did not run)
 *  unknown       outputs whose state is not known after it: without an OUTPUTS line every
 *                one it did not switch off; with one, those whose OUTPUT -n may have run
 *  where         W2's WORLD x y z yaw pitch roll after HALT (have_where), in the
 *                controller's units */
typedef struct fbrl_link_stop {
    fbrl_status result;
    int halted;
    fbrl_status status_result;
    int have_status, homed, have_outputs;
    uint32_t switched_off, off_failed, left_on, unknown;
    int have_where;
    double where[6];
} fbrl_link_stop;

/* Make the cell safe (after Ctrl-C, an abort, a caller's halt()): let a command the
 * controller already has end (at most drain_ms: the controller reads nothing else until
 * it answers), HALT the arm, read STATUS, switch off every output of outputs_on (bit n-1
 * = output n: those the caller switched on) that STATUS shows on, or every one of them
 * when STATUS does not show outputs, and read W2 for the report. Outputs the caller did
 * not switch on are left as they are, and named in out->unknown when the controller does
 * not show them. Blocking, bounded by the link's timeouts; the result is also out->result.
 * docs/link.md 1, "The safe stop". */
FBRL_API fbrl_status fbrl_link_safe_stop(fbrl_link *l, uint32_t outputs_on, uint32_t drain_ms,
                                         fbrl_link_stop *out);

/* Before writing raw bytes to the uart yourself (outside the link): erase whatever the
 * link may have left on the controller's line (a probe leaves three marker characters
 * there), so that a CR or LF you send runs only your own text. Sends one CAN unless the
 * line is known to be empty; afterwards the link treats the line as unknown and
 * verifies it before its next command. FBRL_ESTATE while a command runs. */
FBRL_API fbrl_status fbrl_link_clear_line(fbrl_link *l);

/* ---- settings after init ---- */

typedef void (*fbrl_link_line_fn)(void *ctx, const char *line, size_t len, int flawed);

/* Replace the handler of output lines (cfg.on_line, cfg.line_ctx; fn may be NULL).
 * The previous one goes to *old_fn / *old_ctx when those are not NULL, so a caller
 * can borrow the lines for one command and put the owner's handler back. */
FBRL_API fbrl_status fbrl_link_set_line_handler(fbrl_link *l, fbrl_link_line_fn fn, void *ctx,
                                                fbrl_link_line_fn *old_fn, void **old_ctx);

/* The gate every command line passes just before its first byte is typed (the motion
 * guard's: a robot context installs its own, fbrl_robot_set_link; docs/workcell.md "The
 * guard"): fn(ctx, line, len, unguarded) returns FBRL_OK to let the line go, or the
 * command's result (FBRL_EGUARD: a motion the guard did not check) and nothing is sent.
 * unguarded is 1 when the caller went around the guard on purpose (fbrl_link_unguarded).
 * fn NULL: no gate (a link alone knows no work cell). */
typedef fbrl_status (*fbrl_link_gate_fn)(void *ctx, const char *line, size_t len, int unguarded);
FBRL_API fbrl_status fbrl_link_set_gate(fbrl_link *l, fbrl_link_gate_fn fn, void *ctx);
/* The explicit way around the guard for a caller of the link's own commands: the next
 * command (fbrl_link_cmd, fbrl_link_raw, fbrl_link_start ...) is sent even when it is a
 * motion the guard did not check; the gate is still told (it records the motion in the
 * run log and reads the arm afresh before its next check). */
FBRL_API fbrl_status fbrl_link_unguarded(fbrl_link *l);

/* cfg.on_exec later: every line the controller executed. The previous handler goes to
 * *old_fn / *old_ctx (when not NULL) so a new one can pass each line on to it (a trace
 * beside a run log). */
typedef void (*fbrl_link_exec_fn)(void *ctx, const char *line, size_t len, fbrl_status result);
FBRL_API fbrl_status fbrl_link_set_exec_handler(fbrl_link *l, fbrl_link_exec_fn fn, void *ctx,
                                                fbrl_link_exec_fn *old_fn, void **old_ctx);

/* The command form the link sends (keyword or /NNN token, cfg.form). */
FBRL_API fbrl_status fbrl_link_get_form(const fbrl_link *l, fbrl_rapl_form *form);

/* The arm's axis count the link was configured with (cfg.naxes: 5 on the A255, 6 on the
 * A465): how many joint values MA, MI and precision points carry. */
FBRL_API fbrl_status fbrl_link_get_naxes(const fbrl_link *l, unsigned *naxes);

/* ---- results ---- */

/* The controller's error of the last command that ended with FBRL_ECONTROLLER:
 * *code (e.g. 29) and its text ("TRANSFORM ILLEGAL"); code -1 if none. */
FBRL_API fbrl_status fbrl_link_error(const fbrl_link *l, int *code, const char **text);

FBRL_API const fbrl_rapl_pos *fbrl_link_last_pos(const fbrl_link *l);
/* The value of the last FBRL_LINK_REPLY_INT / REAL command that succeeded. */
FBRL_API fbrl_status fbrl_link_last_int(const fbrl_link *l, long *v);
FBRL_API fbrl_status fbrl_link_last_real(const fbrl_link *l, double *v);
FBRL_API const fbrl_rapl_status_info *fbrl_link_last_status(const fbrl_link *l);
FBRL_API fbrl_status fbrl_link_get_stats(const fbrl_link *l, fbrl_link_stats *out);

/* The class of a command's result (RAN for FBRL_OK, REFUSED for FBRL_ECONTROLLER,
 * MAY_HAVE_RUN for FBRL_EMAYBE, NOT_RUN for anything else). */
FBRL_API fbrl_link_fate fbrl_link_fate_of(fbrl_status result);

/* The last command's outcome (FBRL_ESTATE while one runs). */
FBRL_API fbrl_status fbrl_link_outcome_get(const fbrl_link *l, fbrl_link_outcome *out);

/* How many times the command's line has run so far (fbrl_link_outcome.runs, maybe_runs):
 * after it ended, and inside cfg.on_exec for the line being reported (that run counted:
 * runs + maybe_runs is its number, 2 for a line the link typed again), 0 and 0 there for
 * the link's own STATUS reads. A run log uses it to mark a line that ran again. */
FBRL_API fbrl_status fbrl_link_get_runs(const fbrl_link *l, unsigned *runs, unsigned *maybe_runs);

/* Is this line safe to type twice (docs/link.md 3.9)? Table commands say it in the
 * encoder's table; an assignment is safe unless its value reads its own target
 * (V1=V1+1); anything the link cannot classify is not. */
FBRL_API int fbrl_link_line_safe(const char *line);

#ifdef __cplusplus
}
#endif
#endif
