/* loc.h - location templates: X Y Z O A T (x, y, z in inches; yaw, pitch, roll in degrees). */
#ifndef FBRL_LOC_H
#define FBRL_LOC_H

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
    FBRL_LOC_X = 0, FBRL_LOC_Y, FBRL_LOC_Z, FBRL_LOC_O, FBRL_LOC_A, FBRL_LOC_T, FBRL_LOC_NAXES
} fbrl_loc_axis;

#ifdef __cplusplus
}
#endif
#endif
