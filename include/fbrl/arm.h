/* SPDX-License-Identifier: MIT */
/* arm.h - the arm: the one description of each arm model the library, the monitor and the
 * emulator drive (docs/robot.md, "The arm models"), and its kinematics.
 *
 * Pure computation: no OS, no allocation. Angles are degrees, lengths inches. A model is a
 * row of the table (fbrl_arm_model): geometry, the arm's thickness, joint limits, speeds,
 * pulses per degree and READY, and which kinematic form its geometry fills:
 *
 *  - FBRL_ARM_5R (A255): waist, shoulder (upper arm above horizontal), elbow (forearm
 *    relative to the upper arm's line), wrist pitch (tool relative to the forearm), tool
 *    roll. Yaw is the waist's direction; the arm cannot choose it.
 *  - FBRL_ARM_6R (A465): waist, shoulder (upper arm from vertical, forward positive), elbow
 *    (forearm relative to the upper arm), forearm roll, wrist bend, tool roll: a spherical
 *    wrist, so every pose in reach is a full 6-D pose.
 *
 * A pose p[0..5] is X Y Z yaw pitch roll of the tool point (the flange plus a tool length
 * along the tool axis): the tool's orientation is Rz(yaw) * Ry(-pitch) * Rx(roll), its axis
 * the rotated x axis, so pitch is the tool axis above horizontal (-90 = straight down) and
 * roll is about the tool axis. Joint arrays hold naxes values (at most FBRL_ARM_AXES_MAX). */
#ifndef FBRL_ARM_H
#define FBRL_ARM_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_ARM_AXES_MAX 6 /* joints of the largest arm */
#define FBRL_ARM_CHAIN    4 /* points of fbrl_arm_chain: shoulder, elbow, wrist, tool point */
#define FBRL_ARM_PARTS    3 /* capsules of fbrl_arm_body: upper arm, forearm, tool */

typedef enum fbrl_arm_form {
    FBRL_ARM_5R = 1, /* A255 type: the waist points at the target */
    FBRL_ARM_6R = 2  /* A465 type: spherical wrist */
} fbrl_arm_form;

typedef struct fbrl_arm {
    const char *name; /* "A255": as STATUS shows it, as --arm and --model take it (any case) */
    unsigned naxes;
    int form;      /* fbrl_arm_form */
    double base_h; /* shoulder axis above the base, in */
    double upper;  /* shoulder to elbow, in */
    double fore;   /* elbow to the wrist centre (5R: the wrist pitch axis), in */
    double flange; /* wrist centre to flange, in */
    /* The arm's body for the work cell's guard: the upper arm and the forearm as capsules of
     * these radii around shoulder-elbow and elbow-wrist (the forearm's round end is the wrist
     * housing), in. */
    double r_upper, r_fore;
    double linear;                 /* straight-line speed at 100 %, in/s */
    double ppd[FBRL_ARM_AXES_MAX]; /* encoder pulses per degree */
    double min[FBRL_ARM_AXES_MAX]; /* joint limits, degrees */
    double max[FBRL_ARM_AXES_MAX];
    double speed[FBRL_ARM_AXES_MAX]; /* deg/s at 100 % */
    double ready[FBRL_ARM_AXES_MAX]; /* READY joint angles */
} fbrl_arm;

/* Row i of the model table (row 0, the A255, is the default everywhere); NULL past the end. */
FBRL_API const fbrl_arm *fbrl_arm_model(size_t i);
/* The model named name (case-insensitive), or NULL. */
FBRL_API const fbrl_arm *fbrl_arm_find(const char *name);
/* The models' names in lower case, sep between them ("a255|a465"), into buf[0..cap) (cut
 * short and terminated when it is too small); the length of the whole text. */
FBRL_API size_t fbrl_arm_names(char *buf, size_t cap, char sep);

/* An angle wrapped into (-180, 180]. */
FBRL_API double fbrl_arm_wrap(double deg);

/* Forward kinematics: joints q -> pose of the tool point tool inches past the flange
 * (0 = the flange). FBRL_EINVAL for NULLs. */
FBRL_API fbrl_status fbrl_arm_fk(const fbrl_arm *m, const double *q, double tool, double pose[6]);

/* Inverse kinematics of pose (tool as for fk): the first configuration inside the joint
 * limits, reaching forward (waist pointing at the target) before backward over the
 * shoulder, elbow up before elbow down (6R), and of the two wrists the one nearer hint (the
 * arm's joints now). Where a joint is free (on the base axis, a straight wrist) it keeps
 * hint's value. A 5R arm ignores yaw. FBRL_OK and q; FBRL_ENONFINITE for a pose not finite;
 * FBRL_ERANGE when no configuration reaches the pose (*axis = -1) or the preferred one passes
 * a joint limit (*axis = that joint, 0-based; q then holds that configuration). axis may be
 * NULL. */
FBRL_API fbrl_status fbrl_arm_ik(const fbrl_arm *m, const double pose[6], double tool, const double *hint,
                                 double *q, int *axis);

/* FBRL_OK when every joint of q is inside its limits (a joint a hair past one, from
 * rounding, counts as inside), else FBRL_ERANGE and *axis (may be NULL) the first that is
 * not (or is not finite). */
FBRL_API fbrl_status fbrl_arm_check(const fbrl_arm *m, const double *q, int *axis);

/* Encoder pulses for a joint angle (rounded), and back. */
FBRL_API long fbrl_arm_pulses(const fbrl_arm *m, unsigned axis, double deg);
FBRL_API double fbrl_arm_degrees(const fbrl_arm *m, unsigned axis, long pulses);

/* The pose on the straight segment a -> b at fraction f (0..1): position and angles
 * interpolated linearly, as the controller moves a straight line. */
FBRL_API void fbrl_arm_lerp(const double a[6], const double b[6], double f, double out[6]);

/* Checks the straight line from pose a to pose b, the arm's joints now being hint:
 * FBRL_OK when every sample has a solution inside the limits and no joint jumps (next to
 * the base axis, or from one configuration to another); FBRL_ERANGE otherwise (RAPL 068,
 * "straight line error"). */
FBRL_API fbrl_status fbrl_arm_check_line(const fbrl_arm *m, const double a[6], const double b[6], double tool,
                                         const double *hint);

/* The pose dist back along its tool axis (APPRO, DEPART). The 5R's tool axis points along
 * the waist's direction (toward the target; waist, in degrees, when the target is on the
 * base axis), the 6R's is the pose's own (yaw, pitch). */
FBRL_API fbrl_status fbrl_arm_back_off(const fbrl_arm *m, const double pose[6], double waist, double dist,
                                       double out[6]);

/* The arm's chain at joints q: p[0] the shoulder, p[1] the elbow, p[2] the wrist centre (5R:
 * on the wrist pitch axis), p[3] the tool point tool inches past the flange; the tool axis
 * runs from p[2] to p[3]. */
FBRL_API fbrl_status fbrl_arm_chain(const fbrl_arm *m, const double *q, double tool,
                                    double p[FBRL_ARM_CHAIN][3]);

/* The arm's body as capsules (a segment a-b grown by radius r): its parts. */
typedef enum fbrl_arm_part {
    FBRL_ARM_UPPER = 0, /* shoulder to elbow, radius r_upper */
    FBRL_ARM_FORE = 1,  /* elbow to the wrist centre, radius r_fore: its round end is the wrist housing */
    FBRL_ARM_TOOL = 2   /* the wrist centre through the flange to the tool's end, the caller's radius */
} fbrl_arm_part;

typedef struct fbrl_arm_capsule {
    double a[3], b[3], r;
} fbrl_arm_capsule;

/* The body at joints q, the tool reaching tool inches past the flange with radius tool_r:
 * body[FBRL_ARM_UPPER], [FBRL_ARM_FORE], [FBRL_ARM_TOOL]. Every end of a capsule's axis is a
 * point of fbrl_arm_chain (so fbrl_arm_levers bounds how far the body moves). */
FBRL_API fbrl_status fbrl_arm_body(const fbrl_arm *m, const double *q, double tool, double tool_r,
                                   fbrl_arm_capsule body[FBRL_ARM_PARTS]);
/* "upper arm", "forearm", "tool"; "arm" for another number. */
FBRL_API const char *fbrl_arm_part_name(int part);

/* For each joint, how far (in per radian) point `point` of the chain (1 the elbow, 2 the wrist
 * centre, 3 the tool point tool inches past the flange) can move when that joint turns: its
 * largest distance from the joint's axis, in any configuration (a roll about the tool axis
 * moves no point of the chain). No point before it along the chain moves further. A joint
 * move by dq moves the point no further than the sum of k[i] * |dq[i]| (radians).
 * FBRL_ERANGE for another point. */
FBRL_API fbrl_status fbrl_arm_levers(const fbrl_arm *m, int point, double tool, double k[FBRL_ARM_AXES_MAX]);

#ifdef __cplusplus
}
#endif
#endif
