/* SPDX-License-Identifier: MIT */
/* calib.h - 3-D calibration of movable work blocks and mapping of locations (DESIGN 8). */
#ifndef FBRL_CALIB_H
#define FBRL_CALIB_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"
#include "fbrl/loc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A calibration is the rigid motion that carries the block from where it was first taught
 * (the calibration block C, "original") to where it is now (the recalibration block R,
 * "moved"):  p_moved = r * p_original + t,  r a proper rotation (row-major), t in inches.
 * map: original -> moved (outgoing locations); unmap: moved -> original (taught locations). */
typedef struct fbrl_calib {
    double r[3][3];
    double t[3];
} fbrl_calib;

/* A rotation matrix m[row][col] (a struct so that const works in C99). */
typedef struct fbrl_rot {
    double m[3][3];
} fbrl_rot;

/* The three taught points of a block (CREATE-CAL): slot 1 = P1 the origin, 2 = P2 on the
 * block's x axis, 3 = P3 anywhere in the block's xy plane off that axis. Only x, y, z count. */
typedef struct fbrl_calpts {
    fbrl_loc p[3];
} fbrl_calpts;

/* Points closer to coincident or collinear than this fraction of their spread (their
 * largest pairwise distance) are refused with FBRL_EDEGENERATE: their frame would be noise. */
#define FBRL_CALIB_TOL 1e-3

/* Most a mapped tool axis may miss the one the block asks for, degrees (the block tilted
 * across the arm, which a 5-axis arm cannot follow), before fbrl_calib_map refuses it. */
#define FBRL_CALIB_AXIS_MAX 2.0

/* Positions closer than this to the arm's base axis (inches) have no waist direction. */
#define FBRL_CALIB_AXIS_R 1e-6

/* Size of a saved calibration (see fbrl_calib_save). */
#define FBRL_CALIB_BYTES   108
#define FBRL_CALIB_VERSION 1

/* SET-CAL / GET-CAL: slot index 1..3 (FBRL_ERANGE otherwise). */
FBRL_API fbrl_status fbrl_calpts_set(fbrl_calpts *c, int index, const fbrl_loc *loc);
FBRL_API fbrl_status fbrl_calpts_get(const fbrl_calpts *c, int index, fbrl_loc *loc);

/* The identity (block not moved). */
FBRL_API fbrl_status fbrl_calib_identity(fbrl_calib *c);

/* The block frame of three points as a rigid motion block -> world: origin P1, columns of
 * r the unit axes x = P2-P1, z = x cross (P3-P1), y = z cross x; t = P1. */
FBRL_API fbrl_status fbrl_calib_frame(const fbrl_calpts *pts, fbrl_calib *frame);

/* CALIBRATE: the motion M = F_R * F_C^-1 from the block frame taught on the original block
 * (cal) to the frame taught on the moved block (recal). FBRL_EDEGENERATE if either point
 * set is coincident or collinear (within FBRL_CALIB_TOL). */
FBRL_API fbrl_status fbrl_calib_3point(fbrl_calib *c, const fbrl_calpts *cal, const fbrl_calpts *recal);

/* Least squares over n >= 3 point pairs (Horn's unit-quaternion method): the proper
 * rotation and shift minimising the sum of squared distances |M cal[i] - recal[i]|^2.
 * residuals (n entries, may be NULL) get each pair's distance after the fit, *rms (may be
 * NULL) their root mean square, *worst (may be NULL) the index of the largest residual,
 * so a mistaught point stands out. FBRL_EINVAL for n < 3, FBRL_EDEGENERATE if either set
 * is coincident or collinear. On error *c, *rms and *worst are unchanged. */
FBRL_API fbrl_status fbrl_calib_npoint(fbrl_calib *c, const fbrl_loc *cal, const fbrl_loc *recal, size_t n,
                                       double *residuals, double *rms, size_t *worst);

/* Mapping of whole locations for a 5-axis arm (waist, shoulder, elbow, wrist pitch, tool
 * roll; docs/calibration.md has the model and a worked example). The arm cannot choose
 * its heading: the waist points at the target, and the tool frame at a location is
 * Rz(waist) * Ry(-pitch) * Rx(roll) (the convention of fbrl_calib_orient_to_matrix with yaw
 * = waist); the location's yaw is not used (the controller ignores it), except as the
 * waist of a location on the arm's base axis. The position moves with the block; the tool
 * frame the arm has at the original location turns with the block and is then brought
 * into the mapped position's waist plane by the smallest rotation: the tool axis follows
 * the block as far as pitch can, the grip turns with the block about the tool axis.
 *
 * fbrl_calib_map_arm: out gets yaw = the waist direction at the mapped position (where
 * the controller will point the arm), pitch in (-180, 180] (beyond -90 or 90 the tool
 * leans back toward the base; no flip near straight down) and roll in (-180, 180]. *off
 * (may be NULL) gets the angle, degrees, between the tool axis the block asks for and the
 * one given: the tilt across the arm that a 5-axis arm cannot follow. axis = the arm's
 * base axis (x, y) in the locations' frame, NULL for (0, 0). Positions within
 * FBRL_CALIB_AXIS_R of the base axis have no waist direction: the original location's yaw
 * is taken as its waist, turned with the block for the mapped one. in may equal out.
 * fbrl_calib_unmap_arm: the same through the inverse motion (moved -> original). */
FBRL_API fbrl_status fbrl_calib_map_arm(const fbrl_calib *c, const double axis[2], const fbrl_loc *in,
                                        fbrl_loc *out, double *off);
FBRL_API fbrl_status fbrl_calib_unmap_arm(const fbrl_calib *c, const double axis[2], const fbrl_loc *in,
                                          fbrl_loc *out, double *off);

/* (MAP) and UNMAP: fbrl_calib_map_arm / _unmap_arm with the base axis at (0, 0). map
 * refuses (FBRL_ERANGE, out unchanged) a location whose tool axis the arm would miss by
 * more than FBRL_CALIB_AXIS_MAX degrees; unmap (taught locations coming back) never
 * refuses for that reason, so nothing taught is lost. */
FBRL_API fbrl_status fbrl_calib_map(const fbrl_calib *c, const fbrl_loc *in, fbrl_loc *out);
FBRL_API fbrl_status fbrl_calib_unmap(const fbrl_calib *c, const fbrl_loc *in, fbrl_loc *out);

/* Position only: out = r * in + t for n points packed x, y, z (3n doubles); in may equal
 * out. On a non-finite input (FBRL_ENONFINITE) or result (FBRL_EOVERFLOW) the points
 * before it are mapped and the rest untouched. n == 0 is allowed. */
FBRL_API fbrl_status fbrl_calib_map_points(const fbrl_calib *c, const double *in, double *out, size_t n);
FBRL_API fbrl_status fbrl_calib_unmap_points(const fbrl_calib *c, const double *in, double *out, size_t n);

/* The inverse motion (moved -> original). inv may equal c. */
FBRL_API fbrl_status fbrl_calib_invert(const fbrl_calib *c, fbrl_calib *inv);

/* Orientation convention: the tool's rotation is
 *   R = Rz(yaw) * Ry(-pitch) * Rx(roll)
 * (right-handed, angles in degrees), so the tool axis R*(1,0,0) = (cos yaw cos pitch,
 * sin yaw cos pitch, sin pitch): yaw is its heading, pitch its elevation above horizontal
 * (-90 = straight down) and roll the turn about it. */
FBRL_API fbrl_status fbrl_calib_orient_to_matrix(double yaw, double pitch, double roll, fbrl_rot *r);
/* The inverse; yaw_hint (degrees) is the yaw reported when the tool axis is vertical. */
FBRL_API fbrl_status fbrl_calib_matrix_to_orient(const fbrl_rot *r, double yaw_hint, double *yaw,
                                                 double *pitch, double *roll);

/* Save as FBRL_CALIB_BYTES bytes, little-endian:
 *   0 "FBCL"  4 u16 version (1)  6 u16 reserved (0)  8 r, 9 IEEE-754 doubles row by row
 *   80 t, 3 doubles  104 u32 CRC-32 (IEEE 802.3) of bytes 0..103.
 * FBRL_ENOSPC if size < FBRL_CALIB_BYTES. */
FBRL_API fbrl_status fbrl_calib_save(const fbrl_calib *c, unsigned char *buf, size_t size);
/* Load: FBRL_ETRUNCATED (short), FBRL_EFORMAT (bad magic, reserved bits, non-finite or
 * non-rotation matrix), FBRL_EVERSION, FBRL_ECHECKSUM. *c changes only on success. */
FBRL_API fbrl_status fbrl_calib_load(fbrl_calib *c, const unsigned char *buf, size_t size);

/* ANG-FROM-ORIGIN: the angle (radians, atan2, all four quadrants) of the line from
 * (x1, y1) to (x2, y2) against the positive x axis. FBRL_EDEGENERATE if the points coincide. */
FBRL_API fbrl_status fbrl_calib_ang_from_origin(double x1, double y1, double x2, double y2, double *ang);
/* ROTATE: turn the point (x, y) about the origin by ang radians (counter-clockwise). */
FBRL_API fbrl_status fbrl_calib_rotate(double x, double y, double ang, double *xr, double *yr);

#ifdef __cplusplus
}
#endif
#endif
