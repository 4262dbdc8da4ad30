/* SPDX-License-Identifier: MIT */
/* robot_loc.c - locations between the user's frame and the arm's: host-side location
 * templates, MAP-ON mapping (the glossary's WITH-CAL) and the BASE-OFFSET, the scratch
 * controller points motion words move to, and the arm's position read back (W2). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/arm.h"
#include "fbrl/num.h"
#include "robot_internal.h"

/* ---- the data glossary's side: locations, mapping, units ---- */

/* The location template at a VM address (48 aligned bytes inside the data space). */
static fbrl_loc *gl_loc(fbrl_robot *r, fbrl_cell addr)
{
    fbrl_loc *p = NULL;
    return fbrl_glossary_loc(r->vm, addr, &p) == FBRL_OK ? p : NULL;
}

static int gl_metric(const fbrl_robot *r) { return rb_metric(r); }

/* MAP-ON mapping (identity without a glossary or with MAP-OFF). The waist turns about the
 * arm's base axis: where BASE-OFFSET puts it in the user's frame. */
static void gl_arm_axis(const fbrl_robot *r, double axis[2])
{
    double c = cos(FBRL_RAD(r->base[3])), s = sin(FBRL_RAD(r->base[3]));
    axis[0] = -(c * r->base[0] + s * r->base[1]);
    axis[1] = s * r->base[0] - c * r->base[1];
}

static fbrl_status gl_map_out(fbrl_robot *r, const fbrl_loc *in, fbrl_loc *out, double *off)
{
    double axis[2];
    *out = *in;
    *off = 0.0;
    gl_arm_axis(r, axis);
    return r->g ? fbrl_glossary_map_out(r->g, out, axis, off) : FBRL_OK;
}

static fbrl_status gl_map_in(fbrl_robot *r, const fbrl_loc *in, fbrl_loc *out)
{
    double axis[2];
    *out = *in;
    gl_arm_axis(r, axis);
    return r->g ? fbrl_glossary_map_in(r->g, out, axis) : FBRL_OK;
}

double rb_len_in(const fbrl_robot *r, double v) { return gl_metric(r) ? v / 2.54 : v; }

/* ---- locations: host side, mapping, base offset ---- */

fbrl_status rb_loc_read(fbrl_robot *r, const rb_word *w, fbrl_cell addr, fbrl_loc *out)
{
    const fbrl_loc *p = gl_loc(r, addr);
    char msg[96];
    if (!p) {
        snprintf(msg, sizeof msg, "%s: not a location (use a CREATE-LOC name)", w->name);
        return rb_fail(r, FBRL_THROW_BAD_ADDRESS, msg);
    }
    if (fbrl_loc_check(p) != FBRL_OK) {
        snprintf(msg, sizeof msg, "%s: location holds a NaN or infinity", w->name);
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ENONFINITE), msg);
    }
    *out = *p;
    return FBRL_OK;
}

fbrl_status rb_loc_write(fbrl_robot *r, const rb_word *w, fbrl_cell addr, const fbrl_loc *in)
{
    fbrl_loc *p = gl_loc(r, addr);
    if (!p) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: not a location (use a CREATE-LOC name)", w->name);
        return rb_fail(r, FBRL_THROW_BAD_ADDRESS, msg);
    }
    if (in)
        *p = *in; /* in NULL: only check that addr is a location */
    return FBRL_OK;
}

/* A location of the user's frame as the controller must see it: MAP-ON mapping (the
 * block's motion), then the BASE-OFFSET (where the user's world sits on the arm). */
fbrl_status rb_to_arm(fbrl_robot *r, const rb_word *w, const fbrl_loc *user, fbrl_loc *arm)
{
    fbrl_loc m;
    double off;
    fbrl_status st = gl_map_out(r, user, &m, &off);
    if (st == FBRL_ERANGE) {
        char msg[200], deg[32], lim[32];
        fbrl_num_fixed(deg, sizeof deg, off, 0, 2, 0, NULL);
        fbrl_num_fixed(lim, sizeof lim, FBRL_CALIB_AXIS_MAX, 0, 1, 0, NULL);
        snprintf(msg, sizeof msg,
                 "%s: mapping: the block's tilt asks for the tool axis %s deg across the arm,"
                 " which a 5-axis arm cannot follow (limit %s deg)",
                 w->name, deg, lim);
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), msg);
    }
    if (st != FBRL_OK)
        return rb_fail_st(r, w, st, "mapping");
    double c = cos(FBRL_RAD(r->base[3])), s = sin(FBRL_RAD(r->base[3]));
    arm->x = c * m.x - s * m.y + r->base[0];
    arm->y = s * m.x + c * m.y + r->base[1];
    arm->z = m.z + r->base[2];
    arm->o = r->base[3] != 0.0 ? fbrl_arm_wrap(m.o + r->base[3]) : m.o;
    arm->a = m.a;
    arm->t = m.t;
    return FBRL_OK;
}

/* The inverse: a position the controller reported, in the user's (original block) frame. */
fbrl_status rb_from_arm(fbrl_robot *r, const rb_word *w, const fbrl_loc *arm, fbrl_loc *user, int map)
{
    fbrl_loc m;
    double c = cos(FBRL_RAD(r->base[3])), s = sin(FBRL_RAD(r->base[3]));
    double dx = arm->x - r->base[0], dy = arm->y - r->base[1];
    m.x = c * dx + s * dy;
    m.y = -s * dx + c * dy;
    m.z = arm->z - r->base[2];
    m.o = r->base[3] != 0.0 ? fbrl_arm_wrap(arm->o - r->base[3]) : arm->o;
    m.a = arm->a;
    m.t = arm->t;
    if (!map) {
        *user = m;
        return FBRL_OK;
    }
    fbrl_status st = gl_map_in(r, &m, user);
    return st == FBRL_OK ? FBRL_OK : rb_fail_st(r, w, st, "unmapping");
}

/* POINT a scratch controller location at arm coordinates; its name goes to name[]. */
fbrl_status rb_scratch_point(fbrl_robot *r, const rb_word *w, const fbrl_loc *arm, const char **name)
{
    static const char *const names[2] = {"FBRLT1", "FBRLT2"};
    *name = names[r->scratch++ & 1u];
    fbrl_rapl_arg a[7] = {fbrl_rapl_str(*name),   fbrl_rapl_real(arm->x), fbrl_rapl_real(arm->y),
                          fbrl_rapl_real(arm->z), fbrl_rapl_real(arm->o), fbrl_rapl_real(arm->a),
                          fbrl_rapl_real(arm->t)};
    return rb_cmd(r, w, FBRL_RAPL_POINT, a, 7, 0);
}

/* The arm's position (W2 WORLD line), waiting for the motion to end first when asked. */
fbrl_status rb_arm_where(fbrl_robot *r, const rb_word *w, int finish, fbrl_loc *arm)
{
    fbrl_rapl_pos p;
    fbrl_status st = rb_online(r);
    if (st == FBRL_OK)
        st = rb_units(r, w); /* the WORLD line is in the controller's units */
    if (st != FBRL_OK)
        return st;
    if (finish && (st = rb_cmd(r, w, FBRL_RAPL_FINISH, NULL, 0, 0)) != FBRL_OK)
        return st;
    if ((st = rb_link_result(r, w, fbrl_link_where(r->link, FBRL_RAPL_W2, &p))) != FBRL_OK)
        return st;
    if (p.nworld < 6)
        return rb_fail_st(r, w, FBRL_EPROTOCOL, "W2 had no WORLD line");
    arm->x = p.world[0];
    arm->y = p.world[1];
    arm->z = p.world[2];
    arm->o = p.world[3];
    arm->a = p.world[4];
    arm->t = p.world[5];
    return FBRL_OK;
}
