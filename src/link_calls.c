/* SPDX-License-Identifier: MIT */
/* link_calls.c - the link's blocking calls (docs/link.md 1): each is fbrl_link_start (or
 * the table's encoding of a command) and fbrl_link_poll until it is done; the connect
 * handshake (the ACI switch when asked, NOHELP, the controller's units); and sending the
 * session's modes again after a reconnect. Every wait is the uart's timed read. */
#include "link_internal.h"

static fbrl_status run(fbrl_link *l)
{
    for (;;) {
        int done = 0;
        fbrl_status st = fbrl_link_poll(l, 1000, &done);
        if (done)
            return st;
    }
}

/* The connect's STATUS lines: only an undamaged one is parsed (its units line decides). */
static void units_line(void *ctx, const char *s, size_t n, int flawed)
{
    if (!flawed)
        (void)fbrl_rapl_status_line(ctx, s, n);
}

/* The controller's units, at connect (docs/link.md 1): STATUS shown as it comes (some 700
 * bytes, 0.75 s at 9600 baud), its lines not the caller's. An undamaged units line decides,
 * wherever it came (also in a settling read): no damage makes one of the other. STATUS is
 * read-only, so a reply whose units line came damaged is simply read again; one that came
 * whole without that line means inches (the controller's default). */
static fbrl_status read_units(fbrl_link *l)
{
    fbrl_link_line_fn fn = l->cfg.on_line;
    void *ctx = l->cfg.line_ctx;
    fbrl_rapl_status_info si;
    fbrl_status st = FBRL_OK;
    l->cfg.on_line = units_line;
    l->cfg.line_ctx = &si;
    for (unsigned k = 0; k < l->cfg.max_attempts; k++) {
        uint64_t settled = l->stats.settled;
        fbrl_rapl_status_init(&si);
        st = fbrli_link_start(l, "STATUS", FBRL_LINK_REPLY_LINES, l->cfg.reply_timeout_ms, 1);
        if (st == FBRL_OK)
            st = run(l);
        if (fbrli_link_learn_units(l, &si, st == FBRL_OK && l->stats.settled == settled))
            break;
        if (st != FBRL_OK && st != FBRL_EMAYBE && st != FBRL_EPROTOCOL && st != FBRL_ECONTROLLER)
            break; /* did not run: the controller does not answer */
    }
    l->cfg.on_line = fn;
    l->cfg.line_ctx = ctx;
    return l->units != FBRL_LINK_UNITS_UNKNOWN ? FBRL_OK : st != FBRL_OK ? st : FBRL_EPROTOCOL;
}

fbrl_status fbrl_link_connect(fbrl_link *l)
{
    if (!l || !l->u)
        return FBRL_EINVAL;
    l->ctrl_len = -1;
    l->units = FBRL_LINK_UNITS_UNKNOWN;
    if (l->cfg.aci) {
        fbrl_status sw = fbrli_link_aci_switch(l);
        if (sw != FBRL_OK)
            return sw;
    }
    fbrl_status st = fbrli_link_start(l, "NOHELP", FBRL_LINK_REPLY_NONE, l->cfg.reply_timeout_ms, 1);
    if (st == FBRL_OK)
        st = run(l);
    if (st != FBRL_OK || !l->cfg.check_units)
        return st;
    st = read_units(l);
    if (st != FBRL_OK)
        return st;
    return l->units == FBRL_LINK_UNITS_MM ? FBRL_EUNITS : FBRL_OK;
}

fbrl_status fbrl_link_start_cmd(fbrl_link *l, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *args, size_t nargs,
                                int straight)
{
    char text[FBRL_RAPL_LINE_MAX];
    size_t n;
    if (!l)
        return FBRL_EINVAL;
    fbrl_status st = fbrl_rapl_encode(text, sizeof text, &n, l->cfg.form, cmd, args, nargs, straight);
    if (st != FBRL_OK)
        return st;
    if (n > FBRL_LINK_LINE_MAX)
        return FBRL_ERANGE;
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    if (ci->reply == FBRL_LINK_REPLY_STREAM)
        return FBRL_EINVAL; /* fbrl_link_stream() */
    return fbrli_link_start(l, text, ci->reply,
                            (ci->flags & FBRL_RAPL_F_WAITS) ? l->cfg.wait_timeout_ms : l->cfg.reply_timeout_ms,
                            (ci->flags & FBRL_RAPL_F_SAFE) != 0);
}

fbrl_status fbrl_link_cmd(fbrl_link *l, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *args, size_t nargs,
                          int straight)
{
    fbrl_status st = fbrl_link_start_cmd(l, cmd, args, nargs, straight);
    return st == FBRL_OK ? run(l) : st;
}

fbrl_status fbrl_link_start_raw(fbrl_link *l, const char *line)
{
    fbrl_rapl_cmd c;
    fbrl_link_reply kind = FBRL_LINK_REPLY_LINES;
    if (!l || !line)
        return FBRL_EINVAL;
    if (fbrl_rapl_line_cmd(line, &c, 0) == FBRL_OK)
        kind = fbrl_rapl_cmd_info(c)->reply;
    if (kind == FBRL_LINK_REPLY_STREAM)
        return FBRL_EINVAL; /* fbrl_link_stream() stops a stream */
    return fbrl_link_start(l, line, kind);
}

fbrl_status fbrl_link_raw(fbrl_link *l, const char *line)
{
    fbrl_status st = fbrl_link_start_raw(l, line);
    return st == FBRL_OK ? run(l) : st;
}

fbrl_status fbrl_link_finish(fbrl_link *l) { return fbrl_link_cmd(l, FBRL_RAPL_FINISH, 0, 0, 0); }

fbrl_status fbrl_link_where(fbrl_link *l, fbrl_rapl_cmd cmd, fbrl_rapl_pos *out)
{
    if (cmd != FBRL_RAPL_W0 && cmd != FBRL_RAPL_W2 && cmd != FBRL_RAPL_W4)
        return FBRL_EINVAL;
    fbrl_status st = fbrl_link_cmd(l, cmd, 0, 0, 0);
    if (st == FBRL_OK && out)
        *out = l->pos;
    return st;
}

fbrl_status fbrl_link_status(fbrl_link *l, fbrl_rapl_status_info *out)
{
    fbrl_status st = fbrl_link_cmd(l, FBRL_RAPL_STATUS, 0, 0, 0);
    if (st == FBRL_OK && out)
        *out = l->st;
    return st;
}

int fbrl_link_units(const fbrl_link *l) { return l ? l->units : FBRL_LINK_UNITS_UNKNOWN; }

static fbrl_status type_value(fbrl_link *l, const char *kw, const char *expr, fbrl_link_reply kind)
{
    char text[FBRL_LINK_LINE_MAX + 1];
    size_t n = 0;
    if (!l || !expr)
        return FBRL_EINVAL;
    while (*kw)
        text[n++] = *kw++;
    text[n++] = ' ';
    for (; *expr; expr++) {
        if (n >= FBRL_LINK_LINE_MAX || *expr == ',')
            return FBRL_EINVAL;
        text[n++] = *expr;
    }
    text[n] = '\0';
    fbrl_status st = fbrli_link_start(l, text, kind, l->cfg.reply_timeout_ms, 1); /* read-only */
    return st == FBRL_OK ? run(l) : st;
}

fbrl_status fbrl_link_typei(fbrl_link *l, const char *expr, long *value)
{
    if (!value)
        return FBRL_EINVAL;
    fbrl_status st = type_value(l, "TYPEI", expr, FBRL_LINK_REPLY_INT);
    if (st == FBRL_OK)
        *value = l->ival;
    return st;
}

fbrl_status fbrl_link_typev(fbrl_link *l, const char *expr, double *value)
{
    if (!value)
        return FBRL_EINVAL;
    fbrl_status st = type_value(l, "TYPEV", expr, FBRL_LINK_REPLY_REAL);
    if (st == FBRL_OK)
        *value = l->rval;
    return st;
}

fbrl_status fbrl_link_input(fbrl_link *l, int n, int *on)
{
    char expr[8] = "SIG(";
    long v;
    if (!on || n < 1 || n > 16)
        return n < 1 || n > 16 ? FBRL_ERANGE : FBRL_EINVAL;
    size_t k = 4;
    if (n >= 10)
        expr[k++] = (char)('0' + n / 10);
    expr[k++] = (char)('0' + n % 10);
    expr[k++] = ')';
    expr[k] = '\0';
    fbrl_status st = fbrl_link_typei(l, expr, &v);
    if (st == FBRL_OK) {
        if (v != 0 && v != 1)
            return FBRL_EPROTOCOL;
        *on = (int)v;
    }
    return st;
}

fbrl_status fbrl_link_stream(fbrl_link *l, fbrl_rapl_cmd cmd, unsigned lines)
{
    fbrl_status st = fbrl_link_start_stream(l, cmd, lines);
    return st == FBRL_OK ? run(l) : st;
}

fbrl_status fbrl_link_modes_resend(fbrl_link *l, size_t *sent)
{
    size_t n = 0;
    fbrl_status st = FBRL_OK;
    if (sent)
        *sent = 0;
    if (!l)
        return FBRL_EINVAL;
    fbrl_link_modes *m = l->cfg.modes;
    l->cfg.modes = 0; /* GAIN 0,v would clear the other gains before they are sent */
    for (const char *line; st == FBRL_OK && (line = fbrl_link_modes_line(m, n)) != 0; n += st == FBRL_OK) {
        int typed = fbrli_link_modes_units(m, n);
        st = typed != FBRLI_NO_LENGTHS && typed != l->units ? FBRL_EUNITS : fbrl_link_raw(l, line);
    }
    l->cfg.modes = m;
    if (sent)
        *sent = n;
    return st;
}
