/* arm.h - kinematic model of the emulated 5-axis arm (A255 geometry, DESIGN 6).
 *
 * Pure computation: no OS, no allocation. Angles are degrees, lengths inches.
 * Joints q[0..4]: waist, shoulder (upper arm above horizontal), elbow (forearm
 * relative to the upper arm's line), wrist pitch (tool relative to the forearm),
 * tool roll. A pose p[0..5] is X Y Z yaw pitch roll of the tool point: the
 * flange (wrist pitch axis + 2.0 in along the tool) plus an optional tool
 * length. yaw = waist direction, pitch = tool axis above horizontal. */
#ifndef FBRL_SIM_ARM_H
#define FBRL_SIM_ARM_H

#define FBRL_SIM_ARM_AXES 5

#define FBRL_SIM_ARM_BASE_H   10.0  /* shoulder axis above the base, in */
#define FBRL_SIM_ARM_UPPER    10.0  /* upper arm, in */
#define FBRL_SIM_ARM_FORE     10.0  /* forearm, in */
#define FBRL_SIM_ARM_FLANGE    2.0  /* wrist pitch axis to flange, in */
#define FBRL_SIM_ARM_LINEAR   19.685 /* straight-line speed at 100 %, in/s (0.5 m/s) */

/* Per-joint constants, index 0..4. */
extern const double fbrl_sim_arm_ppd[FBRL_SIM_ARM_AXES];    /* encoder pulses per degree */
extern const double fbrl_sim_arm_min[FBRL_SIM_ARM_AXES];    /* joint limits, degrees */
extern const double fbrl_sim_arm_max[FBRL_SIM_ARM_AXES];
extern const double fbrl_sim_arm_speed[FBRL_SIM_ARM_AXES];  /* deg/s at 100 % */
extern const double fbrl_sim_arm_ready[FBRL_SIM_ARM_AXES];  /* READY joint angles */

/* Forward kinematics. tool_len = tool length beyond the flange (0 = flange). */
void fbrl_sim_arm_fk(const double q[FBRL_SIM_ARM_AXES], double tool_len, double pose[6]);

/* Inverse kinematics of pose (yaw ignored): the first solution inside the
 * joint limits, reaching forward (waist pointing at the target) or else
 * backward over the shoulder (waist turned away). On the base axis the waist
 * keeps waist_hint. Returns 0 and fills q; 29 (RAPL "transform illegal") when
 * the forward reach has no solution at all, 42..46 when its solution passes a
 * joint limit (q then holds that solution). */
int fbrl_sim_arm_ik(const double pose[6], double tool_len, double waist_hint,
                    double q[FBRL_SIM_ARM_AXES]);

/* 0 when every joint is inside its limits, else 42..46 for the first joint out. */
int fbrl_sim_arm_check(const double q[FBRL_SIM_ARM_AXES]);

/* Pulses for joint angles (rounded) and back. */
long fbrl_sim_arm_pulses(int axis, double deg);
double fbrl_sim_arm_degrees(int axis, long pulses);

/* Checks the straight segment from pose a to pose b (position and pitch/roll
 * interpolated linearly), the arm's waist now being waist_hint: 0 when every
 * sample has a solution inside the limits and the waist turns continuously
 * from waist_hint on, else 68 (RAPL "straight line error"). */
int fbrl_sim_arm_check_line(const double a[6], const double b[6], double tool_len,
                            double waist_hint);

/* Pose on the segment a->b at fraction f (0..1). */
void fbrl_sim_arm_lerp(const double a[6], const double b[6], double f, double out[6]);

/* Wraps an angle into (-180, 180]. */
double fbrl_sim_arm_wrap(double deg);

#endif
