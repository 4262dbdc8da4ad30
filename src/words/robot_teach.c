/* robot_teach.c - GET-CAL-POINTS: the three calibration points taught with the arm,
 * each after the input lines that bring the arm there. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* GET-CAL-POINTS ( cal -- ): teach slots 1..3 from the arm's position. For each slot
 * the lines that follow in the current input (a file, or evaluated text; at the end of
 * it, console lines) are run as FBRL until an empty line takes the point. The points
 * are physical arm positions (never mapped: they define the mapping); SET-CAL stores
 * them, all three only when all were taken. */
static fbrl_status next_line(fbrl_robot *r, const rb_word *w, int slot, int *asked, size_t *len)
{
    fbrl_vm *vm = r->vm;
    const fbrl_vm_host *host = fbrl_vmx_host(vm);
    char *buf = (char *)r->tib;
    const char *line;
    size_t n = 0;
    fbrl_status st = fbrl_vmx_refill(vm, &line, &n);
    if (st == FBRL_OK) {
        if (n > FBRL_ROBOT_TIB) n = FBRL_ROBOT_TIB;
        memcpy(buf, line, n);
        *len = n;
        return FBRL_OK;
    }
    if (st != FBRL_EEOF) return st;
    if (!host->key) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: input ended before point %d was taken", w->name, slot);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    /* Ask only a person: lines taken from a plan (file or text) need no prompt. */
    if (!*asked) {
        char ask[128];
        snprintf(ask, sizeof ask, "Calibration point %d: move the arm there (robot words), then an empty line takes it.\n", slot);
        rb_puts(r, ask);
        *asked = 1;
    }
    n = 0;
    for (;;) {
        int c = host->key(host->user);
        if (c < 0) {
            char msg[96];
            snprintf(msg, sizeof msg, "%s: input ended before point %d was taken", w->name, slot);
            return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
        }
        if (c == '\n' || c == '\r') break;
        if (n < FBRL_ROBOT_TIB) buf[n++] = (char)c;
    }
    *len = n;
    return FBRL_OK;
}

static fbrl_status teach3(fbrl_robot *r, const rb_word *w, fbrl_loc pts[3]);

static fbrl_status w_get_cal_points(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_vm *vm = r->vm;
    fbrl_loc pts[3];
    fbrl_calpts *cal;
    char msg[128];
    fbrl_status st = fbrl_glossary_calpts(vm, v[0].i, &cal);
    if (st != FBRL_OK) {
        snprintf(msg, sizeof msg, "%s: not a calibration (use a CREATE-CAL name)", w->name);
        return rb_fail(r, st == FBRL_ETYPE ? FBRL_THROW_TYPE_MISMATCH : -9, msg);
    }
    if ((st = rb_online(r)) != FBRL_OK) return st;
    if (r->teaching) return rb_fail(r, FBRL_THROW_BAD_NUMBER, "GET-CAL-POINTS: already teaching (not inside its own lines)");
    r->teaching = 1;
    st = teach3(r, w, pts);
    r->teaching = 0;
    if (st != FBRL_OK) return st;
    /* the lines run while teaching may have changed the dictionary: look the structure up again */
    if (fbrl_glossary_calpts(vm, v[0].i, &cal) != FBRL_OK) return rb_fail(r, FBRL_THROW_BAD_ADDRESS, "GET-CAL-POINTS: calibration gone");
    for (int slot = 1; slot <= 3; slot++)
        if ((st = fbrl_calpts_set(cal, slot, &pts[slot - 1])) != FBRL_OK) return rb_fail_st(r, w, st, NULL);
    return FBRL_OK;
}

/* The three positions, each after the lines that bring the arm there. */
static fbrl_status teach3(fbrl_robot *r, const rb_word *w, fbrl_loc pts[3])
{
    fbrl_vm *vm = r->vm;
    fbrl_status st;
    for (int slot = 1; slot <= 3; slot++) {
        int asked = 0;
        for (;;) {
            size_t n = 0;
            if ((st = next_line(r, w, slot, &asked, &n)) != FBRL_OK) return st;
            size_t k = 0;
            while (k < n && rb_blank(((char *)r->tib)[k])) k++;
            if (k == n) break;
            if ((st = fbrl_vmx_evaluate(vm, (const char *)r->tib, n)) != FBRL_OK) return st;
        }
        fbrl_loc arm;
        if ((st = rb_arm_where(r, w, 1, &arm)) != FBRL_OK) return st;
        if ((st = rb_from_arm(r, w, &arm, &pts[slot - 1], 0)) != FBRL_OK) return st;
    }
    return FBRL_OK;
}

const rb_word rb_teach_words[] = {
    { "GET-CAL-POINTS", w_get_cal_points, "I", 0, -1, 0, "( cal -- )", "teach the 3 calibration points from the arm's positions" },
};
const size_t rb_teach_nwords = sizeof rb_teach_words / sizeof rb_teach_words[0];
