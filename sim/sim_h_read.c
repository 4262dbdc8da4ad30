/* SPDX-License-Identifier: MIT */
/* sim_h_read.c - the readouts: W0/W2/W4 once, W1/W3/W5 and WE1/WE3/WE5 as a
 * stream until a key, and STATUS, in the RAPL-II layouts (docs/rapl-commands.md)
 * that clients parse at fixed places. */
#include "sim_cmd.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

static void print_position(fbrl_sim *s, const char *title, const double q[FBRL_ARM_AXES_MAX])
{
    sim_out *o = &s->term.out;
    double pose[6];
    int i;
    fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), pose);
    sim_out_printf(o, "\r\n%s\r\nNAME       ", title);
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i < sim_naxes(s) - 1 ? "AX#%d        " : "AX#%d", i + 1);
    sim_out_printf(o, "\r\nPULSES   ");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %+011ld" : "%+011ld", fbrl_arm_pulses(s->arm.model, i, q[i]));
    sim_out_printf(o, "\r\nNAME       ");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i < sim_naxes(s) - 1 ? "JT#%d      " : "JT#%d", i + 1);
    sim_out_printf(o, "\r\nJOINTS   ");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %+09.4f" : "%+09.4f", q[i] + 0.0); /* no "-000.0000" */
    sim_out_printf(o, "\r\nWORLD     ");
    for (i = 0; i < 6; i++)
        sim_out_printf(o, i ? " %+09.4f" : "%+09.4f", (i < 3 ? sim_len_out(s, pose[i]) : pose[i]) + 0.0);
    sim_out_printf(o, "\r\n");
}

static int h_wonce(fbrl_sim *s, args *a, int which)
{
    double q[FBRL_ARM_AXES_MAX];
    int e = sim_args_want(a, 0, 0);
    if (e)
        return e;
    if (which == 4 && s->arm.moving)
        memcpy(q, s->arm.qt, sizeof q);
    else
        sim_joints_now(s, q);
    print_position(s,
                   which == 0   ? "CURRENT COMMAND POSITION :"
                   : which == 2 ? "CURRENT ACTUAL POSITION :"
                                : "END OF PATH POSITION :",
                   q);
    return 0;
}

int sim_h_w0(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_wonce(s, a, 0);
}

int sim_h_w2(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_wonce(s, a, 2);
}

int sim_h_w4(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_wonce(s, a, 4);
}

static int h_stream(fbrl_sim *s, args *a, int kind)
{
    static const char *titles[] = {"ACTUAL POSITION (MOTOR PULSES):",
                                   "COMMAND POSITION (MOTOR PULSES):",
                                   "VELOCITY (PULSES/SEC):",
                                   "EXTRA AXIS ACTUAL (MOTOR PULSES):",
                                   "EXTRA AXIS COMMAND (MOTOR PULSES):",
                                   "EXTRA AXIS VELOCITY (PULSES/SEC):"};
    int e = sim_args_want(a, 0, 0);
    if (e)
        return e;
    s->term.stream_kind = kind;
    s->term.ps = PS_STREAM;
    sim_out_printf(&s->term.out, "%s\r\n", titles[(kind % 10) / 2 + (kind > 10 ? 3 : 0)]);
    return 0;
}

int sim_h_w1(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_stream(s, a, 1);
}

int sim_h_w3(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_stream(s, a, 3);
}

int sim_h_w5(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_stream(s, a, 5);
}

int sim_h_we1(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_stream(s, a, 11);
}

int sim_h_we3(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_stream(s, a, 13);
}

int sim_h_we5(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_stream(s, a, 15);
}

void sim_stream_line(fbrl_sim *s, sim_out *o)
{
    const double dt = 0.01; /* simulated seconds for the velocity difference */
    int i;
    if (s->term.stream_kind < 10) {
        double q[FBRL_ARM_AXES_MAX], q2[FBRL_ARM_AXES_MAX];
        sim_joints_now(s, q);
        if (s->term.stream_kind == 5) {
            /* the difference over the last dt of simulated time, from the segment's own formula */
            double save = s->t0;
            s->t0 += dt / s->opt.time_scale;
            s->clock_back += dt; /* the same, on a given clock */
            sim_joints_now(s, q2);
            s->t0 = save;
            s->clock_back -= dt;
            for (i = 0; i < sim_naxes(s); i++)
                sim_out_printf(o, i ? " %+011ld" : "%+011ld",
                               lround((q[i] - q2[i]) * s->arm.model->ppd[i] / dt));
        } else {
            for (i = 0; i < sim_naxes(s); i++)
                sim_out_printf(o, i ? " %+011ld" : "%+011ld", fbrl_arm_pulses(s->arm.model, i, q[i]));
        }
    } else if (s->term.stream_kind == 15) {
        double v = s->arm.xmoving && sim_now(s) < s->arm.xt1
                       ? (s->arm.xtarget - s->arm.xpos) / (s->arm.xt1 - s->arm.xt0)
                       : 0.0;
        sim_out_printf(o, "%+011ld", lround(v));
    } else {
        sim_out_printf(o, "%+011ld", lround(sim_extra_now(s)));
    }
    sim_out_printf(o, "\r");
}

static void status_extra(fbrl_sim *s, sim_out *o);

int sim_h_status(fbrl_sim *s, args *a, int *b)
{
    sim_out *o = &s->term.out;
    double q[FBRL_ARM_AXES_MAX];
    int e = sim_args_want(a, 0, 0), i, moving[FBRL_ARM_AXES_MAX];
    (void)b;
    if (e)
        return e;
    sim_joints_now(s, q);
    for (i = 0; i < sim_naxes(s); i++)
        moving[i] = s->arm.moving && fabs(s->arm.qt[i] - s->arm.q[i]) > 0 && sim_now(s) < s->arm.mt1;
    /* The RAPL-II 2.60 sample's 20 lines (research notes 1.4, S2; S3 reads them as a fixed
     * count); fbrlsim's own lines only with --status-extra, before the units line. */
    /* --status-extra is fbrlsim's own layout: the header names it, no program line */
    sim_out_printf(o, "RAPL-II Version 2.60     %s Robot%s\r\n", s->arm.model->name,
                   s->opt.status_extra ? " (fbrlsim)" : "");
    if (s->term.last_error < 0)
        sim_out_printf(o, "LAST ERROR CODE: NONE\r\n");
    else
        sim_out_printf(o, "LAST ERROR CODE: %03d-%s.\r\n", s->term.last_error,
                       sim_error_text(s->term.last_error));
    sim_out_printf(o, "SPEED (%% OF FULL) : %+6ld\r\n", lround(s->arm.speed));
    sim_out_printf(o, "MAX LINEAR SPEED: %+09.4f\r\n", sim_len_out(s, s->arm.model->linear));
    sim_out_printf(o, "CURRENT PROGRAM EXECUTING:\r\n");
    if (s->opt.status_extra) {
        /* no program line in fbrlsim's own layout */
    } else if (s->run.prog)
        sim_out_printf(o, "[00]%s#%05d :\r\n", s->run.prog->name, s->run.pc + 1);
    else if (s->term.last_prog[0] && s->term.last_prog_err >= 0)
        sim_out_printf(o, "[00]%s#%05d :%03d-%s.\r\n", s->term.last_prog, s->term.last_prog_line,
                       s->term.last_prog_err, sim_error_text(s->term.last_prog_err));
    else if (s->term.last_prog[0])
        sim_out_printf(o, "[00]%s#%05d :\r\n", s->term.last_prog, s->term.last_prog_line);
    else
        sim_out_printf(o, "[00]NONE\r\n");
    sim_out_printf(o, "JOINT LIMIT CHECK IS ON\r\n");
    sim_out_printf(o, "CONTROLLER IS %sHOMED\r\n", s->arm.homed ? "" : "NOT ");
    sim_out_printf(o, "TOOL TRANSFORM\r\n%-10s", s->mem.tool_set ? "TOOL" : "NULL");
    for (i = 0; i < 6; i++)
        sim_out_printf(o, i ? " %+09.4f" : "%+09.4f",
                       i < 3 ? sim_len_out(s, s->mem.tool[i]) : s->mem.tool[i]);
    sim_out_printf(o, "\r\nGRIPPER TYPE:  SERVO\r\n%-13s", "AXIS#");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %d" : "%d", i + 1);
    sim_out_printf(o, "\r\n%-13s", "LOCK");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %c" : "%c", s->arm.locked[i] ? 'Y' : 'N');
    sim_out_printf(o, "\r\n%-13s", "DONE");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %c" : "%c", moving[i] ? 'N' : 'Y');
    sim_out_printf(o, "\r\n%-13s", "LIMP");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %c" : "%c", s->arm.limp[i] ? 'Y' : 'N');
    sim_out_printf(o, "\r\n%-13s", "HOMED");
    for (i = 0; i < sim_naxes(s); i++)
        sim_out_printf(o, i ? " %c" : "%c", s->arm.homed ? 'Y' : 'N');
    sim_out_printf(o, "\r\nREQUESTED ROBOT CONFIG : UPRIGHT/REACH FORWARD/ELBOW UP/WRIST FREE\r\n");
    {
        /* backward when the tool point lies behind the base axis, seen along the waist */
        double pose[6], w = q[0] * 3.14159265358979323846 / 180.0;
        fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), pose);
        sim_out_printf(o, "CURRENT ROBOT CONFIG : UPRIGHT/REACH %s/ELBOW UP/WRIST FREE\r\n",
                       pose[0] * cos(w) + pose[1] * sin(w) < -1e-9 ? "BACKWARD" : "FORWARD");
    }
    sim_out_printf(o, "MANUAL MODE STATUS IS %s\r\n", s->dev.manual ? "ON" : "OFF");
    if (s->opt.status_extra)
        status_extra(s, o);
    sim_out_printf(o, "%s UNITS.\r\n", s->dev.metric ? "METRIC" : "INCH");
    return 0;
}

/* fbrlsim's own STATUS lines (--status-extra): not in the 2.60 sample. */
static void status_extra(fbrl_sim *s, sim_out *o)
{
    int i;
    sim_out_printf(o, "ARM POWER IS %s\r\n", s->arm.power ? "ON" : "OFF");
    sim_out_printf(o, "PENDANT LAMP IS %s\r\n", s->dev.flash ? "FLASHING" : "OFF");
    if (s->mem.teach)
        sim_out_printf(o, "TEACH MODE IS ON: %s%s, NEXT %03d\r\n", s->mem.teach == 2 ? "#" : "",
                       s->mem.teach_name, s->mem.teach_next);
    else
        sim_out_printf(o, "TEACH MODE IS OFF\r\n");
    sim_out_printf(o, "GRIPPER OPENING: %+09.4f FORCE (%% OF FULL): %+6ld\r\n", sim_len_out(s, s->dev.grip),
                   lround(s->dev.grip_force));
    sim_out_printf(o, "INPUTS  1-16: ");
    for (i = 0; i < SIM_IO; i++)
        sim_out_printf(o, "%d", s->dev.in[i]);
    sim_out_printf(o, "\r\nOUTPUTS 1-16: ");
    for (i = 0; i < SIM_IO; i++)
        sim_out_printf(o, "%d", s->dev.out_[i]);
    sim_out_printf(o, "\r\n");
}
