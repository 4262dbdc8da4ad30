/* SPDX-License-Identifier: MIT */
/* units.c - metric conversion at the user interface (thesis 5.6). */
#include <math.h>
#include "fbrl/units.h"

static fbrl_status scale(double v, double factor, int divide, double *out)
{
    double r;
    if (!out)
        return FBRL_EINVAL;
    if (!isfinite(v))
        return FBRL_ENONFINITE;
    r = divide ? v / factor : v * factor;
    if (!isfinite(r))
        return FBRL_EOVERFLOW;
    *out = r;
    return FBRL_OK;
}

fbrl_status fbrl_units_init(fbrl_units *u) { return fbrl_units_metric_off(u); }

fbrl_status fbrl_units_metric_on(fbrl_units *u)
{
    if (!u)
        return FBRL_EINVAL;
    u->metric = 1;
    return FBRL_OK;
}

fbrl_status fbrl_units_metric_off(fbrl_units *u)
{
    if (!u)
        return FBRL_EINVAL;
    u->metric = 0;
    return FBRL_OK;
}

fbrl_status fbrl_units_is_metric(const fbrl_units *u, int *on)
{
    if (!u || !on)
        return FBRL_EINVAL;
    *on = u->metric != 0;
    return FBRL_OK;
}

fbrl_status fbrl_units_in_to_cm(double in, double *cm) { return scale(in, FBRL_CM_PER_IN, 0, cm); }

/* Divide rather than multiply by 1/2.54: 2.54 cm then gives exactly 1 inch. */
fbrl_status fbrl_units_cm_to_in(double cm, double *in) { return scale(cm, FBRL_CM_PER_IN, 1, in); }

fbrl_status fbrl_units_in(const fbrl_units *u, double user, double *inches)
{
    if (!u)
        return FBRL_EINVAL;
    return u->metric ? fbrl_units_cm_to_in(user, inches) : scale(user, 1.0, 0, inches);
}

fbrl_status fbrl_units_out(const fbrl_units *u, double inches, double *user)
{
    if (!u)
        return FBRL_EINVAL;
    return u->metric ? fbrl_units_in_to_cm(inches, user) : scale(inches, 1.0, 0, user);
}

/* Convert x, y, z with `conv` into a temporary so that a failure leaves dst untouched. */
static fbrl_status loc_conv(const fbrl_units *u, const fbrl_loc *src, fbrl_loc *dst,
                            fbrl_status (*conv)(const fbrl_units *, double, double *))
{
    fbrl_loc r;
    fbrl_status st;
    if (!u || !src || !dst)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(src)) != FBRL_OK)
        return st;
    r = *src;
    if ((st = conv(u, src->x, &r.x)) != FBRL_OK || (st = conv(u, src->y, &r.y)) != FBRL_OK ||
        (st = conv(u, src->z, &r.z)) != FBRL_OK)
        return st;
    *dst = r;
    return FBRL_OK;
}

fbrl_status fbrl_units_loc_in(const fbrl_units *u, const fbrl_loc *user, fbrl_loc *inches)
{
    return loc_conv(u, user, inches, fbrl_units_in);
}

fbrl_status fbrl_units_loc_out(const fbrl_units *u, const fbrl_loc *inches, fbrl_loc *user)
{
    return loc_conv(u, inches, user, fbrl_units_out);
}
