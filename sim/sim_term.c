/* SPDX-License-Identifier: MIT */
/* sim_term.c - the controller's terminal mode: the line editor (echo, BS/DEL,
 * Ctrl-X, HELP-mode hints), the framing of a reply (CR LF, error line, prompt),
 * the controller's own time to process a command, and the position readouts
 * that stream until a key is pressed. What a line means is sim_cmd.c's. */
#include "sim_internal.h"

#include <ctype.h>
#include <errno.h>
#include <string.h>

#define TX_BUSY       512  /* pending output bytes at which the controller stops reading input */
#define STREAM_PERIOD 0.1  /* s between the lines of a W1/W3/W5 readout */
#define NAK           0x15 /* --nak: sent before an error line, as S3 expects */
#define CTRL_Z        0x1A /* two of them: back to ACI mode (--aci), research notes 2.5 */

static void emit_str(fbrl_sim *s, const char *str) { sim_emit(s, str, strlen(str)); }

void sim_term_reset(sim_term *t)
{
    if (t->ps == PS_STREAM || t->ps == PS_THINK)
        t->ps = PS_IDLE; /* nobody left to stop the readout or to read the reply */
    t->len = 0;
    t->overlong = 0;
}

void sim_term_greet(fbrl_sim *s)
{
    if (s->term.ps == PS_IDLE && s->term.len == 0 && !s->term.aci) /* ACI mode never prompts */
        emit_str(s, ">>");
}

static void finish(fbrl_sim *s, int err)
{
    sim_term *t = &s->term;
    if (t->out.len)
        sim_emit(s, t->out.buf, t->out.len);
    t->out.len = 0;
    if (err >= 0) {
        char e[96];
        static const char nak[] = {NAK, 0};
        snprintf(e, sizeof e, "%s%03d-%s.\r\n", s->opt.nak ? nak : "", err, sim_error_text(err));
        emit_str(s, e);
        s->term.last_error = err;
    }
    if (t->cmd_logged && s->log) {
        /* the stamped log: when the line was taken, how it ended, the line */
        char st[12] = "OK";
        if (err >= 0)
            snprintf(st, sizeof st, "%03d", err);
        fprintf(s->log, "%.3f %s %s\n", t->cmd_t, st, t->cur);
        fflush(s->log);
    }
    t->cmd_logged = 0;
    if (t->ps == PS_STREAM) {
        t->stream_next = sim_real_now(s);
    } else {
        t->ps = PS_IDLE;
        emit_str(s, ">>");
    }
    if (s->dirty && s->state_path) {
        if (sim_state_save(s) != 0 && !s->save_warned) {
            fprintf(stderr, "fbrlsim: cannot write %s: %s\n", s->state_path, strerror(errno));
            s->save_warned = 1;
        }
        s->dirty = 0;
    }
}

static void run(fbrl_sim *s)
{
    int err = -1;
    if (sim_exec(s, s->term.cur, &err) == EXEC_BLOCK) {
        s->term.ps = PS_BUSY;
        return;
    }
    finish(s, err);
}

static void submit(fbrl_sim *s)
{
    sim_term *t = &s->term;
    int overlong = t->overlong, i, blank = 1;
    memcpy(t->cur, t->line, (size_t)t->len);
    t->cur[t->len] = 0;
    t->len = 0;
    t->overlong = 0;
    if (s->line.f_stall > 0)
        sim_line_hold(&s->line, sim_real_now(s) + s->line.f_stall / 1000.0);
    emit_str(s, "\r\n");
    for (i = 0; t->cur[i]; i++)
        if (t->cur[i] != ' ')
            blank = 0;
    if (t->editing) { /* EDIT: the line is the program's next line, kept and not run */
        int e = overlong ? SIM_E_LINE_TOO_LONG : sim_prog_edit(s, t->cur, blank);
        if (s->log && !blank && !e) { /* not a command the controller ran: '#' first */
            fprintf(s->log, "# EDIT %s: %s\n", t->edit_prog, t->cur);
            fflush(s->log);
        }
        finish(s, e ? e : -1);
        return;
    }
    if (blank && !overlong) {
        emit_str(s, ">>");
        return;
    }
    if (s->log && s->opt.log_stamped) {
        t->cmd_t = sim_now(s); /* written with its result when it ends (finish) */
        t->cmd_logged = 1;
    } else if (s->log) {
        fprintf(s->log, "%s\n", t->cur);
        fflush(s->log);
    }
    if (overlong) {
        finish(s, SIM_E_LINE_TOO_LONG);
        return;
    }
    if (s->opt.cmd_time_ms > 0) {
        /* the controller's processor reads and parses the line before anything happens */
        t->ps = PS_THINK;
        t->think_until = sim_real_now(s) + s->opt.cmd_time_ms / 1000.0 / s->opt.time_scale;
        return;
    }
    run(s);
}

static void echo(fbrl_sim *s, const char *b, size_t n)
{
    if (s->dev.chan[0].echo)
        sim_emit(s, b, n);
}

static void erase_one(fbrl_sim *s)
{
    sim_term *t = &s->term;
    if (t->len > 0) {
        t->len--;
        echo(s, "\b \b", 3);
    }
    if (t->len == 0)
        t->overlong = 0; /* an emptied line starts afresh */
}

/* HELP mode: after the first word, show its syntax and erase it again. */
static void help_hint(fbrl_sim *s)
{
    sim_term *t = &s->term;
    char word[SIM_LINE_MAX + 1];
    const char *hint;
    int i;
    memcpy(word, t->line, (size_t)t->len - 1);
    word[t->len - 1] = 0;
    for (i = 0; word[i]; i++)
        if (word[i] == ' ' || word[i] == ',')
            return;
    hint = sim_help_hint(word);
    if (hint && *hint) {
        size_t k, n = strlen(hint);
        echo(s, hint, n);
        for (k = 0; k < n; k++)
            echo(s, "\b \b", 3);
    }
}

static void line_byte(fbrl_sim *s, unsigned char b)
{
    sim_term *t = &s->term;
    char c;
    if (t->aci && !sim_aci_byte(s, b))
        return;
    if (s->opt.aci && b == CTRL_Z) {
        if (t->ctrl_z) {
            sim_aci_enter(s); /* the half-typed line is dropped */
            return;
        }
        t->ctrl_z = 1;
        return;
    }
    t->ctrl_z = 0;
    if (b == '\n' && t->last_cr) {
        t->last_cr = 0;
        return;
    }
    t->last_cr = b == '\r';
    if (b == '\r' || b == '\n') {
        submit(s);
        return;
    }
    if (b == 0x08 || b == 0x7f) {
        erase_one(s);
        return;
    }
    if (b == 0x18) {
        while (t->len > 0)
            erase_one(s);
        return;
    }
    if (b < 0x20 || b > 0x7e)
        return;
    c = (char)toupper(b);
    if (t->len >= SIM_LINE_MAX) {
        t->overlong = 1;
        return;
    }
    t->line[t->len++] = c;
    if (s->opt.echo_as_typed) {
        char typed = (char)b;
        echo(s, &typed, 1);
    } else {
        echo(s, &c, 1);
    }
    if (t->help && (c == ' ' || c == ','))
        help_hint(s);
}

void sim_term_process(fbrl_sim *s)
{
    sim_term *t = &s->term;
    int err;
    double now = sim_real_now(s);
    if (t->ps == PS_THINK && now >= t->think_until)
        run(s);
    if (t->ps == PS_BUSY && sim_exec_step(s, &err) == EXEC_DONE)
        finish(s, err);
    if (t->ps == PS_STREAM) {
        int b = sim_line_rx_pop(s);
        if (b >= 0) {
            t->ps = PS_IDLE;
            emit_str(s, "\r\n>>");
        } else if (now >= t->stream_next) {
            sim_stream_line(s, &t->out);
            sim_emit(s, t->out.buf, t->out.len);
            t->out.len = 0;
            t->stream_next += STREAM_PERIOD;
            if (t->stream_next < now)
                t->stream_next = now + STREAM_PERIOD;
        }
    }
    while (t->ps == PS_IDLE && s->line.rxcount > 0 && sim_line_tx_pending(&s->line) < TX_BUSY)
        line_byte(s, (unsigned char)sim_line_rx_pop(s));
}

double sim_term_due(const sim_term *t, const sim_line *l, double now, double limit)
{
    double r = limit;
    if (t->ps == PS_BUSY && r > SIM_POLL_BUSY)
        r = SIM_POLL_BUSY; /* WAIT and RUN poll their conditions */
    if (t->ps == PS_THINK && t->think_until - now < r)
        r = t->think_until - now;
    if (t->ps == PS_STREAM && t->stream_next - now < r)
        r = t->stream_next - now;
    if (t->ps == PS_IDLE && l->rxcount > 0 && sim_line_tx_pending(l) < TX_BUSY)
        r = 0;
    return r;
}
