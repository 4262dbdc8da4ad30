/* loc.c - location templates (thesis appendix III-1). */
#include <math.h>
#include <stdio.h>
#include "fbrl/loc.h"
#include "fbrl/num.h"
#include "fbrl/units.h"

/* Room for one formatted number of a location (what fits FBRL_LOC_TEXT_SIZE and more). */
#define LOC_NUM_CHARS 64

/* The six components as an array view, in X Y Z O A T order. */
static double *comp(fbrl_loc *loc, int axis)
{
    switch (axis) {
    case FBRL_LOC_X: return &loc->x;
    case FBRL_LOC_Y: return &loc->y;
    case FBRL_LOC_Z: return &loc->z;
    case FBRL_LOC_O: return &loc->o;
    case FBRL_LOC_A: return &loc->a;
    default: return &loc->t;
    }
}

static int valid_axis(fbrl_loc_axis axis) { return (int)axis >= FBRL_LOC_X && (int)axis < FBRL_LOC_NAXES; }

fbrl_status fbrl_loc_check(const fbrl_loc *loc)
{
    if (!loc)
        return FBRL_EINVAL;
    if (!isfinite(loc->x) || !isfinite(loc->y) || !isfinite(loc->z) || !isfinite(loc->o) ||
        !isfinite(loc->a) || !isfinite(loc->t))
        return FBRL_ENONFINITE;
    return FBRL_OK;
}

fbrl_status fbrl_loc_get(const fbrl_loc *loc, fbrl_loc_axis axis, double *value)
{
    if (!loc || !value)
        return FBRL_EINVAL;
    if (!valid_axis(axis))
        return FBRL_ERANGE;
    *value = *comp((fbrl_loc *)loc, (int)axis); /* read only */
    return FBRL_OK;
}

fbrl_status fbrl_loc_set(fbrl_loc *loc, fbrl_loc_axis axis, double value)
{
    if (!loc)
        return FBRL_EINVAL;
    if (!valid_axis(axis))
        return FBRL_ERANGE;
    if (!isfinite(value))
        return FBRL_ENONFINITE;
    *comp(loc, (int)axis) = value;
    return FBRL_OK;
}

fbrl_status fbrl_loc_define(fbrl_loc *loc, double x, double y, double z, double o, double a, double t)
{
    fbrl_loc r;
    fbrl_status st;
    if (!loc)
        return FBRL_EINVAL;
    r.x = x;
    r.y = y;
    r.z = z;
    r.o = o;
    r.a = a;
    r.t = t;
    if ((st = fbrl_loc_check(&r)) != FBRL_OK)
        return st;
    *loc = r;
    return FBRL_OK;
}

fbrl_status fbrl_loc_copy(fbrl_loc *dst, const fbrl_loc *src)
{
    fbrl_status st;
    if (!dst || !src)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(src)) != FBRL_OK)
        return st;
    *dst = *src;
    return FBRL_OK;
}

fbrl_status fbrl_loc_shift(fbrl_loc *loc, const fbrl_loc *by)
{
    fbrl_loc r;
    fbrl_status st;
    int i;
    if (!loc || !by)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(loc)) != FBRL_OK || (st = fbrl_loc_check(by)) != FBRL_OK)
        return st;
    r = *loc;
    for (i = 0; i < FBRL_LOC_NAXES; i++)
        *comp(&r, i) += *comp((fbrl_loc *)by, i);
    if (fbrl_loc_check(&r) != FBRL_OK)
        return FBRL_EOVERFLOW;
    *loc = r;
    return FBRL_OK;
}

fbrl_status fbrl_loc_distance(const fbrl_loc *a, const fbrl_loc *b, double *inches)
{
    fbrl_status st;
    double d;
    if (!a || !b || !inches)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(a)) != FBRL_OK || (st = fbrl_loc_check(b)) != FBRL_OK)
        return st;
    /* hypot twice: no overflow for large but finite coordinates. */
    d = hypot(hypot(a->x - b->x, a->y - b->y), a->z - b->z);
    if (!isfinite(d))
        return FBRL_EOVERFLOW;
    *inches = d;
    return FBRL_OK;
}

/* A value that rounds to zero at the shown precision prints as +0, not -0. */
static double tidy(double v, double half_step) { return fabs(v) < half_step ? 0.0 : v; }

fbrl_status fbrl_loc_format(const fbrl_loc *loc, int metric, char *buf, size_t size)
{
    fbrl_loc shown;
    fbrl_status st;
    int n;
    if (!loc || !buf || size == 0)
        return FBRL_EINVAL;
    /* Scaled here with units.h's constant, not through fbrl_units_loc_out: units.c
     * builds on this module (fbrl_loc_check), so the dependency stays one way. */
    shown = *loc;
    if ((st = fbrl_loc_check(&shown)) == FBRL_OK && metric) {
        shown.x *= FBRL_CM_PER_IN;
        shown.y *= FBRL_CM_PER_IN;
        shown.z *= FBRL_CM_PER_IN;
        if (fbrl_loc_check(&shown) != FBRL_OK)
            st = FBRL_EOVERFLOW;
    }
    if (st != FBRL_OK) {
        buf[0] = '\0';
        return st;
    }
    /* fbrl_num, not printf's %f: the same text whatever locale the host has set. */
    {
        const double v[6] = {tidy(shown.x, 5e-5), tidy(shown.y, 5e-5), tidy(shown.z, 5e-5),
                             tidy(shown.o, 5e-4), tidy(shown.a, 5e-4), tidy(shown.t, 5e-4)};
        char f[6][LOC_NUM_CHARS];
        int i;
        for (i = 0; i < 6; i++)
            if (fbrl_num_fixed(f[i], sizeof f[i], v[i], i < 3 ? 10 : 8, i < 3 ? 4 : 3, FBRL_NUM_PLUS, NULL) !=
                FBRL_OK) {
                buf[0] = '\0';
                return FBRL_ENOSPC;
            }
        n = snprintf(buf, size, "X %s Y %s Z %s %s  O %s A %s T %s deg", f[0], f[1], f[2],
                     metric ? "cm" : "in", f[3], f[4], f[5]);
    }
    if (n < 0) {
        buf[0] = '\0';
        return FBRL_EINVAL;
    }
    return (size_t)n < size ? FBRL_OK : FBRL_ENOSPC;
}
