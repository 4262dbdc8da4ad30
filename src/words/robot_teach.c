/* SPDX-License-Identifier: MIT */
/* robot_teach.c - GET-CAL-POINTS: the three calibration points taught with the arm,
 * each after the input lines that bring the arm there.
 *
 * GET-CAL-POINTS ( cal -- ): teach slots 1..3 from the arm's position. For each slot the
 * lines that follow in the current input (a file, or evaluated text) are run as FBRL
 * until an empty line takes the point. At the end of that input the lines come from the
 * console, with the host's line editing (fbrl_vm_host.read_line; else keys one by one),
 * and there the procedure is forgiving (docs/robot.md "GET-CAL-POINTS"):
 *   - a line that fails is reported and the same point is asked again;
 *   - TEACH alone runs the host's keyboard pendant ((TEACH), fbrlmon's): Enter there
 *     takes the point, Esc comes back to the same point;
 *   - BACK asks the point before again; CANCEL or Ctrl-C leaves, nothing changed.
 * The points are physical arm positions (never mapped: they define the mapping); SET-CAL
 * stores them, all three only when all were taken. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "fbrl/num.h"

#include "robot_internal.h"

/* The scratch location (TEACH's) and the text that runs the pendant share the line
 * buffer (the line itself is not needed any more then). */
#define TEACH_TEXT_AT 64

static const char *const slot_what[3] = {"P1, the block's origin", "P2, on the block's x axis",
                                         "P3, in the block's plane off that axis"};

enum { FROM_INPUT = 1, FROM_CONSOLE = 2 };

static fbrl_status ended(fbrl_robot *r, const rb_word *w, int slot)
{
    char msg[128];
    snprintf(msg, sizeof msg, "%s: input ended before point %d was taken (the calibration is unchanged)",
             w->name, slot);
    return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
}

static fbrl_status cancelled(fbrl_robot *r, const rb_word *w, const char *how)
{
    char msg[128];
    snprintf(msg, sizeof msg, "%s cancelled%s: the calibration is unchanged", w->name, how);
    return rb_fail(r, FBRL_THROW_INTERRUPT, msg);
}

/* The next line into the line buffer: *from = FROM_INPUT (the file or text) or
 * FROM_CONSOLE. The point's question is asked the first time the console is read. */
static fbrl_status next_line(fbrl_robot *r, const rb_word *w, int slot, int *asked, size_t *len, int *from)
{
    fbrl_vm *vm = r->vm;
    const fbrl_vm_host *host = fbrl_vmx_host(vm);
    char *buf = (char *)r->tib;
    const char *line;
    size_t n = 0;
    fbrl_status st = fbrl_vmx_refill(vm, &line, &n);
    if (st == FBRL_OK) {
        if (n > FBRL_ROBOT_TIB)
            n = FBRL_ROBOT_TIB;
        memcpy(buf, line, n);
        *len = n;
        *from = FROM_INPUT;
        return FBRL_OK;
    }
    if (st != FBRL_EEOF)
        return st;
    if (!host->read_line && !host->key)
        return ended(r, w, slot);
    *from = FROM_CONSOLE;
    if (!*asked) {
        char ask[200];
        snprintf(ask, sizeof ask,
                 "Calibration point %d of 3 (%s): move the arm there with robot words or TEACH, "
                 "then an empty line takes it.%s\n",
                 slot, slot_what[slot - 1],
                 slot == 1 ? " BACK redoes the point before; CANCEL or Ctrl-C leaves." : "");
        rb_puts(r, ask);
        *asked = 1;
    }
    if (host->read_line) {
        char prompt[16];
        snprintf(prompt, sizeof prompt, "cal %d> ", slot);
        st = host->read_line(host->user, prompt, buf, FBRL_ROBOT_TIB, &n);
        if (fbrl_vmx_take_interrupt(vm))
            return cancelled(r, w, " by Ctrl-C");
        if (st != FBRL_OK)
            return ended(r, w, slot);
        *len = n < FBRL_ROBOT_TIB ? n : FBRL_ROBOT_TIB;
        return FBRL_OK;
    }
    for (;;) {
        int c = host->key(host->user);
        if (fbrl_vmx_take_interrupt(vm))
            return cancelled(r, w, " by Ctrl-C");
        if (c < 0)
            return ended(r, w, slot);
        if (c == '\n' || c == '\r')
            break;
        if (n < FBRL_ROBOT_TIB)
            buf[n++] = (char)c;
    }
    *len = n;
    return FBRL_OK;
}

/* The line, blanks trimmed, is exactly word (any case). */
static int is_cmd(const char *s, size_t n, const char *word)
{
    size_t k = strlen(word);
    while (n && rb_blank(*s))
        s++, n--;
    while (n && rb_blank(s[n - 1]))
        n--;
    if (n != k)
        return 0;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (c >= 'a' && c <= 'z')
            c = (char)(c - 'a' + 'A');
        if (c != word[i])
            return 0;
    }
    return 1;
}

/* A console line that failed: say why; the point is asked again. */
static void failed_line(fbrl_robot *r, int slot, const char *msg)
{
    char line[200];
    snprintf(line, sizeof line, "error: %s (point %d again)\n", msg, slot);
    rb_puts(r, line);
}

/* TEACH at the point's prompt: the host's pendant on the scratch location. 1 = Enter
 * took a position, 0 = not (Esc, or an error that was reported), or an exception. */
static fbrl_status pendant(fbrl_robot *r, const rb_word *w, int slot, int *took)
{
    fbrl_vm *vm = r->vm;
    char msg[128], *text = (char *)r->tib + TEACH_TEXT_AT;
    int code = 0;
    size_t n = (size_t)snprintf(text, FBRL_ROBOT_TIB - TEACH_TEXT_AT, "#%ld (TEACH)", (long)r->tib);
    fbrl_status st = fbrl_vmx_evaluate_catch(vm, text, n, &code, msg, sizeof msg);
    *took = 0;
    if (st != FBRL_OK)
        return st;
    if (code == FBRL_THROW_INTERRUPT)
        return cancelled(r, w, " by Ctrl-C");
    if (code) {
        failed_line(r, slot, msg);
        return FBRL_OK;
    }
    fbrl_vmx_val res[2]; /* what (TEACH) left: ( loc flag ) */
    if ((st = fbrl_vmx_args(vm, w->name, "AI", NULL, FBRL_VMX_STACKS, res)) != FBRL_OK)
        return st;
    *took = res[1].i != 0;
    return FBRL_OK;
}

/* Where the arm is, as point `slot`; on the console it is shown. */
static fbrl_status take(fbrl_robot *r, const rb_word *w, int slot, int from, fbrl_loc *pt)
{
    fbrl_loc arm;
    fbrl_status st;
    if ((st = rb_arm_where(r, w, 1, &arm)) != FBRL_OK)
        return st;
    if ((st = rb_from_arm(r, w, &arm, pt, 0)) != FBRL_OK)
        return st;
    if (from == FROM_CONSOLE) {
        char line[160], x[24], y[24], z[24]; /* "%+.4f": the firmware's printf has no %f */
        fbrl_num_fixed(x, sizeof x, pt->x, 0, 4, FBRL_NUM_PLUS, NULL);
        fbrl_num_fixed(y, sizeof y, pt->y, 0, 4, FBRL_NUM_PLUS, NULL);
        fbrl_num_fixed(z, sizeof z, pt->z, 0, 4, FBRL_NUM_PLUS, NULL);
        snprintf(line, sizeof line, "point %d taken: X %s Y %s Z %s in\n", slot, x, y, z);
        rb_puts(r, line);
    }
    return FBRL_OK;
}

/* The three positions, each after the lines that bring the arm there. */
static fbrl_status teach3(fbrl_robot *r, const rb_word *w, fbrl_loc pts[3])
{
    fbrl_vm *vm = r->vm;
    fbrl_status st;
    char msg[128];
    int slot = 1, asked = 0;
    while (slot <= 3) {
        size_t n = 0;
        int from = 0, code = 0, took = 0;
        if ((st = next_line(r, w, slot, &asked, &n, &from)) != FBRL_OK)
            return st;
        const char *line = (const char *)r->tib;
        size_t k = 0;
        while (k < n && rb_blank(line[k]))
            k++;
        if (k == n) { /* an empty line takes the point */
            if ((st = take(r, w, slot, from, &pts[slot - 1])) != FBRL_OK)
                return st;
            slot++, asked = 0;
            continue;
        }
        if (from == FROM_INPUT) { /* a plan's line: an error ends the plan, as anywhere in it */
            if ((st = fbrl_vmx_evaluate(vm, line, n)) != FBRL_OK)
                return st;
            continue;
        }
        if (is_cmd(line, n, "CANCEL"))
            return cancelled(r, w, "");
        if (is_cmd(line, n, "BACK")) {
            if (slot > 1)
                slot--;
            asked = 0;
            continue;
        }
        if (is_cmd(line, n, "TEACH") && fbrl_vmx_find(vm, "(TEACH)", 7, &(fbrl_cell){0}) == FBRL_OK) {
            if ((st = pendant(r, w, slot, &took)) != FBRL_OK)
                return st;
            if (took) {
                if ((st = take(r, w, slot, from, &pts[slot - 1])) != FBRL_OK)
                    return st;
                slot++, asked = 0;
            }
            continue;
        }
        if ((st = fbrl_vmx_evaluate_catch(vm, line, n, &code, msg, sizeof msg)) != FBRL_OK)
            return st;
        if (code == FBRL_THROW_INTERRUPT)
            return cancelled(r, w, " by Ctrl-C");
        if (code)
            failed_line(r, slot, msg);
    }
    return FBRL_OK;
}

static fbrl_status w_get_cal_points(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_loc pts[3];
    fbrl_calpts *cal;
    char msg[128];
    fbrl_status st = fbrl_glossary_calpts(vm, v[0].i, &cal);
    if (st != FBRL_OK) {
        snprintf(msg, sizeof msg, "%s: not a calibration (use a CREATE-CAL name)", w->name);
        return rb_fail(r, st == FBRL_ETYPE ? FBRL_THROW_TYPE_MISMATCH : -9, msg);
    }
    if ((st = rb_online(r)) != FBRL_OK)
        return st;
    if (r->teaching)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER,
                       "GET-CAL-POINTS: already teaching (not inside its own lines)");
    r->teaching = 1;
    st = teach3(r, w, pts);
    r->teaching = 0;
    if (st != FBRL_OK)
        return st;
    /* the lines run while teaching may have changed the dictionary: look the structure up again */
    if (fbrl_glossary_calpts(vm, v[0].i, &cal) != FBRL_OK)
        return rb_fail(r, FBRL_THROW_BAD_ADDRESS, "GET-CAL-POINTS: calibration gone");
    for (int slot = 1; slot <= 3; slot++)
        if ((st = fbrl_calpts_set(cal, slot, &pts[slot - 1])) != FBRL_OK)
            return rb_fail_st(r, w, st, NULL);
    return FBRL_OK;
}

const rb_word rb_teach_words[] = {
    {"GET-CAL-POINTS", w_get_cal_points, "I", 0, -1, 0,
     FBRL_DOC("( cal -- )",
              "teach the 3 calibration points from the arm's positions (at the console: TEACH, BACK, CANCEL; "
              "docs/robot.md)")},
};
const size_t rb_teach_nwords = sizeof rb_teach_words / sizeof rb_teach_words[0];
