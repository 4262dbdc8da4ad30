/* sim_control.c - control lines: the world outside the serial line (inputs,
 * analog inputs, the arm power switch, an object in the gripper, the teach
 * pendant's button), from the --control FIFO or the --inputs script. */
#include "sim_cmd.h"

#include <stdio.h>
#include <string.h>

int sim_control(fbrl_sim *s, const char *line)
{
    char w[16];
    double a = 0, b = 0;
    int n = sscanf(line, "%15s %lf %lf", w, &a, &b);
    if (n < 1)
        return -1;
    if (!strcmp(w, "IN") && n == 3 && a >= 1 && a <= SIM_IO && (b == 0 || b == 1)) {
        if (s)
            s->dev.in[(int)a - 1] = (int)b;
        return 0;
    }
    if (!strcmp(w, "AIN") && n == 3 && a >= 1 && a <= SIM_AIN && a == (int)a && b >= -10 && b <= 10) {
        if (s)
            s->dev.ain[(int)a - 1] = b;
        return 0;
    }
    if (!strcmp(w, "POWER") && n == 2 && (a == 0 || a == 1)) {
        if (s) {
            if (!a)
                sim_halt(s);
            s->arm.power = (int)a;
        }
        return 0;
    }
    if (!strcmp(w, "OBJECT") && n == 2 && a >= 0 && a <= SIM_GRIP_MAX) {
        if (s)
            s->dev.object = a;
        return 0;
    }
    if (!strcmp(w, "TEACH") && n == 1) {
        if (s && s->mem.teach && s->mem.teach_next <= 999) {
            char name[32];
            double q[FBRL_SIM_ARM_MAX_AXES];
            sim_loc *l;
            int i;
            snprintf(name, sizeof name, "%.5s%03d", s->mem.teach_name, s->mem.teach_next);
            if (sim_loc_new(s, name, s->mem.teach == 2, &l) == 0) {
                sim_joints_now(s, q);
                if (s->mem.teach == 2)
                    for (i = 0; i < sim_naxes(s); i++)
                        l->p[i] = fbrl_sim_arm_pulses(s->arm.model, i, q[i]);
                else
                    fbrl_sim_arm_fk(s->arm.model, q, sim_tool_len(s), l->v);
                s->mem.teach_next++;
                if (s->state_path)
                    sim_state_save(s);
                s->dirty = 0;
            }
        }
        return 0;
    }
    return -1;
}
