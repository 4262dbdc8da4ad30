/* SPDX-License-Identifier: MIT */
/* units.h - the metric switch: inches inside, centimetres at the user interface when on. */
#ifndef FBRL_UNITS_H
#define FBRL_UNITS_H

#include "fbrl/export.h"

#include "fbrl/status.h"
#include "fbrl/loc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Exactly 2.54 cm to the inch (the international inch). */
#define FBRL_CM_PER_IN 2.54

/* The switch is state the caller owns (one per language VM, per monitor, ...), never a
 * global. Everything stored, sent to the controller or written to a file is in inches;
 * only lengths convert, angles never do. Scalars are unitless (the thesis's rule): convert
 * them explicitly with fbrl_units_in_to_cm / fbrl_units_cm_to_in. */
typedef struct fbrl_units {
    int metric; /* 0 = inches (the default), 1 = centimetres */
} fbrl_units;

#define FBRL_UNITS_INIT \
    {                   \
        0               \
    }

/* All functions: FBRL_EINVAL for NULL, FBRL_ENONFINITE for a NaN/infinite input,
 * FBRL_EOVERFLOW when a finite input converts to a non-finite value. */

FBRL_API fbrl_status fbrl_units_init(fbrl_units *u);                     /* metric off */
FBRL_API fbrl_status fbrl_units_metric_on(fbrl_units *u);                /* METRIC-ON */
FBRL_API fbrl_status fbrl_units_metric_off(fbrl_units *u);               /* METRIC-OFF */
FBRL_API fbrl_status fbrl_units_is_metric(const fbrl_units *u, int *on); /* METRIC? (1 or 0) */

FBRL_API fbrl_status fbrl_units_in_to_cm(double in, double *cm); /* IN->CM */
FBRL_API fbrl_status fbrl_units_cm_to_in(double cm, double *in); /* CM->IN */

/* METRIC-IN: a length the user typed (cm when metric is on) -> inches. */
FBRL_API fbrl_status fbrl_units_in(const fbrl_units *u, double user, double *inches);
/* METRIC-OUT: inches -> the user's unit (cm when metric is on). */
FBRL_API fbrl_status fbrl_units_out(const fbrl_units *u, double inches, double *user);

/* The same for a whole location: x, y, z convert, yaw, pitch, roll are copied.
 * dst may equal src. */
FBRL_API fbrl_status fbrl_units_loc_in(const fbrl_units *u, const fbrl_loc *user, fbrl_loc *inches);
FBRL_API fbrl_status fbrl_units_loc_out(const fbrl_units *u, const fbrl_loc *inches, fbrl_loc *user);

#ifdef __cplusplus
}
#endif
#endif
