/* SPDX-License-Identifier: MIT */
/* robot_line.c - thesis I-8: a RAPL command line built piecewise (SEND-COM, SEND-INT,
 * SEND-LOC ...) and sent, echo-verified, by SEND-CR. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* ---- I-8: building a command line piecewise ---- */

static fbrl_status put(fbrl_robot *r, const char *s, size_t n)
{
    if (r->len + n > FBRL_LINK_LINE_MAX) {
        r->line_bad = 1;
        return FBRL_OK; /* reported by SEND-CR, which refuses the whole line */
    }
    memcpy(r->line + r->len, s, n);
    r->len += n;
    r->line[r->len] = '\0';
    return FBRL_OK;
}

/* A parameter right after the command word is separated from it by a space. */
static void sep(fbrl_robot *r)
{
    if (r->len > 0 && r->line[r->len - 1] != ' ' && r->line[r->len - 1] != ',' &&
        !memchr(r->line, ' ', r->len))
        put(r, " ", 1);
}

static fbrl_status w_send_com(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char tok[8];
    const char *text = NULL;
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++) {
        const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)c);
        if (ci->token && ci->token == v[0].i) {
            fbrl_rapl_form form = FBRL_RAPL_KEYWORD;
            if (r->link)
                (void)fbrl_link_get_form(r->link, &form);
            if (form == FBRL_RAPL_TOKEN) {
                snprintf(tok, sizeof tok, "/%03u", (unsigned)ci->token);
                text = tok;
            } else {
                text = ci->keyword;
            }
            break;
        }
    }
    if (!text) {
        char msg[80];
        snprintf(msg, sizeof msg, "%s: no RAPL command has the number %ld", w->name, (long)v[0].i);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    r->len = 0;
    r->line[0] = '\0';
    r->line_bad = 0;
    return put(r, text, strlen(text));
}

static fbrl_status w_send_real(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char buf[32];
    size_t n;
    fbrl_status st = fbrl_rapl_format_real(buf, sizeof buf, &n, v[0].f);
    if (st != FBRL_OK)
        return rb_fail_st(r, w, st, NULL);
    sep(r);
    return put(r, buf, n);
}

static fbrl_status w_send_int(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char buf[32];
    (void)w;
    int n = snprintf(buf, sizeof buf, "%ld", (long)v[0].i);
    sep(r);
    return put(r, buf, (size_t)n);
}

static fbrl_status w_send_text(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    for (size_t k = 0; k < v[0].n; k++)
        if (v[0].s[k] < 0x20 || v[0].s[k] > 0x7e || v[0].s[k] == '?')
            return rb_fail(r, FBRL_THROW_BAD_NUMBER, "SEND-TEXT: only printable characters (no '?')");
    (void)w;
    sep(r);
    return put(r, v[0].s, v[0].n);
}

static fbrl_status w_send_const(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    (void)v;
    return put(r, (const char *)w->arg, strlen((const char *)w->arg));
}

/* SEND-LOC ( loc -- ): the six components, mapped like every outgoing location */
static fbrl_status w_send_loc(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_loc user, arm;
    fbrl_status st = rb_loc_read(r, w, v[0].i, &user);
    if (st == FBRL_OK)
        st = rb_to_arm(r, w, &user, &arm);
    if (st != FBRL_OK)
        return st;
    const double c[6] = {arm.x, arm.y, arm.z, arm.o, arm.a, arm.t};
    sep(r);
    for (int k = 0; k < 6; k++) {
        char buf[32];
        size_t n;
        if ((st = fbrl_rapl_format_real(buf, sizeof buf, &n, c[k])) != FBRL_OK)
            return rb_fail_st(r, w, st, NULL);
        if (k)
            put(r, ",", 1);
        put(r, buf, n);
    }
    return FBRL_OK;
}

static fbrl_status w_send_cr(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char line[FBRL_LINK_LINE_MAX + 1];
    int bad = r->line_bad;
    (void)v;
    memcpy(line, r->line, r->len + 1);
    size_t n = r->len;
    r->len = 0;
    r->line[0] = '\0';
    r->line_bad = 0;
    if (bad)
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "SEND-CR: the line grew past 80 characters");
    if (n == 0)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, "SEND-CR: nothing to send (start with SEND-COM)");
    return rb_raw(r, w, line, 1);
}

const rb_word rb_line_words[] = {
    /* I-8 */
    {"SEND-COM", w_send_com, "I", 0, -1, 0,
     FBRL_DOC("( command# -- )", "start a command line with the RAPL command of that number")},
    {"SEND-REAL", w_send_real, "R", 0, -1, 0, FBRL_DOC("( F: r -- )", "add a real to the command line")},
    {"SEND-INT", w_send_int, "I", 0, -1, 0, FBRL_DOC("( n -- )", "add an integer to the command line")},
    {"SEND-TEXT", w_send_text, "S", 0, -1, 1,
     FBRL_DOC("( c-addr u -- )", "add a name or text to the command line")},
    {"SEND-COMMA", w_send_const, "", 0, -1, (intptr_t) ",",
     FBRL_DOC("( -- )", "add a comma to the command line")},
    {"SEND-STRT", w_send_const, "", 0, -1, (intptr_t) ",S",
     FBRL_DOC("( -- )", "add the straight-line suffix ,S")},
    {"SEND-LOC", w_send_loc, "L", 0, -1, 0,
     FBRL_DOC("( loc -- )", "add a location's six components (mapped)")},
    {"SEND-CR", w_send_cr, "", 0, -1, 0,
     FBRL_DOC("( -- )", "send the command line (echo-verified) and show its output")},
};
const size_t rb_line_nwords = sizeof rb_line_words / sizeof rb_line_words[0];
