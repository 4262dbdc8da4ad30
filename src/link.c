/* SPDX-License-Identifier: MIT */
/* link.c - the command machine of the echo-verified RAPL session over an fbrl_uart (no
 * OS header): typing a command with echo checks, judging what the CR did, reading the
 * reply, and the command's fate (docs/link.md 3).
 *
 * The controller (docs/rapl-commands.md 1) echoes every printable byte upper-cased,
 * erases with BS SP BS (one "triple" per erased character), ignores other control
 * bytes, and on CR/LF prints CR LF, the output lines and the prompt ">>". The link
 * keeps track of how many characters sit on the controller's line (ctrl_len) and:
 *  - types a command as [CAN] + text; the echo must be exactly ctrl_len triples then
 *    the text, or the attempt is abandoned before any CR is sent;
 *  - after the CR, proof of execution is the controller's CR LF, its prompt, or three
 *    or more bytes (a line that did not end shows at most two stray bytes); without
 *    proof, a probe decides, and a CR is never sent twice;
 *  - whenever the line's content is unknown it sends a probe (link_probe.c) whose echo
 *    proves the line now holds exactly its three markers.
 * None of the bytes the link sends can turn into CR or LF by a single bit flip except
 * '-' (see docs/link.md): letters go out in lower case for that reason.
 *
 * The link's other files, each one idea: the reply's lines and framing are the reply
 * reader's (rapl_reply.c); link_probe.c the probe; link_settle.c settling a damaged reply
 * by STATUS; link_calls.c the blocking calls and the connect; link_aci.c the ACI switch;
 * link_many.c many links from one thread; link_outcome.c what a command ended with;
 * link_modes.c the session's modes; link_query.c believing a query's reply; link_stop.c
 * the safe stop; link_config.c the settings. */
#include "link_internal.h"

#define CAN 0x18
#define BS  0x08
#define XON 0x11

enum { ERR_NONE, ERR_VALID, ERR_GARBLED };

uint64_t fbrli_link_now_us(const fbrl_link *l)
{
    if (l->cfg.now_us)
        return l->cfg.now_us(l->cfg.clock_ctx);
    return l->u->ops->now_us(l->u->ctx);
}

fbrl_status fbrl_link_init(fbrl_link *l, fbrl_uart *u, const fbrl_link_config *cfg)
{
    if (!l || !u || !u->ops || !u->ops->now_us)
        return FBRL_EINVAL;
    fbrl_link_config c;
    if (cfg)
        c = *cfg;
    else
        fbrl_link_config_init(&c);
    if (c.echo_timeout_ms == 0 || c.reply_timeout_ms == 0 || c.wait_timeout_ms == 0 || c.max_attempts == 0 ||
        c.query_reads == 0 || c.query_reads > 3 || c.naxes == 0 || c.naxes > FBRL_RAPL_MAX_AXES ||
        (c.form != FBRL_RAPL_KEYWORD && c.form != FBRL_RAPL_TOKEN))
        return FBRL_EINVAL;
    fbrl_uart_config uc;
    if (fbrl_uart_get_config(u, &uc) != FBRL_OK)
        return FBRL_EINVAL;
    *l = (fbrl_link){0};
    l->u = u;
    l->cfg = c;
    l->units = FBRL_LINK_UNITS_UNKNOWN;
    l->xon_ok = uc.flow == FBRL_FLOW_NONE; /* with XON/XOFF the uart owns 0x11 */
    fbrl_uart_counters cnt;
    if (fbrl_uart_get_counters(u, &cnt) == FBRL_OK)
        l->parity_seen = cnt.parity_errors;
    l->ctrl_len = -1;
    l->phase = PH_IDLE;
    l->err_code = -1;
    l->known_err = FBRLI_ERR_UNKNOWN;
    return FBRL_OK;
}

int fbrl_link_busy(const fbrl_link *l) { return l && l->busy; }

/* ---- sending ---- */

fbrl_status fbrli_link_send(fbrl_link *l, const uint8_t *p, size_t n)
{
    size_t done = 0;
    fbrl_status st = fbrl_uart_write(l->u, p, n, &done, l->cfg.echo_timeout_ms);
    l->t_last = fbrli_link_now_us(l);
    return st;
}

static char lower(char c) { return (c >= 'A' && c <= 'Z') ? (char)(c - 'A' + 'a') : c; }
static char upper(char c) { return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c; }

/* Out of attempts: the echo never matched, or nothing at all came back. */
static fbrl_status gave_up(const fbrl_link *l) { return l->heard ? FBRL_EECHO : FBRL_ETIMEOUT; }

/* Whether a line is command want (by its keyword or its /NNN token). */
static int line_is(const char *line, fbrl_rapl_cmd want)
{
    fbrl_rapl_cmd c;
    return fbrl_rapl_line_cmd(line, &c, 0) == FBRL_OK && c == want;
}

/* A line of the caller's ran with this result: a mode it set is noted (cfg.modes) in the
 * units its lengths were typed in; METRIC and NOMETRIC switch the controller's units, and
 * the link follows what ran (a line that may have run leaves them unknown). */
static void follow_units(fbrl_link *l, fbrl_status result)
{
    if (result == FBRL_OK && l->cfg.modes)
        fbrli_link_modes_note(l->cfg.modes, l->line, l->units);
    int metric = line_is(l->line, FBRL_RAPL_METRIC);
    if (!metric && !line_is(l->line, FBRL_RAPL_NOMETRIC))
        return;
    if (result == FBRL_OK)
        l->units = metric ? FBRL_LINK_UNITS_MM : FBRL_LINK_UNITS_INCH;
    else if (result == FBRL_EMAYBE)
        l->units = FBRL_LINK_UNITS_UNKNOWN;
}

int fbrli_link_learn_units(fbrl_link *l, const fbrl_rapl_status_info *si, int whole)
{
    if (si->have & FBRL_RAPL_ST_UNITS)
        l->units = si->metric ? FBRL_LINK_UNITS_MM : FBRL_LINK_UNITS_INCH;
    else if (whole)
        l->units = FBRL_LINK_UNITS_INCH;
    else
        return 0;
    return 1;
}

/* A STATUS ran: its last line says the units. Read as a value (verified by a second
 * reading) it came whole; shown as it came (a damaged line is not parsed), only the line
 * itself counts. */
static void learn_units(fbrl_link *l) { (void)fbrli_link_learn_units(l, &l->st, l->kind == FBRL_LINK_REPLY_STATUS); }

/* The run log (cfg.on_exec) of one run of the current line. While STATUS settles a
 * command's damaged reply, its runs are only counted: the command itself ran before
 * them and is reported first, once its result is known (settle_end()). */
static void journal(fbrl_link *l, fbrl_status result)
{
    l->cr_pending = 0;
    if (l->stage == ST_ERRQ) {
        fbrli_settle_ran(&l->settle, result);
        return;
    }
    follow_units(l, result);
    if (l->cfg.on_exec)
        l->cfg.on_exec(l->cfg.exec_ctx, l->line, l->len, result);
}

static void report_n(fbrl_link *l, unsigned n, fbrl_status result)
{
    l->own_report = 1; /* not the command's runs (fbrl_link_get_runs) */
    for (unsigned k = 0; k < n && l->cfg.on_exec; k++)
        l->cfg.on_exec(l->cfg.exec_ctx, "STATUS", 6, result);
    l->own_report = 0;
}

/* The settling STATUS reads are over: the command is reported first, then the reads,
 * in the order the controller ran them; the link is back at the command. */
static void settle_end(fbrl_link *l, fbrl_status result)
{
    fbrli_settle_end(&l->settle, l->line, &l->len, &l->kind, &l->attempts);
    l->stage = ST_MAIN;
    l->cr_pending = 0;
    follow_units(l, result);
    if (l->cfg.on_exec)
        l->cfg.on_exec(l->cfg.exec_ctx, l->line, l->len, result);
    report_n(l, l->settle.bad, FBRL_EPROTOCOL);
    report_n(l, l->settle.maybe, FBRL_EMAYBE);
    report_n(l, l->settle.ok, FBRL_OK);
}

/* The command has ended. A failure after a CR that may have taken effect is never
 * "did not run" (docs/link.md 3.9): it becomes FBRL_EMAYBE, whatever the later step
 * that failed (a timeout, a lost port, a STATUS read that never got through), and the
 * cause is kept for fbrl_link_outcome_get(). */
static fbrl_status finish(fbrl_link *l, fbrl_status st)
{
    fbrl_status res = st;
    l->cause = st == FBRL_ECONTROLLER ? FBRL_OK : st;
    if (st != FBRL_OK && st != FBRL_ECONTROLLER) {
        if (l->stage == ST_ERRQ) {
            /* the command ran; its damaged reply could not be settled */
            if (l->cr_pending)
                journal(l, FBRL_EMAYBE);
            res = l->settle.shaped ? FBRL_ECONTROLLER : FBRL_EMAYBE;
            l->err_code = -1;
            l->err_text[0] = '\0';
            l->seen = SEEN_UNSETTLED;
            l->known_err = FBRLI_ERR_UNKNOWN;
            settle_end(l, res);
        } else if (l->ran || l->maybe || l->cr_pending) {
            if (l->cr_pending) {
                l->maybe_runs++;
                journal(l, FBRL_EMAYBE);
            }
            res = FBRL_EMAYBE;
            l->known_err = FBRLI_ERR_UNKNOWN;
        }
    }
    if (res == FBRL_EMAYBE)
        l->stats.may_have_run++;
    if (res == FBRL_OK && l->stage == ST_MAIN && line_is(l->line, FBRL_RAPL_STATUS))
        learn_units(l);
    l->result = res;
    l->busy = 0;
    l->phase = PH_IDLE;
    if (res != FBRL_OK && res != FBRL_ECONTROLLER)
        l->stats.failed++;
    return res;
}

/* A probe (link_probe.c; docs/link.md 3.3): it erases whatever the line holds and leaves
 * exactly its three markers on it. Answered once the controller reads input again, so it
 * also shows the controller is idle at its prompt. With flow control off it begins with
 * XON, which releases a controller that a flipped '3' (0x33 -> XOFF) had paused. */
static fbrl_status send_probe(fbrl_link *l)
{
    uint8_t probe[FBRLI_PROBE_MAX];
    size_t n = fbrli_probe_make(&l->probe, probe, l->xon_ok);
    l->stats.probes++;
    l->probes_here++;
    l->t_probe = fbrli_link_now_us(l);
    return fbrli_link_send(l, probe, n);
}

static fbrl_status begin_erase(fbrl_link *l)
{
    l->lead = 0;
    l->phase = PH_ERASE;
    l->ctrl_len = -1;
    return send_probe(l);
}

/* The byte the controller should echo next: the previous prompt's second '>' when it is
 * owed (3.10), ctrl_len triples, then the text. */
static uint8_t expected(const fbrl_link *l, size_t i, size_t triples)
{
    if (l->lead) {
        if (i == 0)
            return '>';
        i--;
    }
    if (i < 3 * triples)
        return (uint8_t) "\b \b"[i % 3];
    return (uint8_t)l->line[i - 3 * triples];
}

static fbrl_status begin_type(fbrl_link *l)
{
    if (l->attempts >= l->cfg.max_attempts) {
        l->ctrl_len = -1;
        return finish(l, gave_up(l));
    }
    l->attempts++;
    l->stats.attempts++;
    uint8_t out[FBRL_LINK_LINE_MAX + 1];
    size_t n = 0, triples = l->ctrl_len > 0 ? (size_t)l->ctrl_len : 0;
    if (l->ctrl_len != 0)
        out[n++] = CAN;
    for (size_t k = 0; k < l->len; k++)
        out[n++] = (uint8_t)(l->cfg.lower_case ? lower(l->line[k]) : l->line[k]);
    l->match = 0;
    l->triples = triples;
    l->lead = l->owed;
    l->owed = 0;
    l->expect = (size_t)l->lead + 3 * triples + l->len;
    l->phase = PH_TYPE;
    l->ctrl_len = -1; /* unknown until the echo is complete */
    return fbrli_link_send(l, out, n);
}

static void begin_reply(fbrl_link *l)
{
    fbrl_rapl_reader_init(&l->rd);
    l->lead = 0;
    l->phase = PH_REPLY;
    l->prompt_seen = 0;
    l->probe_out = PR_NONE;
    l->probe_seen = 0;
    l->probes_here = 0;
    l->err_state = ERR_NONE;
    l->out_bad = 0;
    l->nvalues = 0;
    l->stream_got = 0;
    l->stop_sent = 0;
    fbrl_rapl_pos_init(&l->pos);
    fbrl_rapl_status_init(&l->st);
    l->t_deadline = fbrli_link_now_us(l) + fbrli_ms(l->timeout_ms);
    /* the CR goes out now: until proof either way, this line may run */
    l->cr_pending = 1;
    l->first_probe = 0;
    l->seen = SEEN_SILENT;
}

/* ---- replies ---- */

/* "NNN-": the start of an error line, whatever happened to the rest. */
static int error_shaped(const char *s, size_t n)
{
    return n >= 6 && s[0] >= '0' && s[0] <= '9' && s[1] >= '0' && s[1] <= '9' && s[2] >= '0' && s[2] <= '9' &&
           s[3] == '-';
}

static void reply_line(fbrl_link *l, const char *s, size_t n, int flawed)
{
    int code;
    char text[sizeof l->err_text];
    fbrl_status est = fbrl_rapl_parse_error(s, n, &code, text, sizeof text);
    if (est == FBRL_OK && !flawed) {
        l->err_state = ERR_VALID;
        l->err_code = code;
        for (size_t k = 0; k < sizeof text; k++)
            l->err_text[k] = text[k];
        return;
    }
    if (est == FBRL_ECHECKSUM || (est == FBRL_OK && flawed) || error_shaped(s, n)) {
        l->err_state = ERR_GARBLED;
        return;
    }
    if (l->kind != FBRL_LINK_REPLY_NONE && l->kind != FBRL_LINK_REPLY_STREAM && l->cfg.on_line)
        l->cfg.on_line(l->cfg.line_ctx, s, n, flawed);
    switch (l->kind) {
    case FBRL_LINK_REPLY_NONE:
        /* anything of error length is a damaged error line; shorter is damaged framing */
        if (n >= 5)
            l->err_state = ERR_GARBLED;
        break;
    case FBRL_LINK_REPLY_POS:
        if (flawed || fbrl_rapl_pos_line(&l->pos, s, n) != FBRL_OK)
            l->out_bad = 1;
        break;
    case FBRL_LINK_REPLY_STATUS:
        if (l->stage == ST_ERRQ) {
            /* only the LAST ERROR CODE line counts (its text is checked against the code) */
            (void)fbrl_rapl_status_line(&l->st, s, n);
            break;
        }
        if (flawed || fbrl_rapl_status_line(&l->st, s, n) == FBRL_ESYNTAX)
            l->out_bad = 1;
        break;
    case FBRL_LINK_REPLY_INT: fbrli_query_value(l, s, n, flawed, fbrl_rapl_parse_int(s, n, &l->ival) == FBRL_OK); break;
    case FBRL_LINK_REPLY_REAL: fbrli_query_value(l, s, n, flawed, fbrl_rapl_parse_real(s, n, &l->rval) == FBRL_OK); break;
    case FBRL_LINK_REPLY_STREAM: {
        long v[FBRL_RAPL_MAX_AXES];
        size_t nv;
        if (fbrl_rapl_parse_ints(s, n, v, FBRL_RAPL_MAX_AXES, &nv) == FBRL_OK && !flawed)
            l->stream_got++;
        if (l->cfg.on_line)
            l->cfg.on_line(l->cfg.line_ctx, s, n, flawed);
        break;
    }
    case FBRL_LINK_REPLY_LINES:
        /* a STATUS shown as it comes (ROBOT-STATUS) still tells the controller's units */
        if (!flawed && l->stage == ST_MAIN && line_is(l->line, FBRL_RAPL_STATUS))
            (void)fbrl_rapl_status_line(&l->st, s, n);
        break;
    }
}

/* A byte of the command's reply (before any probe's echo): the reader cuts the lines and
 * keeps the framing. */
static void feed_reply(fbrl_link *l, uint8_t b)
{
    if (l->seen == SEEN_SILENT)
        l->seen = SEEN_STARTED;
    fbrl_rapl_event ev = fbrl_rapl_reader_feed(&l->rd, b);
    if (ev == FBRL_RAPL_EV_PROMPT) {
        l->prompt_seen = 1;
    } else if (ev == FBRL_RAPL_EV_LINE) {
        size_t n;
        int flawed;
        const char *s = fbrl_rapl_reader_line(&l->rd, &n, &flawed);
        reply_line(l, s, n, flawed);
    }
}

static fbrl_status run_status_query(fbrl_link *l);

/* The reply arrived whole (docs/link.md 3.5): it began with the CR's CR LF, every line
 * ended with CR LF and was undamaged, no byte was lost to a parity error, and the
 * controller's own prompt ended it (not a probe's echo). A command that prints nothing
 * else shows "CR LF >>", or "CR LF NNN-TEXT. CR LF >>" when refused: nothing else. */
static int reply_complete(const fbrl_link *l)
{
    const fbrl_rapl_reader *r = &l->rd;
    if (!fbrl_rapl_reader_whole(r) || l->out_bad)
        return 0;
    if (l->kind == FBRL_LINK_REPLY_NONE)
        return r->eols == 1u + r->lines && r->lines <= 1 && (r->lines == 0 || l->err_state == ERR_VALID);
    return 1;
}

/* Type the line (again): straight away when the line's content is known. */
static fbrl_status retype(fbrl_link *l) { return l->ctrl_len >= 0 ? begin_type(l) : begin_erase(l); }

static fbrl_status run_status_query(fbrl_link *l)
{
    static const char q[] = "STATUS";
    for (size_t k = 0; k < sizeof q; k++)
        l->line[k] = q[k];
    l->len = sizeof q - 1;
    l->kind = FBRL_LINK_REPLY_STATUS;
    l->stage = ST_ERRQ;
    l->attempts = 0;
    l->have_prev = 0;
    l->val_longest = 0;
    l->timeout_ms = l->cfg.reply_timeout_ms;
    return retype(l);
}

/* A command's reply was damaged: read STATUS to settle it (docs/link.md 3.5). */
static fbrl_status begin_settle(fbrl_link *l)
{
    fbrli_settle_begin(&l->settle, l->line, l->len, l->kind, l->attempts, l->err_state == ERR_GARBLED);
    l->stats.settled++;
    l->stats.error_queries++;
    return run_status_query(l);
}

static void set_error(fbrl_link *l, int code)
{
    const char *t = fbrl_rapl_error_text(code);
    size_t k = 0;
    l->err_code = code;
    for (; t && t[k] && k + 1 < sizeof l->err_text; k++)
        l->err_text[k] = t[k];
    l->err_text[k] = '\0';
}

/* STATUS's LAST ERROR settles a damaged reply (fbrli_settle_verdict); a command safe to
 * repeat that it cannot settle is run again. */
static fbrl_status settle_read(fbrl_link *l)
{
    if (!(l->st.have & FBRL_RAPL_ST_ERROR)) {
        journal(l, FBRL_EPROTOCOL);
        l->stats.requeries++;
        if (l->attempts >= l->cfg.max_attempts)
            return finish(l, FBRL_EPROTOCOL);
        return retype(l);
    }
    journal(l, FBRL_OK);
    int last = l->st.last_error;
    fbrl_status res = fbrli_settle_verdict(&l->settle, last, l->known_err);
    if (res == FBRL_ECONTROLLER)
        set_error(l, last);
    if (res == FBRL_EMAYBE)
        l->seen = SEEN_SAME_ERROR;
    int again = res == FBRL_EMAYBE && l->safe && !l->settle.shaped && l->attempts < l->cfg.max_attempts;
    /* it ran (it is settled because its reply came damaged): run again, that run is one
     * whose reply was damaged, as a query's (3.9) */
    settle_end(l, again ? FBRL_EPROTOCOL : res);
    l->known_err = last;
    if (again) {
        /* safe to repeat: run it again, and its clean reply tells (3.5) */
        l->stats.requeries++;
        return retype(l);
    }
    res = finish(l, res == FBRL_EMAYBE ? FBRL_EPROTOCOL : res);
    l->known_err = last;
    return res;
}

/* The controller executed the line: judge the reply, repeat a damaged read-only query,
 * or settle a damaged reply of any other command by reading STATUS. */
static fbrl_status executed(fbrl_link *l)
{
    l->stats.executed++;
    if (!l->rd.done && l->rd.len > 0) {
        /* the reply ended in an unfinished line (its CR LF was lost, and the prompt was
         * found by a probe): an error line "011-LOCATION UNDEFINED.>>" must not pass as
         * success. Only the error shape counts: the rest of such a line is the damaged
         * echo of a probe. */
        size_t n;
        const char *s = fbrl_rapl_reader_line(&l->rd, &n, 0);
        if (error_shaped(s, n))
            l->err_state = ERR_GARBLED;
    }
    if (l->stage == ST_ERRQ)
        return settle_read(l);
    l->ran = 1;
    l->runs++;
    int complete = reply_complete(l);
    if (l->err_state == ERR_VALID) {
        /* its text matches its code: no damage can make one */
        l->known_err = l->err_code;
        journal(l, FBRL_ECONTROLLER);
        return finish(l, FBRL_ECONTROLLER);
    }
    int query = l->kind >= FBRL_LINK_REPLY_POS && l->kind <= FBRL_LINK_REPLY_REAL;
    if (!query) {
        if (l->kind == FBRL_LINK_REPLY_STREAM || (complete && l->err_state == ERR_NONE)) {
            journal(l, l->err_state == ERR_NONE ? FBRL_OK : FBRL_EMAYBE);
            return finish(l, l->err_state == ERR_NONE ? FBRL_OK : FBRL_EPROTOCOL);
        }
        return begin_settle(l);
    }
    int damaged = l->err_state == ERR_GARBLED || !complete;
    if (!damaged) {
        switch (l->kind) {
        case FBRL_LINK_REPLY_POS: damaged = !fbrl_rapl_pos_complete(&l->pos, l->cfg.naxes); break;
        case FBRL_LINK_REPLY_STATUS: {
            unsigned need = FBRL_RAPL_ST_ERROR | FBRL_RAPL_ST_SPEED | FBRL_RAPL_ST_HOMED | FBRL_RAPL_ST_LOCK |
                            FBRL_RAPL_ST_DONE | FBRL_RAPL_ST_LIMP | FBRL_RAPL_ST_AXHOMED;
            damaged = (l->st.have & need) != need || l->st.naxes != l->cfg.naxes;
            break;
        }
        default: damaged = l->nvalues != 1; break;
        }
    }
    /* not yet believed: damaged, or not yet query_reads agreeing replies */
    int again = damaged || !fbrli_query_confirmed(l);
    journal(l, damaged ? FBRL_EPROTOCOL : FBRL_OK);
    if (!again) {
        if (l->kind == FBRL_LINK_REPLY_STATUS)
            l->known_err = l->st.last_error;
        return finish(l, FBRL_OK);
    }
    /* read-only: running it again cannot change anything */
    l->stats.requeries++;
    if (l->attempts >= l->cfg.max_attempts) {
        l->seen = SEEN_UNREADABLE;
        return finish(l, FBRL_EPROTOCOL);
    }
    return retype(l);
}

/* The controller's CR LF proves the line ended (the reader has the line ends). Once a
 * verify probe is out on an 8N1 line no byte reaches the reader (on_byte, PH_VERIFY): an
 * LF then may be the probe's BS (0x08) with one bit flipped. On 8N1 a CR alone proves
 * nothing either: a CR turned into 'M' on its way in is echoed as 'M', which one more flip
 * makes a CR again (3.6); an LF cannot come of a CR that way (they differ in three bits). */
static int eol_seen(const fbrl_link *l)
{
    unsigned cr_ok = l->parity ? FBRL_RAPL_END_CR : 0u;
    return (l->rd.ends & (cr_ok | FBRL_RAPL_END_CRLF | FBRL_RAPL_END_LF)) != 0;
}

/* Proof that the CR ended the line (docs/link.md "after the CR"): the controller's CR
 * LF, its prompt, or three bytes or more. A line that did not end can show at most two
 * stray bytes: a damaged CR echoed as a character, and the first byte of the probe
 * damaged into another ('?' becomes '>' by one flip, so a single '>' proves nothing).
 * With parity a damaged byte is dropped, never echoed as another: a line that did not
 * end shows nothing at all, so one byte (or one parity error) before the probe is
 * proof. That matters: "CR LF >>" can lose CR, LF and one '>'. */
static int cr_took_effect(const fbrl_link *l)
{
    const fbrl_rapl_reader *r = &l->rd;
    return l->prompt_seen || eol_seen(l) || r->gtgt || r->bytes >= (l->parity ? 1u : 3u);
}

/* The first probe after the CR, parsed whole, erased the text (and a damaged CR echoed
 * as a character) besides its own '?': the line was still there when it arrived. */
static int text_was_there(const fbrl_link *l)
{
    long k = l->first_probe ? fbrli_probe_erased(&l->probe) : -1;
    return k >= 0 && ((size_t)k == l->len + 1 || (size_t)k == l->len + 2);
}

/* Did the CR take effect? 1 ran, 0 did not, -1 cannot be proven (docs/link.md 3.2).
 * Proof that it ran: cr_took_effect(). Besides, the FIRST probe after the CR shows what
 * the line held when it arrived: its CAN erases k1 characters, 1 (its own '?') when the
 * CR had emptied the line, len + 1 (len + 2 with a damaged CR echoed as a character)
 * when the text was still there. Only the first: a later probe finds whatever an
 * earlier one, partly lost on the way, left or erased. */
static int verify_decides(const fbrl_link *l)
{
    if (cr_took_effect(l))
        return 1;
    if (l->first_probe && fbrli_probe_erased(&l->probe) == 1)
        return 1;
    return text_was_there(l) ? 0 : -1;
}

/* A probe after the CR has been answered (ctrl_len 3) or its echo came damaged (-1):
 * the command ran, or is typed again because it did not, or - when neither is proven -
 * is typed again only if it is safe to repeat; otherwise it "may have run". */
static fbrl_status verify_done(fbrl_link *l, int ctrl_len)
{
    int d = verify_decides(l);
    l->ctrl_len = ctrl_len;
    l->probe_out = PR_NONE;
    if (d > 0) {
        if (!l->prompt_seen)
            l->stats.prompt_lost++;
        return executed(l);
    }
    l->stats.cr_unconfirmed++;
    if (d == 0) {
        l->cr_pending = 0;
        return retype(l);
    }
    l->seen = SEEN_AMBIGUOUS;
    if (l->safe) {
        l->maybe_runs += l->stage == ST_MAIN; /* (a settling STATUS's is not the command's) */
        journal(l, FBRL_EMAYBE);
        l->maybe = 1;
        return retype(l);
    }
    l->stats.cr_unconfirmed--;
    l->stats.not_retyped++;
    return finish(l, FBRL_EPROTOCOL);
}

/* Enough stream lines came: stop the readout. Any byte ends a stream and is consumed.
 * The first stop is a bare CR (what clients of real controllers send), and only while
 * nothing else has been sent since the W1's own CR: then the controller's line is
 * empty and the stream is running (only a byte from the host ends it), so the CR can
 * end nothing but the stream. Once any byte may have reached the line editor - a
 * probe, or a stop byte the stream had no need of - a CR could run what is on the
 * line (a probe's markers, a damaged earlier byte), so every later stop is a probe:
 * its first byte ends a stream still running, and its echo proves the line's state. */
static fbrl_status stop_stream(fbrl_link *l)
{
    l->stop_sent++;
    if (l->stop_sent == 1 && l->probes_here == 0) {
        static const uint8_t cr = '\r';
        return fbrli_link_send(l, &cr, 1);
    }
    l->probe_out = PR_IDLE;
    l->probe_seen = 0;
    return send_probe(l);
}

/* A probe's markers stay on the controller's line. When a command's idle probe has
 * been answered (it waited: FINISH, a motion, WAIT), the command erases them itself
 * with one CAN and waits for its three triples, so the next command is typed onto an
 * empty line, as fast as after any other command (docs/link.md 3.3). The controller is
 * idle then and the CAN cannot run anything; if its echo is not exactly the triples the
 * line counts as unknown and the next command starts with a probe, as before. */
#define MARKER_LEN 3u
static fbrl_status begin_clean(fbrl_link *l)
{
    static const uint8_t can = CAN;
    l->phase = PH_CLEAN;
    l->match = 0;
    l->expect = 3u * MARKER_LEN;
    l->ctrl_len = -1;
    fbrl_status st = fbrli_link_send(l, &can, 1);
    if (st != FBRL_OK)
        return st;
    l->stats.cleans++;
    return FBRL_OK;
}

/* The clean step ended: erased (ctrl_len 0) or not known (-1); the reply decides now. */
static fbrl_status clean_done(fbrl_link *l, int ctrl_len)
{
    l->ctrl_len = ctrl_len;
    l->phase = PH_REPLY;
    return executed(l);
}

/* ---- the byte-driven state machine ---- */

/* While no CR of ours is out (erasing, typing), a CR LF or a prompt from the controller
 * means it ran something we did not send whole (a '-' turned into CR, 3.4): whatever
 * that was may have set LAST ERROR, so STATUS no longer settles by comparison (3.5). */
static void saw_foreign(fbrl_link *l, uint8_t b)
{
    if (b == '\r' || b == '\n' || (b == '>' && l->last_byte == '>'))
        l->known_err = FBRLI_ERR_UNKNOWN;
    l->last_byte = b;
}

/* The last prompt's second '>' (3.10) answers the command before this one: alone it
 * does not make a silent controller one whose echo went wrong (gave_up()). */
static int is_owed_gt(const fbrl_link *l, uint8_t b)
{
    return b == '>' &&
           ((l->phase == PH_ERASE && l->owed) || (l->phase == PH_TYPE && l->lead && l->match == 0));
}

static fbrl_status on_byte(fbrl_link *l, uint8_t b)
{
    l->t_last = fbrli_link_now_us(l);
    if (!is_owed_gt(l, b))
        l->heard = 1;
    switch (l->phase) {
    case PH_ERASE:
        if (l->owed) {
            /* the last prompt's second '>' (3.10), or the first byte after its loss */
            l->owed = 0;
            if (b == '>')
                return FBRL_OK;
        }
        saw_foreign(l, b);
        fbrli_probe_echo(&l->probe, b, 0);
        if (fbrli_probe_answered(&l->probe)) {
            l->ctrl_len = 3;
            return begin_type(l);
        }
        if (fbrli_probe_ended(&l->probe)) {
            /* the probe's echo ended damaged: no need to wait for silence */
            if (l->attempts >= l->cfg.max_attempts)
                return finish(l, gave_up(l));
            l->attempts++;
            return send_probe(l);
        }
        return FBRL_OK;
    case PH_TYPE:
        /* exact: the controller echoes letters upper-cased, so a lower-case letter in
         * the echo is a damaged byte */
        if (b != expected(l, l->match, l->triples)) {
            l->stats.echo_mismatch++;
            saw_foreign(l, b);
            return begin_erase(l);
        }
        if (++l->match == l->expect) {
            static const uint8_t cr = '\r';
            begin_reply(l);
            return fbrli_link_send(l, &cr, 1);
        }
        return FBRL_OK;
    case PH_REPLY:
        if (l->probe_out == PR_IDLE && (b == '?' || l->probe_seen)) {
            /* the idle probe's echo: the controller reads input again, so it is idle */
            l->probe_seen = 1;
            fbrli_probe_echo(&l->probe, b, l->first_probe);
            if (fbrli_probe_answered(&l->probe)) {
                l->ctrl_len = 3;
                if (!l->prompt_seen && text_was_there(l)) {
                    /* the "proof" was a damaged CR echoed back as CR or LF by a second flip
                     * (3.6): the text is still on the line, the CR took no effect */
                    l->stats.cr_unconfirmed++;
                    l->cr_pending = 0;
                    l->probe_out = PR_NONE;
                    return retype(l);
                }
                if (!l->prompt_seen)
                    l->stats.prompt_lost++;
                l->probe_out = PR_NONE;
                l->prompt_seen = 1;
                return begin_clean(l);
            }
            return FBRL_OK;
        }
        feed_reply(l, b);
        if (l->kind == FBRL_LINK_REPLY_STREAM && !l->prompt_seen &&
            l->stream_got >= l->stream_lines + 3u * (unsigned)l->stop_sent)
            return stop_stream(l);
        if (l->prompt_seen && l->probe_out == PR_NONE) {
            /* after a stream the stop byte may have reached the line editor (a real
             * controller may pass it on): the line is verified before the next command */
            l->ctrl_len = l->kind == FBRL_LINK_REPLY_STREAM ? -1 : 0;
            return executed(l);
        }
        return FBRL_OK;
    case PH_CLEAN:
        if (b != expected(l, l->match, MARKER_LEN))
            return clean_done(l, -1);
        return ++l->match == l->expect ? clean_done(l, 0) : FBRL_OK;
    case PH_VERIFY:
        if (!l->probe_seen && !fbrli_probe_may_echo(b)) {
            /* a byte before the probe's echo: the command's late reply, or the echo
             * damaged. With parity no byte turns into another, so one the echo cannot
             * hold ('?', BS, SP, a marker: with '?' and BS lost it starts with SP) is the
             * reply's. On 8N1 the stray bytes of a damaged CR and of a probe's echo hit
             * twice add up to three: there only the probe's echo decides (3.2) */
            if (l->parity)
                feed_reply(l, b);
            return FBRL_OK;
        }
        l->probe_seen = 1;
        fbrli_probe_echo(&l->probe, b, l->first_probe);
        if (fbrli_probe_answered(&l->probe))
            return verify_done(l, 3);
        return FBRL_OK;
    default: return FBRL_OK; /* idle: stray bytes */
    }
}

/* The prompt has begun and nothing has come after its first '>' yet (docs/link.md 3.10):
 * the reply so far began with CR LF (so the line ran) and the '>' starts a line. No
 * reply line starts with a byte one bit flip away from '>' (error lines start with '0';
 * a query whose value line lost its first digit this way lacks a value and is read
 * again), so this '>' is the prompt as surely as ">>" would be. */
static int prompt_begun(const fbrl_link *l)
{
    return l->phase == PH_REPLY && l->probe_out == PR_NONE && l->kind != FBRL_LINK_REPLY_STREAM &&
           l->rd.began && eol_seen(l) && !l->rd.done && l->rd.len == 1 && l->rd.line[0] == '>' &&
           !l->rd.flawed;
}

/* Finish on the prompt's first '>': its second is owed, and the next echo the link
 * awaits must start with it (expected(), or PH_ERASE). The next command's first byte
 * then reaches the controller while it sends that '>', so its output line never idles
 * between one command's prompt and the next one's echo. */
static fbrl_status early_prompt(fbrl_link *l)
{
    feed_reply(l, '>');
    l->owed = 1;
    l->ctrl_len = 0;
    l->stats.early_prompts++;
    return executed(l);
}

/* The uart dropped a byte with a parity error since the last look (the marks of
 * uart_posix, or a UART's line status): the bytes just read are incomplete. */
static int parity_error(fbrl_link *l)
{
    fbrl_uart_counters c;
    if (fbrl_uart_get_counters(l->u, &c) != FBRL_OK || c.parity_errors == l->parity_seen)
        return 0;
    l->stats.parity_errors += c.parity_errors - l->parity_seen;
    l->parity_seen = c.parity_errors;
    return 1;
}

/* How long an unanswered probe is given before the next: a controller busy with a long
 * motion answers none, so the interval doubles (4, 8, 16 ... echo timeouts, at most 2 s). */
static uint64_t probe_interval(const fbrl_link *l)
{
    uint64_t iv = fbrli_ms(4 * l->cfg.echo_timeout_ms);
    for (unsigned k = 1; k < l->probes_here && iv < 2000000u; k++)
        iv *= 2;
    return iv < 2000000u ? iv : 2000000u;
}

/* Nothing arrived for a while: decide what the silence means. */
static fbrl_status on_silence(fbrl_link *l, uint64_t t)
{
    switch (l->phase) {
    case PH_ERASE:
        if (l->attempts >= l->cfg.max_attempts)
            return finish(l, gave_up(l));
        l->attempts++;
        return send_probe(l);
    case PH_TYPE: l->stats.echo_timeout++; return begin_erase(l);
    case PH_REPLY:
        if (l->kind == FBRL_LINK_REPLY_STREAM && !l->stop_sent && !l->prompt_seen && cr_took_effect(l)) {
            /* a running stream may be slower than the echo timeout: a probe now would
             * end it and leave its markers on the line; wait for the lines (the
             * deadline bounds this) */
            l->t_last = t;
            return FBRL_OK;
        }
        if (cr_took_effect(l)) {
            /* executed; the prompt is late (a waiting command) or was damaged: ask */
            if (t - l->t_probe >= probe_interval(l) || l->probe_out == PR_NONE) {
                /* the first one also checks the proof (on_byte) */
                l->first_probe = l->probes_here == 0 && l->kind != FBRL_LINK_REPLY_STREAM;
                l->probe_out = PR_IDLE;
                l->probe_seen = 0;
                return send_probe(l);
            }
            l->t_last = t;
            return FBRL_OK;
        }
        /* no proof the CR arrived: find out without risking an execution */
        l->phase = PH_VERIFY;
        l->probe_out = PR_VERIFY;
        l->probe_seen = 0;
        l->probes_here = 0;
        l->first_probe = 1;
        return send_probe(l);
    case PH_CLEAN: return clean_done(l, -1);
    case PH_VERIFY:
        if (l->probe_seen) {
            /* the probe's echo was damaged, but the bytes before it may decide */
            return verify_done(l, -1);
        }
        if (t - l->t_probe >= probe_interval(l)) {
            l->first_probe = 0; /* its echo is lost: the next one proves less */
            return send_probe(l);
        }
        l->t_last = t;
        return FBRL_OK;
    default: return FBRL_OK;
    }
}

fbrl_status fbrl_link_poll(fbrl_link *l, uint32_t timeout_ms, int *done)
{
    if (!l || !done)
        return FBRL_EINVAL;
    *done = 0;
    if (!l->busy) {
        *done = 1;
        return l->result;
    }
    uint64_t start = fbrli_link_now_us(l), budget = fbrli_ms(timeout_ms);
    for (;;) {
        uint64_t t = fbrli_link_now_us(l);
        uint64_t quiet_end = l->t_last + fbrli_ms(l->cfg.echo_timeout_ms);
        if ((l->phase == PH_REPLY || l->phase == PH_VERIFY) && t >= l->t_deadline) {
            l->ctrl_len = -1;
            if (l->seen == SEEN_STARTED && l->probes_here > 0)
                l->seen = SEEN_BUSY;
            *done = 1;
            return finish(l, FBRL_ETIMEOUT);
        }
        /* Past the quiet time the line is still looked at once, without waiting: bytes
         * that came while this thread was not running are not silence. */
        int quiet = t >= quiet_end;
        uint64_t spent = t - start;
        if (!quiet && spent > budget)
            return FBRL_OK;
        uint64_t wait = quiet ? 0 : quiet_end - t;
        if (wait > budget - spent)
            wait = budget - spent;
        uint8_t buf[64];
        size_t got = 0;
        fbrl_status st = fbrl_uart_read(l->u, buf, sizeof buf, &got, (uint32_t)((wait + 999) / 1000));
        if (st != FBRL_OK && st != FBRL_ETIMEOUT && got == 0) {
            l->ctrl_len = -1;
            *done = 1;
            return finish(l, st);
        }
        int damaged = parity_error(l);
        if (quiet && got == 0 && !damaged) {
            st = on_silence(l, t);
            if (!l->busy || st != FBRL_OK) {
                *done = 1;
                if (l->busy)
                    l->ctrl_len = -1;
                return l->busy ? finish(l, st) : l->result;
            }
            continue;
        }
        if (damaged) {
            if (l->phase == PH_TYPE) {
                /* a byte of the echo (or a stray one before it) was lost: nothing of it
                 * can be trusted, and no CR goes out for it; older than the probe, the
                 * bytes just read are of no use after it */
                st = begin_erase(l);
                if (st != FBRL_OK) {
                    *done = 1;
                    return finish(l, st);
                }
                got = 0;
            } else if (l->phase == PH_REPLY || l->phase == PH_VERIFY) {
                l->out_bad = 1; /* a query is asked again; an error line is checked anyway */
                if (l->phase == PH_REPLY && l->probe_out == PR_NONE)
                    fbrl_rapl_reader_lost(&l->rd); /* a byte came after the CR, before any probe */
            }
        }
        size_t k = 0;
        for (; k < got && l->busy; k++) {
            fbrl_status s2 = on_byte(l, buf[k]);
            if (s2 != FBRL_OK && l->busy) {
                l->ctrl_len = -1; /* a byte may not have gone out */
                *done = 1;
                return finish(l, s2);
            }
        }
        if (l->busy && k == got && prompt_begun(l) && fbrl_uart_rx_available(l->u) == 0) {
            fbrl_status s2 = early_prompt(l);
            if (s2 != FBRL_OK && l->busy) {
                l->ctrl_len = -1;
                *done = 1;
                return finish(l, s2);
            }
        }
        if (!l->busy) {
            /* bytes after the prompt are the echo of something on the line (noise): the
             * next command must not type onto it unverified */
            if (k < got)
                l->ctrl_len = -1;
            *done = 1;
            return l->result;
        }
        if (got == 0 && spent >= budget)
            return FBRL_OK;
    }
}

fbrl_status fbrl_link_line_check(const char *line, size_t len)
{
    if (!line || len == 0 || len > FBRL_LINK_LINE_MAX)
        return FBRL_EINVAL;
    for (size_t k = 0; k < len; k++)
        if (line[k] < 0x20 || line[k] > 0x7e || line[k] == '?')
            return FBRL_EINVAL;
    return FBRL_OK;
}

static fbrl_status check_line(const char *line, size_t *len)
{
    size_t n = 0;
    if (!line)
        return FBRL_EINVAL;
    while (n <= FBRL_LINK_LINE_MAX && line[n])
        n++;
    fbrl_status st = fbrl_link_line_check(line, n);
    if (st == FBRL_OK)
        *len = n;
    return st;
}

fbrl_status fbrli_link_start(fbrl_link *l, const char *line, fbrl_link_reply kind, uint32_t timeout_ms,
                             int safe)
{
    size_t n;
    if (!l || !l->u)
        return FBRL_EINVAL;
    if (l->busy)
        return FBRL_ESTATE;
    fbrl_status st = check_line(line, &n);
    int unguarded = l->unguarded;
    l->unguarded = 0; /* for this one line only, whatever becomes of it */
    if (st != FBRL_OK)
        return st;
    if (l->gate && (st = l->gate(l->gate_ctx, line, n, unguarded)) != FBRL_OK)
        return st; /* the guard's: nothing of it is typed */
    for (size_t k = 0; k < n; k++)
        l->line[k] = upper(line[k]);
    l->line[n] = '\0';
    l->len = n;
    l->kind = kind;
    l->timeout_ms = timeout_ms;
    l->stage = ST_MAIN;
    l->attempts = 0;
    l->have_prev = 0;
    l->val_longest = 0;
    l->heard = 0;
    l->err_code = -1;
    l->err_text[0] = '\0';
    l->result = FBRL_OK;
    l->safe = safe;
    l->ran = l->maybe = l->cr_pending = 0;
    l->runs = l->maybe_runs = 0;
    l->seen = SEEN_NONE;
    l->cause = FBRL_OK;
    l->busy = 1;
    l->stats.commands++;
    fbrl_uart_config uc;
    l->parity = fbrl_uart_get_config(l->u, &uc) == FBRL_OK && uc.parity != FBRL_PARITY_NONE;
    /* a known line (a probe's markers) is erased by the CAN in front of the text, whose
     * echo must show exactly its triples: no probe needed */
    return l->ctrl_len >= 0 ? begin_type(l) : begin_erase(l);
}

int fbrl_link_line_safe(const char *line) { return fbrl_rapl_line_safe(line); }

/* The deadline for the prompt: long for what the table says may wait, and for lines
 * the link cannot classify. */
static uint32_t timeout_for_line(const fbrl_link *l, const char *line)
{
    fbrl_rapl_cmd c;
    if (fbrl_rapl_line_cmd(line, &c, 0) == FBRL_OK && !(fbrl_rapl_cmd_info(c)->flags & FBRL_RAPL_F_WAITS))
        return l->cfg.reply_timeout_ms;
    return l->cfg.wait_timeout_ms;
}

fbrl_status fbrl_link_start(fbrl_link *l, const char *line, fbrl_link_reply kind)
{
    if (!l || !line || (int)kind < 0 || kind > FBRL_LINK_REPLY_STREAM)
        return FBRL_EINVAL;
    return fbrli_link_start(l, line, kind, timeout_for_line(l, line), fbrl_link_line_safe(line));
}

fbrl_status fbrl_link_start_stream(fbrl_link *l, fbrl_rapl_cmd cmd, unsigned lines)
{
    char text[FBRL_RAPL_LINE_MAX];
    size_t n;
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    if (!l || lines == 0 || !ci || ci->reply != FBRL_LINK_REPLY_STREAM)
        return FBRL_EINVAL;
    if (l->busy)
        return FBRL_ESTATE;
    fbrl_status st = fbrl_rapl_encode(text, sizeof text, &n, l->cfg.form, cmd, 0, 0, 0);
    if (st != FBRL_OK)
        return st;
    l->stream_lines = lines;
    return fbrli_link_start(l, text, FBRL_LINK_REPLY_STREAM, l->cfg.reply_timeout_ms + lines * 1000u, 1);
}

fbrl_status fbrl_link_clear_line(fbrl_link *l)
{
    static const uint8_t can = CAN;
    if (!l || !l->u)
        return FBRL_EINVAL;
    if (l->busy)
        return FBRL_ESTATE;
    if (l->owed) {
        /* the last prompt's second '>' is still on its way: take it off the line, so raw
         * reads after this start with the answer to the raw bytes */
        uint8_t b = 0;
        size_t got = 0;
        (void)fbrl_uart_read(l->u, &b, 1, &got, l->cfg.echo_timeout_ms);
        l->owed = 0;
        if (got != 1 || b != '>')
            l->ctrl_len = -1;
    }
    fbrl_status st = l->ctrl_len == 0 ? FBRL_OK : fbrli_link_send(l, &can, 1);
    l->ctrl_len = -1;
    return st;
}
