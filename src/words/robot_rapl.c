/* SPDX-License-Identifier: MIT */
/* robot_rapl.c - thesis I-5 words that show the controller's text (W0..WE5, STATUS,
 * SERIAL), configure its serial channel, and read and set its variables and locations. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/num.h"
#include "robot_internal.h"

static fbrl_status w_config(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    static const long bauds[] = {300, 600, 1200, 2400, 4800, 9600, 19200, 38400};
    const char *par = NULL, *hs = NULL;
    size_t k;
    fbrl_status st = rb_range(r, w, "device", v[0].i, 0, 1);
    for (k = 0; st == FBRL_OK && k < sizeof bauds / sizeof bauds[0] && bauds[k] != v[1].i; k++)
        ;
    if (st == FBRL_OK && k == sizeof bauds / sizeof bauds[0])
        st = rb_fail(r, FBRL_THROW_BAD_NUMBER, "CONFIG: baud must be 300..38400 (a standard rate)");
    switch (v[2].i) {
    case 'N':
    case 'n': par = "N"; break;
    case 'E':
    case 'e': par = "E"; break;
    case 'O':
    case 'o': par = "O"; break;
    default: break;
    }
    switch (v[5].i) {
    case 'N':
    case 'n':
    case 0: hs = "N"; break;
    case 'X':
    case 'x':
    case 1:
    case -1: hs = "X"; break;
    default: break;
    }
    if (st == FBRL_OK && !par)
        st = rb_fail(r, FBRL_THROW_BAD_NUMBER, "CONFIG: parity must be the character N, E or O");
    if (st == FBRL_OK)
        st = rb_range(r, w, "data bits", v[3].i, 7, 8);
    if (st == FBRL_OK)
        st = rb_range(r, w, "stop bits", v[4].i, 1, 2);
    if (st == FBRL_OK && !hs)
        st = rb_fail(r, FBRL_THROW_BAD_NUMBER, "CONFIG: handshake must be N or X (or 0 / 1)");
    if (st == FBRL_OK)
        st = rb_range(r, w, "echo", v[6].i, -1, 1);
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a[7] = {fbrl_rapl_int((long)v[0].i),  fbrl_rapl_int((long)v[1].i), fbrl_rapl_str(par),
                          fbrl_rapl_int((long)v[3].i),  fbrl_rapl_int((long)v[4].i), fbrl_rapl_str(hs),
                          fbrl_rapl_int(v[6].i ? 1 : 0)};
    return rb_cmd(r, w, FBRL_RAPL_CONFIG, a, 7, 0);
}

/* The WORLD numbers of a position block, read as it is shown. */
static void parse_block(void *ctx, const char *line, size_t len, int flawed)
{
    fbrl_rapl_pos *p = ctx;
    if (!flawed)
        (void)fbrl_rapl_pos_line(p, line, len);
}

/* W0 W2 W4 ROBOT-STATUS SERIAL: the controller's text on the console, once (rb_show).
 * A position block is followed by its WORLD numbers with their names, in the user's
 * units (cm with METRIC-ON), from the controller's (millimetres when the link knows it
 * works in them, docs/link.md 1); the yaw is marked as the arm's own: a 5-axis arm
 * cannot choose it, it is the waist's direction (DESIGN 6). */
static fbrl_status w_show(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    (void)v;
    fbrl_rapl_cmd cmd = (fbrl_rapl_cmd)w->code;
    int pos = cmd == FBRL_RAPL_W0 || cmd == FBRL_RAPL_W2 || cmd == FBRL_RAPL_W4;
    fbrl_rapl_pos p;
    fbrl_rapl_pos_init(&p);
    fbrl_status st = rb_show(r, w, fbrl_rapl_cmd_info(cmd)->keyword, pos ? parse_block : NULL, &p);
    if (st != FBRL_OK || !pos || p.nworld < 6)
        return st;
    int metric = rb_metric(r);
    double k = metric ? FBRL_CM_PER_IN : 1.0;
    if (fbrl_link_units(r->link) == FBRL_LINK_UNITS_MM)
        k /= 10.0 * FBRL_CM_PER_IN; /* the block's lengths are millimetres */
    char out[256], f[6][24]; /* "%+.4f" "%+.3f" through fbrl_num_fixed: the firmware's printf has no %f */
    for (int i = 0; i < 6; i++)
        fbrl_num_fixed(f[i], sizeof f[i], i < 3 ? p.world[i] * k : p.world[i], 0, i < 3 ? 4 : 3,
                       FBRL_NUM_PLUS, NULL);
    snprintf(out, sizeof out, "world: X %s Y %s Z %s %s  yaw %s (the arm's own)  pitch %s  roll %s deg\n",
             f[0], f[1], f[2], metric ? "cm" : "in", f[3], f[4], f[5]);
    rb_puts(r, out);
    return FBRL_OK;
}

/* W1 W3 W5 WE1 WE3 WE5: FBRL_ROBOT_STREAM_LINES readings, then the stream is stopped */
static fbrl_status w_stream(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    (void)v;
    return rb_stream(r, w, (fbrl_rapl_cmd)w->code);
}

/* TYPEINT / TYPEREAL ( string -- ): print a controller variable */
static fbrl_status w_typevar(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[16], out[48];
    fbrl_status st = rb_name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    if (w->arg) {
        double d;
        if ((st = rb_link_result(r, w, fbrl_link_typev(r->link, name, &d))) != FBRL_OK)
            return st;
        if (w->arg == 2)
            return fbrl_vm_fpush(r->vm, d) == FBRL_OK ? FBRL_OK
                                                      : rb_fail(r, FBRL_THROW_FSTACK_OVERFLOW, NULL);
        fbrl_num_fixed(out, sizeof out - 1, d, 0, 6, 0, NULL); /* "%.6f", whatever the locale */
        strcat(out, " ");
    } else {
        long i;
        if ((st = rb_link_result(r, w, fbrl_link_typei(r->link, name, &i))) != FBRL_OK)
            return st;
        if (w->code == 1)
            return fbrl_vm_push(r->vm, (fbrl_cell)i) == FBRL_OK ? FBRL_OK
                                                                : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
        snprintf(out, sizeof out, "%ld ", i);
    }
    rb_puts(r, out);
    return FBRL_OK;
}

/* RAPL ( PAR: text ) or ( c-addr u -- ): a line straight to the controller */
static fbrl_status w_rapl(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char line[FBRL_LINK_LINE_MAX + 1];
    if (v[0].n == 0 || v[0].n > FBRL_LINK_LINE_MAX)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, "RAPL: the line must be 1..80 characters");
    memcpy(line, v[0].s, v[0].n);
    line[v[0].n] = '\0';
    return rb_raw(r, w, line, 1);
}

/* SET-RAPL-REAL ( PAR: name value ), SET-RAPL-INT */
static fbrl_status w_set_var(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[16];
    fbrl_status st = rb_name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK && w->arg)
        st = rb_finite(r, w, &v[1], 1);
    if (st != FBRL_OK)
        return st;
    if (!w->arg) { /* the encoder writes every value as a real; an integer goes as typed */
        char line[40];
        if (fbrl_rapl_name_check(name, 0) != FBRL_OK)
            return rb_fail_st(r, w, FBRL_ENAME, name);
        snprintf(line, sizeof line, "%s=%ld", name, (long)v[1].i);
        return rb_raw(r, w, line, 0);
    }
    fbrl_rapl_arg a[2] = {fbrl_rapl_str(name), fbrl_rapl_real(v[1].f)};
    return rb_cmd(r, w, FBRL_RAPL_ASSIGN, a, 2, 0);
}

/* RAPL-ANALOG ( PAR: input# variable ): the controller reads A/D channel n into a
 * variable with `NAME=ADC(n)` (ADC is our decision; see docs/rapl-commands.md). */
static fbrl_status w_analog(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[16], line[40];
    fbrl_status st = rb_name_arg(r, w, &v[1], name, 10);
    if (st != FBRL_OK)
        return st;
    if (v[0].i < 1 || v[0].i > 8)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, "RAPL-ANALOG: the analog input must be 1..8");
    if (fbrl_rapl_name_check(name, 0) != FBRL_OK)
        return rb_fail_st(r, w, FBRL_ENAME, name);
    snprintf(line, sizeof line, "%s=ADC(%ld)", name, (long)v[0].i);
    return rb_raw(r, w, line, 0);
}

/* RAPL-HERE, RAPL-RUN ( PAR: name ) */
static fbrl_status w_name1(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[16];
    fbrl_status st = rb_name_arg(r, w, &v[0], name, 10);
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a = fbrl_rapl_str(name);
    if (w->code == FBRL_RAPL_RUN) { /* a program may move the arm: the guard cannot follow it */
        fbrl_robot_move m;
        rb_out o;
        memset(&m, 0, sizeof m);
        m.kind = FBRL_ROBOT_MOVE_OTHER;
        memset(&o, 0, sizeof o);
        o.cmd = FBRL_RAPL_RUN, o.a = &a, o.n = 1;
        return rb_motion(r, w, &m, &o);
    }
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->code, &a, 1, 0);
}

/* RAPL-SET, RAPL-SHIFTA ( PAR: loc1 loc2 ) */
static fbrl_status w_name2(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char a1[16], a2[16];
    fbrl_status st = rb_name_arg(r, w, &v[0], a1, 10);
    if (st == FBRL_OK)
        st = rb_name_arg(r, w, &v[1], a2, 10);
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a[2] = {fbrl_rapl_str(a1), fbrl_rapl_str(a2)};
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->code, a, 2, 0);
}

/* RAPL-POINT ( PAR: rapl-loc fbrl-loc ): define a controller location from a host one */
static fbrl_status w_rapl_point(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[16];
    fbrl_loc user, arm;
    fbrl_status st = rb_name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK && name[0] == '#')
        st = rb_fail(r, FBRL_THROW_BAD_NUMBER, "RAPL-POINT: a host location is cartesian: no '#' name");
    if (st == FBRL_OK)
        st = rb_loc_read(r, w, v[1].i, &user);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st == FBRL_OK)
        st = rb_to_arm(r, w, &user, &arm);
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a[7] = {fbrl_rapl_str(name),   fbrl_rapl_real(arm.x), fbrl_rapl_real(arm.y),
                          fbrl_rapl_real(arm.z), fbrl_rapl_real(arm.o), fbrl_rapl_real(arm.a),
                          fbrl_rapl_real(arm.t)};
    return rb_cmd(r, w, FBRL_RAPL_POINT, a, 7, 0);
}

/* RAPL-ERROR ( -- n ) */
static fbrl_status w_rapl_error(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    (void)w;
    (void)v;
    return fbrl_vm_push(r->vm, r->last_error) == FBRL_OK ? FBRL_OK
                                                         : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

#define CMD(x) FBRL_RAPL_##x
const rb_word rb_rapl_words[] = {
    /* I-5 display */
    {"W0", w_show, "", 0, CMD(W0), 0,
     FBRL_DOC("( -- )", "show the commanded position (pulses, joints, world)")},
    {"W1", w_stream, "", 0, CMD(W1), 0,
     FBRL_DOC("( -- )", "show the actual position in pulses, 10 readings")},
    {"W2", w_show, "", 0, CMD(W2), 0, FBRL_DOC("( -- )", "show the actual position (pulses, joints, world)")},
    {"W3", w_stream, "", 0, CMD(W3), 0,
     FBRL_DOC("( -- )", "show the commanded position in pulses, 10 readings")},
    {"W4", w_show, "", 0, CMD(W4), 0, FBRL_DOC("( -- )", "show the end point of the current path")},
    {"W5", w_stream, "", 0, CMD(W5), 0, FBRL_DOC("( -- )", "show the velocity, 10 readings")},
    {"WE1", w_stream, "", 0, CMD(WE1), 0,
     FBRL_DOC("( -- )", "show the extra axis's actual position, 10 readings")},
    {"WE3", w_stream, "", 0, CMD(WE3), 0,
     FBRL_DOC("( -- )", "show the extra axis's commanded position, 10 readings")},
    {"WE5", w_stream, "", 0, CMD(WE5), 0, FBRL_DOC("( -- )", "show the extra axis's velocity, 10 readings")},
    {"ROBOT-STATUS", w_show, "", 0, CMD(STATUS), 0, FBRL_DOC("( -- )", "show the controller's STATUS block")},
    {"SERIAL", w_show, "", 0, CMD(SERIAL), 0, FBRL_DOC("( -- )", "show the controller's serial settings")},
    {"CONFIG", w_config, "IICIICI", 0, -1, 0,
     FBRL_DOC("( dev baud parity #data #stop handshake echo -- )", "configure a controller serial channel")},
    /* I-5 controller variables and locations */
    {"TYPEINT", w_typevar, "S", 0, 0, 0,
     FBRL_DOC("( c-addr u -- ) or ( PAR: variable )", "print a controller variable as an integer")},
    {"TYPEREAL", w_typevar, "S", 0, 0, 1,
     FBRL_DOC("( c-addr u -- ) or ( PAR: variable )", "print a controller variable as a real")},
    {"RAPL-INT@", w_typevar, "S", 0, 1, 0,
     FBRL_DOC("( c-addr u -- n )", "a controller variable's value as an integer")},
    {"RAPL-REAL@", w_typevar, "S", 0, 0, 2,
     FBRL_DOC("( c-addr u -- ) ( F: -- r )", "a controller variable's value as a real")},
    {"RAPL", w_rapl, "T", 0, -1, 0,
     FBRL_DOC("( PAR: text ) or ( c-addr u -- )", "send a line to the controller as it is; show its output")},
    {"SET-RAPL-REAL", w_set_var, "SR", 0, -1, 1,
     FBRL_DOC("( PAR: variable value ) or ( c-addr u -- ) ( F: r -- )",
              "set a controller variable to a real")},
    {"SET-RAPL-INT", w_set_var, "SI", 0, -1, 0,
     FBRL_DOC("( PAR: variable value ) or ( c-addr u n -- )", "set a controller variable to an integer")},
    {"RAPL-ANALOG", w_analog, "IS", 0, -1, 0,
     FBRL_DOC("( PAR: input# variable ) or ( n c-addr u -- )",
              "read analog input n (1..8, volts) into a controller variable")},
    {"RAPL-HERE", w_name1, "S", 0, CMD(HERE), 0,
     FBRL_DOC("( PAR: name ) or ( c-addr u -- )", "store the arm's position in a controller location")},
    {"RAPL-RUN", w_name1, "S", 0, CMD(RUN), 0,
     FBRL_DOC("( PAR: program ) or ( c-addr u -- )", "run a RAPL program stored in the controller")},
    {"RAPL-SET", w_name2, "SS", 0, CMD(SET), 0,
     FBRL_DOC("( PAR: loc1 loc2 ) or ( c-addr1 u1 c-addr2 u2 -- )", "controller location loc1 := loc2")},
    {"RAPL-SHIFTA", w_name2, "SS", 0, CMD(SHIFTA), 0,
     FBRL_DOC("( PAR: loc1 loc2 ) or ( c-addr1 u1 c-addr2 u2 -- )",
              "shift controller location loc1 by loc2's components")},
    {"RAPL-POINT", w_rapl_point, "SL", 0, -1, 0,
     FBRL_DOC("( PAR: rapl-loc fbrl-loc ) or ( c-addr u loc -- )",
              "define a controller location from a host location (mapped)")},
    {"RAPL-ERROR", w_rapl_error, "", 0, -1, 0,
     FBRL_DOC("( -- n )", "code of the controller's last error seen by a robot word (-1 none)")},
};
const size_t rb_rapl_nwords = sizeof rb_rapl_words / sizeof rb_rapl_words[0];
