/* SPDX-License-Identifier: MIT */
/* robot_motion.c - thesis I-5 robot commands: motion to host locations (a scratch
 * controller point, then the move), joint and motor moves, positions read back, arm
 * state, gripper and numbered I/O. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* ---- I-5 robot commands ---- */

/* Commands without parameters (HOME, READY, HALT, FINISH ...). */
static fbrl_status w_plain(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_move m;
    rb_out o;
    (void)v;
    if (w->code != FBRL_RAPL_READY && w->code != FBRL_RAPL_HOME && w->code != FBRL_RAPL_ALIGN)
        return rb_cmd(r, w, (fbrl_rapl_cmd)w->code, NULL, 0, 0); /* HALT: the link's gate notes it */
    memset(&m, 0, sizeof m);
    m.kind = w->code == FBRL_RAPL_READY  ? FBRL_ROBOT_MOVE_READY
             : w->code == FBRL_RAPL_HOME ? FBRL_ROBOT_MOVE_HOME
                                         : FBRL_ROBOT_MOVE_OTHER;
    memset(&o, 0, sizeof o);
    o.cmd = (fbrl_rapl_cmd)w->code;
    return rb_motion(r, w, &m, &o);
}

/* One axis / number. arg: 0 plain; 1 axis 1..n with 0 = all (no argument sent);
 * 2 axis 1..n; 3 extra axis 1..8; 4 SPEED 1..100; 5 FLASH interval >= 0 (n: the arm's axes). */
static fbrl_status w_int1(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = FBRL_OK;
    switch (w->arg) {
    case 1: st = rb_range(r, w, "axis", v[0].i, 0, (fbrl_cell)rb_naxes(r)); break;
    case 2: st = rb_range(r, w, "axis", v[0].i, 1, (fbrl_cell)rb_naxes(r)); break;
    case 3: st = rb_range(r, w, "axis", v[0].i, 1, 8); break;
    case 4: st = rb_range(r, w, "speed", v[0].i, 1, 100); break;
    case 5: st = rb_range(r, w, "interval", v[0].i, 0, 32767); break;
    default: break;
    }
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a = fbrl_rapl_int((long)v[0].i);
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->code, &a, (w->arg == 1 && v[0].i == 0) ? 0 : 1, 0);
}

/* JOINT ( joint degrees -- ), MOTOR ( axis# #pulses -- ): the gripper's motor follows the
 * arm's joints. */
static fbrl_status w_joint(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_cell n = (fbrl_cell)rb_naxes(r);
    fbrl_status st = rb_range(r, w, w->code == FBRL_RAPL_MOTOR ? "motor" : "joint", v[0].i, 1,
                              w->code == FBRL_RAPL_MOTOR ? n + 1 : n);
    if (st == FBRL_OK)
        st = rb_range(r, w, w->code == FBRL_RAPL_MOTOR ? "pulses" : "degrees", v[1].i, -2000000000L,
                      2000000000L);
    if (st != FBRL_OK)
        return st;
    fbrl_robot_move m;
    rb_out o;
    memset(&m, 0, sizeof m);
    if (w->code == FBRL_RAPL_MOTOR) {
        m.kind = FBRL_ROBOT_MOVE_MOTOR;
        m.v[0] = (double)v[0].i;
        m.v[1] = (double)v[1].i;
    } else {
        m.kind = FBRL_ROBOT_MOVE_DJOINTS;
        m.v[v[0].i - 1] = (double)v[1].i;
    }
    fbrl_rapl_arg a[2] = {fbrl_rapl_int((long)v[0].i), w->code == FBRL_RAPL_MOTOR
                                                           ? fbrl_rapl_int((long)v[1].i)
                                                           : fbrl_rapl_real((double)v[1].i)};
    memset(&o, 0, sizeof o);
    o.cmd = (fbrl_rapl_cmd)w->code, o.a = a, o.n = 2;
    return rb_motion(r, w, &m, &o);
}

/* GAIN ( motor# -- | F: value ) */
static fbrl_status w_gain(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_range(r, w, "motor", v[0].i, 0, 8);
    if (st == FBRL_OK)
        st = rb_finite(r, w, &v[1], 1);
    if (st == FBRL_OK && v[1].f < 0)
        st = rb_fail(r, FBRL_THROW_BAD_NUMBER, "GAIN: value must not be negative");
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a[2] = {fbrl_rapl_int((long)v[0].i), fbrl_rapl_real(v[1].f)};
    return rb_cmd(r, w, FBRL_RAPL_GAIN, a, 2, 0);
}

/* GRIP ( torque -- | F: distance ): GRIP distance,torque */
static fbrl_status w_grip(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_range(r, w, "torque (% of full)", v[0].i, 1, 100);
    if (st == FBRL_OK)
        st = rb_finite(r, w, &v[1], 1);
    if (st != FBRL_OK)
        return st;
    double d = rb_len_in(r, v[1].f);
    if (d < 0)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, "GRIP: distance must not be negative");
    fbrl_rapl_arg a[2] = {fbrl_rapl_real(d), fbrl_rapl_int((long)v[0].i)};
    return rb_cmd(r, w, FBRL_RAPL_GRIP, a, 2, 0);
}

/* JOG ( F: dX dY dZ -- ), lengths in the user's units */
static fbrl_status w_jog(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_finite(r, w, v, 3);
    if (st != FBRL_OK)
        return st;
    fbrl_robot_move m;
    rb_out o;
    memset(&m, 0, sizeof m);
    m.kind = FBRL_ROBOT_MOVE_JOG;
    m.straight = 1;
    for (int k = 0; k < 3; k++)
        m.v[k] = rb_len_in(r, v[k].f);
    fbrl_rapl_arg a[3] = {fbrl_rapl_real(m.v[0]), fbrl_rapl_real(m.v[1]), fbrl_rapl_real(m.v[2])};
    memset(&o, 0, sizeof o);
    o.cmd = FBRL_RAPL_JOG, o.a = a, o.n = 3;
    return rb_motion(r, w, &m, &o);
}

/* MA / MI ( F: j1 .. jn -- ), one per axis of the arm; arg 1 = straight */
static fbrl_status w_joints(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    size_t n = rb_naxes(r);
    fbrl_status st = n <= FBRL_RAPL_ARM_AXES_MAX ? rb_finite(r, w, v, n) : FBRL_EINVAL;
    if (st != FBRL_OK)
        return st;
    fbrl_robot_move m;
    rb_out o;
    memset(&m, 0, sizeof m);
    m.kind = w->code == FBRL_RAPL_MA ? FBRL_ROBOT_MOVE_JOINTS : FBRL_ROBOT_MOVE_DJOINTS;
    m.straight = (int)w->arg;
    for (size_t k = 0; k < n && k < 6; k++)
        m.v[k] = v[k].f * (180.0 / 3.14159265358979323846);
    fbrl_rapl_arg a[FBRL_RAPL_ARM_AXES_MAX];
    for (size_t k = 0; k < n; k++)
        a[k] = fbrl_rapl_real(v[k].f);
    memset(&o, 0, sizeof o);
    o.cmd = (fbrl_rapl_cmd)w->code, o.a = a, o.n = n, o.straight = (int)w->arg;
    return rb_motion(r, w, &m, &o);
}

/* DEPART / DEPART-STRT ( F: distance -- ) */
static fbrl_status w_depart(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_finite(r, w, v, 1);
    if (st != FBRL_OK)
        return st;
    fbrl_robot_move m;
    rb_out o;
    memset(&m, 0, sizeof m);
    m.kind = FBRL_ROBOT_MOVE_DEPART;
    m.straight = (int)w->arg;
    m.dist = rb_len_in(r, v[0].f);
    fbrl_rapl_arg a = fbrl_rapl_real(m.dist);
    memset(&o, 0, sizeof o);
    o.cmd = FBRL_RAPL_DEPART, o.a = &a, o.n = 1, o.straight = (int)w->arg;
    return rb_motion(r, w, &m, &o);
}

/* The guard's view of a move to a location (at arm coordinates). */
static fbrl_robot_move *pose_move(fbrl_robot_move *m, const fbrl_loc *arm, double dist, int straight)
{
    memset(m, 0, sizeof *m);
    m->kind = FBRL_ROBOT_MOVE_POSE;
    m->straight = straight;
    m->v[0] = arm->x, m->v[1] = arm->y, m->v[2] = arm->z;
    m->v[3] = arm->o, m->v[4] = arm->a, m->v[5] = arm->t;
    m->dist = dist;
    return m;
}

/* MOV / MOV-STRT ( loc -- ): POINT scratch, then MOVE scratch[,S] */
static fbrl_status w_mov(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_loc user, arm;
    fbrl_robot_move m;
    fbrl_rapl_arg a[1];
    rb_out o;
    fbrl_status st = rb_loc_read(r, w, v[0].i, &user);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st == FBRL_OK)
        st = rb_to_arm(r, w, &user, &arm);
    if (st != FBRL_OK)
        return st;
    memset(&o, 0, sizeof o);
    o.cmd = FBRL_RAPL_MOVE, o.a = a, o.n = 1, o.straight = (int)w->arg, o.point = &arm;
    r->target = user, r->have_target = 1; /* what tell shows: the user's location */
    return rb_motion(r, w, pose_move(&m, &arm, 0.0, (int)w->arg), &o);
}

/* APPROACH / APPROACH-STRT ( loc -- | F: distance -- ) */
static fbrl_status w_approach(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_loc user, arm;
    fbrl_robot_move m;
    fbrl_rapl_arg a[2];
    rb_out o;
    fbrl_status st = rb_finite(r, w, &v[1], 1);
    if (st == FBRL_OK)
        st = rb_loc_read(r, w, v[0].i, &user);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st == FBRL_OK)
        st = rb_to_arm(r, w, &user, &arm);
    if (st != FBRL_OK)
        return st;
    pose_move(&m, &arm, rb_len_in(r, v[1].f), (int)w->arg);
    a[1] = fbrl_rapl_real(m.dist);
    memset(&o, 0, sizeof o);
    o.cmd = FBRL_RAPL_APPRO, o.a = a, o.n = 2, o.straight = (int)w->arg, o.point = &arm;
    /* above the location: no target shown */
    return rb_motion(r, w, &m, &o);
}

/* ARM-HERE ( loc -- ): wait for the motion to end, read W2, store it unmapped */
static fbrl_status w_arm_here(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_loc arm, user;
    fbrl_status st = rb_loc_write(r, w, v[0].i, NULL);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st == FBRL_OK)
        st = rb_arm_where(r, w, 1, &arm);
    if (st == FBRL_OK)
        st = rb_from_arm(r, w, &arm, &user, 1);
    if (st == FBRL_OK)
        st = rb_loc_write(r, w, v[0].i, &user);
    return st;
}

/* ACTUAL ( loc -- ) or ( PAR: controller-name ): the actual position now, into a host
 * location (unmapped) or, for a name that is no FBRL word, into the controller's location. */
static fbrl_status w_actual(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    if (v[0].s) {
        char name[16];
        fbrl_status st = rb_name_arg(r, w, &v[0], name, 10);
        if (st != FBRL_OK)
            return st;
        fbrl_rapl_arg a = fbrl_rapl_str(name);
        return rb_cmd(r, w, FBRL_RAPL_ACTUAL, &a, 1, 0);
    }
    fbrl_loc arm, user;
    fbrl_status st = rb_loc_write(r, w, v[0].i, NULL);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st == FBRL_OK)
        st = rb_arm_where(r, w, 0, &arm);
    if (st == FBRL_OK)
        st = rb_from_arm(r, w, &arm, &user, 1);
    if (st == FBRL_OK)
        st = rb_loc_write(r, w, v[0].i, &user);
    return st;
}

/* TOOL ( loc -- ): the tool transform is relative to the flange: never mapped */
static fbrl_status w_tool(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_loc t;
    const char *name;
    fbrl_status st = rb_loc_read(r, w, v[0].i, &t);
    if (st == FBRL_OK)
        st = rb_scratch_point(r, w, &t, &name);
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a = fbrl_rapl_str(name);
    return rb_cmd(r, w, FBRL_RAPL_TOOL, &a, 1, 0);
}

/* ARM ( flag -- ) */
static fbrl_status w_arm(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_rapl_arg a = fbrl_rapl_str(v[0].i ? "ON" : "OFF");
    return rb_cmd(r, w, FBRL_RAPL_ARM, &a, 1, 0);
}

/* CONFIG ( dev baud parity #data #stop handshake echo -- ) */

/* BASE-OFFSET ( F: dX dY dZ dO -- ): where the user's world frame sits on the arm */
static fbrl_status w_base_offset(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_finite(r, w, v, 4);
    if (st != FBRL_OK)
        return st;
    r->base[0] = rb_len_in(r, v[0].f);
    r->base[1] = rb_len_in(r, v[1].f);
    r->base[2] = rb_len_in(r, v[2].f);
    r->base[3] = v[3].f;
    return FBRL_OK;
}

/* SHIFT-RIGHT ( n -- n' b ) */
static fbrl_status w_shift_right(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    (void)w;
    fbrl_ucell u = (fbrl_ucell)v[0].i;
    fbrl_status st = fbrl_vm_push(r->vm, (fbrl_cell)(u >> 1));
    if (st == FBRL_OK)
        st = fbrl_vm_push(r->vm, (fbrl_cell)(u & 1u));
    return st == FBRL_OK ? FBRL_OK : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

/* OUTPORT ( output# -- ): output n on, -n off */
static fbrl_status w_outport(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_cell n = v[0].i < 0 ? -v[0].i : v[0].i;
    fbrl_status st = rb_range(r, w, "output", n, 1, FBRL_ROBOT_IO_MAX);
    if (st != FBRL_OK)
        return st;
    fbrl_rapl_arg a = fbrl_rapl_int((long)v[0].i);
    return rb_cmd(r, w, FBRL_RAPL_OUTPUT, &a, 1, 0);
}

/* OUT2BYTE ( n -- ): bit k of n sets output k+1 (16 outputs, two OUTPUT lines of 8) */
static fbrl_status w_out2byte(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_range(r, w, "value", v[0].i, 0, 0xFFFF);
    for (int half = 0; st == FBRL_OK && half < 2; half++) {
        fbrl_rapl_arg a[8];
        for (int k = 0; k < 8; k++) {
            int out = half * 8 + k + 1;
            a[k] = fbrl_rapl_int(((v[0].i >> (out - 1)) & 1) ? out : -out);
        }
        st = rb_cmd(r, w, FBRL_RAPL_OUTPUT, a, 8, 0);
    }
    return st;
}

/* WAITPORT ( input# -- ): RAPL WAIT: input n on, -n off; beside other tasks the host
 * polls the input instead, as long as the link would allow the controller's WAIT */
#define WAITPORT_POLL_MS 20u
#define WAITPORT_MAX_MS  120000u
static fbrl_status w_waitport(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_cell n = v[0].i < 0 ? -v[0].i : v[0].i;
    fbrl_status st = rb_range(r, w, "input", n, 1, FBRL_ROBOT_IO_MAX);
    if (st != FBRL_OK)
        return st;
    if (fbrl_vmx_tasking(r->vm)) { /* the controller's WAIT would hold the link: poll it here */
        uint64_t t0 = fbrl_vmx_wait_state(r->vm)->since_us;
        for (;;) {
            int on = 0;
            if ((st = rb_online(r)) != FBRL_OK ||
                (st = rb_link_result(r, w, fbrl_link_input(r->link, (int)n, &on))) != FBRL_OK)
                return st;
            if ((on != 0) == (v[0].i > 0))
                return FBRL_OK;
            uint64_t now = rb_now_us(r);
            if (now - t0 > (uint64_t)WAITPORT_MAX_MS * RB_US_PER_MS)
                return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ETIMEOUT),
                               "WAITPORT: the input never came (120 s)");
            if ((st = rb_pause_until(r, now + WAITPORT_POLL_MS * RB_US_PER_MS)) != FBRL_OK)
                return st;
        }
    }
    fbrl_rapl_arg a = fbrl_rapl_int((long)v[0].i);
    return rb_cmd(r, w, FBRL_RAPL_WAIT, &a, 1, 0);
}

/* W0 W2 W4: the link repeats a read-only query until query_reads replies agree and
 * hands over the lines of every reply; only the last block (the confirmed reading)
 * is kept for the console. A block starts at its title line. */

/* WGRIP ( string -- ): the gripper opening into a controller variable */
static fbrl_status w_wgrip(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[16], line[40];
    fbrl_status st = rb_name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK && fbrl_rapl_name_check(name, 0) != FBRL_OK)
        st = rb_fail_st(r, w, FBRL_ENAME, name);
    if (st != FBRL_OK)
        return st;
    snprintf(line, sizeof line, "%s=GRIPPER", name);
    return rb_raw(r, w, line, 0);
}

#define CMD(x) FBRL_RAPL_##x
const rb_word rb_motion_words[] = {
    /* I-5 motion */
    {"APPROACH", w_approach, "LR", 0, -1, 0,
     FBRL_DOC("( loc -- ) ( F: distance -- )",
              "joint-interpolated move to distance back from loc along the tool axis (APPRO)")},
    {"APPROACH-STRT", w_approach, "LR", 0, -1, 1,
     FBRL_DOC("( loc -- ) ( F: distance -- )", "straight-line approach (APPRO ...,S)")},
    {"DEPART", w_depart, "R", 0, -1, 0,
     FBRL_DOC("( F: distance -- )", "joint-interpolated move back along the tool axis")},
    {"DEPART-STRT", w_depart, "R", 0, -1, 1,
     FBRL_DOC("( F: distance -- )", "straight-line depart (DEPART ...,S)")},
    {"MOV", w_mov, "L", 0, -1, 0,
     FBRL_DOC("( loc -- )", "joint-interpolated move to a location (POINT scratch, MOVE scratch)")},
    {"MOV-STRT", w_mov, "L", 0, -1, 1,
     FBRL_DOC("( loc -- )", "straight-line move to a location (MOVE scratch,S)")},
    {"JOG", w_jog, "RRR", 0, -1, 0,
     FBRL_DOC("( F: dX dY dZ -- )", "move the tool by the displacements (straight line)")},
    {"JOINT", w_joint, "II", 0, CMD(JOINT), 0,
     FBRL_DOC("( joint degrees -- )", "drive one joint by degrees")},
    {"MOTOR", w_joint, "II", 0, CMD(MOTOR), 0,
     FBRL_DOC("( axis# #pulses -- )", "drive one motor by encoder pulses")},
    {"MA", w_joints, "J", 0, CMD(MA), 0,
     FBRL_DOC(
         "( F: j1 .. jn -- )",
         "joint-interpolated move to absolute joint angles, radians, one per axis (5 on the A255, 6 on the "
         "A465)")},
    {"MI", w_joints, "J", 0, CMD(MI), 0,
     FBRL_DOC("( F: j1 .. jn -- )", "joint-interpolated move by joint increments, radians, one per axis (5 "
                                    "on the A255, 6 on the A465)")},
    {"READY", w_plain, "", 0, CMD(READY), 0, FBRL_DOC("( -- )", "move the arm to the READY position")},
    {"HOME", w_plain, "", 0, CMD(HOME), 0, FBRL_DOC("( -- )", "initialise the robot position registers")},
    {"ALIGNTOOL", w_plain, "", 0, CMD(ALIGN), 0,
     FBRL_DOC("( -- )", "align the tool with the nearest major axis")},
    {"FINISH", w_plain, "", 0, CMD(FINISH), 0, FBRL_DOC("( -- )", "wait until the current motion is done")},
    {"HALT", w_plain, "", 0, CMD(HALT), 0, FBRL_DOC("( -- )", "stop the motion in progress")},
    /* I-5 positions */
    {"ARM-HERE", w_arm_here, "L", 0, -1, 0,
     FBRL_DOC("( loc -- )", "store the arm's position (after the motion ends) in loc, unmapped")},
    {"ACTUAL", w_actual, "X", 0, -1, 0,
     FBRL_DOC("( loc -- ) or ( PAR: name )",
              "actual position now into a host location, or into a controller location")},
    {"TOOL", w_tool, "L", 0, -1, 0, FBRL_DOC("( loc -- )", "set the tool transform from a location")},
    {"BASE-OFFSET", w_base_offset, "RRRR", 0, -1, 0,
     FBRL_DOC("( F: dX dY dZ dO -- )", "where the user's world frame sits on the arm's base")},
    /* I-5 arm state */
    {"ARM", w_arm, "I", 0, -1, 0, FBRL_DOC("( flag -- )", "arm power relay on (true) or off")},
    {"LIMP", w_int1, "I", 0, CMD(LIMP), 1, FBRL_DOC("( axis# -- )", "limp one axis (0 = all)")},
    {"NOLIMP", w_plain, "", 0, CMD(NOLIMP), 0, FBRL_DOC("( -- )", "servo control on again after LIMP")},
    {"LOCK", w_int1, "I", 0, CMD(LOCK), 2, FBRL_DOC("( axis# -- )", "lock one axis")},
    {"UNLOCK", w_int1, "I", 0, CMD(UNLOCK), 1, FBRL_DOC("( axis# -- )", "unlock one axis (0 = all)")},
    {"SPEED", w_int1, "I", 0, CMD(SPEED), 4,
     FBRL_DOC("( speed -- )", "speed of later moves, percent of full")},
    {"GAIN", w_gain, "IR", 0, -1, 0,
     FBRL_DOC("( motor# -- ) ( F: value -- )", "position gain of a motor (0 = all)")},
    {"MANUAL", w_plain, "", 0, CMD(MANUAL), 0, FBRL_DOC("( -- )", "teach-pendant manual mode on")},
    {"NOMANUAL", w_plain, "", 0, CMD(NOMANUAL), 0, FBRL_DOC("( -- )", "manual mode off")},
    {"NOTEACH", w_plain, "", 0, CMD(NOTEACH), 0, FBRL_DOC("( -- )", "teach mode off")},
    {"NOHELP", w_plain, "", 0, CMD(NOHELP), 0, FBRL_DOC("( -- )", "controller syntax help off")},
    {"FLASH", w_int1, "I", 0, CMD(FLASH), 5, FBRL_DOC("( interval -- )", "flash the teach-pendant lamp")},
    {"NOFLASH", w_plain, "", 0, CMD(NOFLASH), 0, FBRL_DOC("( -- )", "pendant lamp off")},
    {"XCAL", w_int1, "I", 0, CMD(XCAL), 3,
     FBRL_DOC("( axis# -- )", "store the home position of an extra axis")},
    {"XHOME", w_int1, "I", 0, CMD(XHOME), 3, FBRL_DOC("( axis# -- )", "home an extra axis")},
    {"XZERO", w_int1, "I", 0, CMD(XZERO), 3,
     FBRL_DOC("( axis# -- )", "zero an extra axis's position register")},
    /* I-5 gripper */
    {"GRIP", w_grip, "IR", 0, -1, 0,
     FBRL_DOC("( torque -- ) ( F: distance -- )", "servo gripper to an opening with a force")},
    {"CLOSE-GRIP", w_plain, "", 0, CMD(CLOSE), 0, FBRL_DOC("( -- )", "close the gripper")},
    {"WGRIP", w_wgrip, "S", 0, -1, 0,
     FBRL_DOC("( c-addr u -- ) or ( PAR: variable )", "gripper opening into a controller variable")},
    /* I-5 I/O */
    {"OUTPORT", w_outport, "I", 0, -1, 0, FBRL_DOC("( output# -- )", "set output n on (-n: off)")},
    {"OUT2BYTE", w_out2byte, "I", 0, -1, 0, FBRL_DOC("( n -- )", "set outputs 1..16 from the 16 bits of n")},
    {"SHIFT-RIGHT", w_shift_right, "I", 0, -1, 0,
     FBRL_DOC("( n -- n' b )", "n shifted right one bit, and the bit shifted out")},
    {"WAITPORT", w_waitport, "I", 0, -1, 0,
     FBRL_DOC("( input# -- )", "controller waits until input n is on (-n: off)")},
};
const size_t rb_motion_nwords = sizeof rb_motion_words / sizeof rb_motion_words[0];
