/* SPDX-License-Identifier: MIT */
/* loc.h - location templates: X Y Z O A T (x, y, z in inches; yaw, pitch, roll in degrees). */
#ifndef FBRL_LOC_H
#define FBRL_LOC_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The thesis's location template: six reals. Field order is the wire and file order. */
typedef struct fbrl_loc {
    double x, y, z; /* inches */
    double o;       /* yaw (orientation), degrees */
    double a;       /* pitch (altitude), degrees; -90 = tool straight down */
    double t;       /* roll (twist), degrees */
} fbrl_loc;

/* Component index for get/set (X Y Z O A T). */
typedef enum fbrl_loc_axis {
    FBRL_LOC_X = 0,
    FBRL_LOC_Y,
    FBRL_LOC_Z,
    FBRL_LOC_O,
    FBRL_LOC_A,
    FBRL_LOC_T,
    FBRL_LOC_NAXES
} fbrl_loc_axis;

/* Location angles are degrees; matrices and calibration compute in radians. */
#define FBRL_PI       3.14159265358979323846
#define FBRL_DEG(rad) ((rad) * (180.0 / FBRL_PI))
#define FBRL_RAD(deg) ((deg) * (FBRL_PI / 180.0))

/* Buffer size that always holds fbrl_loc_format()'s text (terminating NUL included) when
 * every shown component is below 1e9 in magnitude; larger values may give FBRL_ENOSPC. */
#define FBRL_LOC_TEXT_SIZE 128

/* Every function below returns FBRL_EINVAL for a NULL pointer, FBRL_ERANGE for an axis
 * outside X..T and FBRL_ENONFINITE for a NaN or infinite input; on error no output changes. */

/* FBRL_OK when all six components are finite (GETx/SETx callers use it to vet a location). */
FBRL_API fbrl_status fbrl_loc_check(const fbrl_loc *loc);

/* GETX .. GETT and SETX .. SETT, by axis. */
FBRL_API fbrl_status fbrl_loc_get(const fbrl_loc *loc, fbrl_loc_axis axis, double *value);
FBRL_API fbrl_status fbrl_loc_set(fbrl_loc *loc, fbrl_loc_axis axis, double value);

/* DEFINE-LOC: set all six components. */
FBRL_API fbrl_status fbrl_loc_define(fbrl_loc *loc, double x, double y, double z, double o, double a,
                                     double t);

/* SET-LOC: copy src into dst (dst may equal src). */
FBRL_API fbrl_status fbrl_loc_copy(fbrl_loc *dst, const fbrl_loc *src);

/* SHIFTA: add every component of `by` to loc (angles add too; they are not wrapped).
 * A finite sum that overflows gives FBRL_EOVERFLOW. */
FBRL_API fbrl_status fbrl_loc_shift(fbrl_loc *loc, const fbrl_loc *by);

/* Straight-line distance between the positions (x, y, z) of two locations, in inches;
 * orientation is ignored. */
FBRL_API fbrl_status fbrl_loc_distance(const fbrl_loc *a, const fbrl_loc *b, double *inches);

/* DISPLAY-LOC's text, one line without newline, fixed width so that rows line up:
 *   "X   +12.0000 Y    -3.5000 Z    +1.2500 in  O  +90.000 A  -90.000 T   +0.000 deg"
 * With metric != 0 the lengths are shown in centimetres (unit "cm"); angles are always
 * degrees. FBRL_ENOSPC if buf is too small (buf then holds a truncated, terminated text). */
FBRL_API fbrl_status fbrl_loc_format(const fbrl_loc *loc, int metric, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
