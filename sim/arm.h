/* SPDX-License-Identifier: MIT */
/* arm.h - kinematic models of the emulated arms, as data (docs/fbrlsim.md).
 *
 * Pure computation: no OS, no allocation. Angles are degrees, lengths inches.
 * A model is a row of fbrl_sim_models: geometry, joint limits, speeds, pulses
 * per degree and READY, plus which kinematic form its geometry fills:
 *
 *  - FBRL_SIM_KIN_5R (A255): waist, shoulder (upper arm above horizontal), elbow
 *    (forearm relative to the upper arm's line), wrist pitch (tool relative to the
 *    forearm), tool roll. Yaw is the waist's direction; the arm cannot choose it.
 *  - FBRL_SIM_KIN_6R (A465): waist, shoulder (upper arm from vertical, forward
 *    positive), elbow (forearm relative to the upper arm), forearm roll, wrist bend,
 *    tool roll: a spherical wrist, so every pose in reach is a full 6-D pose.
 *
 * A pose p[0..5] is X Y Z yaw pitch roll of the tool point (the flange plus an
 * optional tool length along the tool axis): the tool's orientation is
 * Rz(yaw) * Ry(-pitch) * Rx(roll), its axis the rotated x axis, so pitch is the
 * tool axis above horizontal (-90 = straight down) and roll is about the tool axis. */
#ifndef FBRL_SIM_ARM_H
#define FBRL_SIM_ARM_H

#define FBRL_SIM_ARM_MAX_AXES 6

typedef enum fbrl_sim_kin { FBRL_SIM_KIN_5R, FBRL_SIM_KIN_6R } fbrl_sim_kin;

typedef struct fbrl_sim_model {
    const char *name; /* "A255", as STATUS shows it and the state file keeps it */
    int naxes;
    fbrl_sim_kin kin;
    double base_h;                     /* shoulder axis above the base, in */
    double upper;                      /* shoulder to elbow, in */
    double fore;                       /* elbow to the wrist centre, in */
    double flange;                     /* wrist centre to flange, in */
    double linear;                     /* straight-line speed at 100 %, in/s */
    double ppd[FBRL_SIM_ARM_MAX_AXES]; /* encoder pulses per degree */
    double min[FBRL_SIM_ARM_MAX_AXES]; /* joint limits, degrees */
    double max[FBRL_SIM_ARM_MAX_AXES];
    double speed[FBRL_SIM_ARM_MAX_AXES]; /* deg/s at 100 % */
    double ready[FBRL_SIM_ARM_MAX_AXES]; /* READY joint angles */
} fbrl_sim_model;

extern const fbrl_sim_model fbrl_sim_models[];
extern const int fbrl_sim_nmodels;

/* The model by name (case-insensitive), or NULL. */
const fbrl_sim_model *fbrl_sim_model_find(const char *name);

/* Forward kinematics. tool_len = tool length beyond the flange (0 = flange). */
void fbrl_sim_arm_fk(const fbrl_sim_model *m, const double *q, double tool_len, double pose[6]);

/* Inverse kinematics of pose: the first configuration inside the joint limits,
 * reaching forward (waist pointing at the target) before backward over the
 * shoulder, elbow up before elbow down (6R), and of the two wrists the one nearer
 * hint (the arm's joints now). Where a joint is free (on the base axis, a straight
 * wrist) it keeps hint's value. A 5R arm ignores yaw. Returns 0 and fills q; 029
 * when no configuration reaches the pose; 042.. when the preferred one passes a
 * joint limit (q then holds it). */
int fbrl_sim_arm_ik(const fbrl_sim_model *m, const double pose[6], double tool_len, const double *hint,
                    double *q);

/* 0 when every joint is inside its limits, else the joint's out-of-range code. */
int fbrl_sim_arm_check(const fbrl_sim_model *m, const double *q);

/* Pulses for joint angles (rounded) and back. */
long fbrl_sim_arm_pulses(const fbrl_sim_model *m, int axis, double deg);
double fbrl_sim_arm_degrees(const fbrl_sim_model *m, int axis, long pulses);

/* Checks the straight segment from pose a to pose b (position and angles
 * interpolated linearly), the arm's joints now being hint: 0 when every sample
 * has a solution inside the limits and no joint jumps (next to the base axis, or
 * from one configuration to another), else 068 (RAPL "straight line error"). */
int fbrl_sim_arm_check_line(const fbrl_sim_model *m, const double a[6], const double b[6], double tool_len,
                            const double *hint);

/* Pose on the segment a->b at fraction f (0..1). */
void fbrl_sim_arm_lerp(const double a[6], const double b[6], double f, double out[6]);

/* Wraps an angle into (-180, 180]. */
double fbrl_sim_arm_wrap(double deg);

#endif
