/* SPDX-License-Identifier: MIT */
/* matrix.h - generic arrays over caller storage, and the location matrices RECTMAT and RADMAT. */
#ifndef FBRL_MATRIX_H
#define FBRL_MATRIX_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"
#include "fbrl/loc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Generic arrays (thesis figures 5.3 and 5.4) ----
 * A descriptor over storage the caller owns: cells of a fixed size, counted in rows and
 * columns (a one-dimensional array has one column). Cells are stored row by row; cell
 * (row, col) starts at data + (row * cols + col) * cell_size. Address-of-cell is bounds
 * checked: an index outside the array is FBRL_ERANGE, never an address past the storage. */
typedef struct fbrl_array {
    unsigned char *data;
    size_t cell_size; /* bytes per cell, >= 1 */
    size_t rows;      /* >= 1 */
    size_t cols;      /* >= 1 */
} fbrl_array;

/* Bytes of storage an array of rows x cols cells needs; FBRL_EOVERFLOW if not a size_t. */
FBRL_API fbrl_status fbrl_array_bytes(size_t cell_size, size_t rows, size_t cols, size_t *bytes);

/* ARRAY: a 1-D array of `count` cells over storage of storage_size bytes.
 * FBRL_EINVAL for NULL or a zero size/count, FBRL_ENOSPC if the storage is too small. */
FBRL_API fbrl_status fbrl_array_init(fbrl_array *a, void *storage, size_t storage_size, size_t cell_size,
                                     size_t count);
/* 2ARRAY: a rows x cols array. */
FBRL_API fbrl_status fbrl_array2_init(fbrl_array *a, void *storage, size_t storage_size, size_t cell_size,
                                      size_t rows, size_t cols);

/* Address of cell `index` of a 1-D array (in a 2-D array, index counts cells row by row). */
FBRL_API fbrl_status fbrl_array_cell(const fbrl_array *a, size_t index, void **cell);
/* Address of cell (row, col). */
FBRL_API fbrl_status fbrl_array2_cell(const fbrl_array *a, size_t row, size_t col, void **cell);

/* ---- Rectangular location matrix: RECTMAT (= AUTOMAT) ----
 * Location (i, j, k) = base + (i*dx, j*dy, k*dz); yaw, pitch and roll are the base's.
 * Indices may be negative: the base need not be a corner (a matrix taught from its middle
 * tube reaches both sides). The base is copied at init; re-init after re-teaching it. */
typedef struct fbrl_rectmat {
    fbrl_loc base;
    double dx, dy, dz; /* inches between neighbours along x, y, z (may be negative) */
} fbrl_rectmat;

FBRL_API fbrl_status fbrl_rectmat_init(fbrl_rectmat *m, const fbrl_loc *base, double dx, double dy,
                                       double dz);
FBRL_API fbrl_status fbrl_rectmat_loc(const fbrl_rectmat *m, long i, long j, long k, fbrl_loc *out);

/* ---- Radial location matrix: RADMAT ----
 * Centre = the arm's base axis (x = y = 0). The base location has radius r0 = hypot(x, y),
 * angle a0 = atan2(y, x) and height z0. Location (ring, idx, k) has
 *   radius = r0 + ring * ring_dist, angle = a0 + idx * inc_angle (radians),
 *   z = z0 + k * z_off, yaw = base yaw + idx * inc_angle (converted to degrees),
 * pitch and roll the base's. (0, 0, 0) is the base location itself, exactly.
 * Negative indices are allowed (rings inward, radials clockwise, levels down); a radius
 * that would become negative (through the centre) is FBRL_ERANGE. The yaw is not wrapped,
 * so it turns continuously with idx. A base on the axis (r0 == 0) has no angle: FBRL_ERANGE. */
typedef struct fbrl_radmat {
    fbrl_loc base;
    double inc_angle; /* radians between neighbouring radials */
    double ring_dist; /* inches between rings */
    double z_off;     /* inches between levels */
    double r0, a0;    /* base radius (inches) and angle (radians), derived at init */
} fbrl_radmat;

FBRL_API fbrl_status fbrl_radmat_init(fbrl_radmat *m, const fbrl_loc *base, double inc_angle,
                                      double ring_dist, double z_off);
FBRL_API fbrl_status fbrl_radmat_loc(const fbrl_radmat *m, long ring, long idx, long k, fbrl_loc *out);

/* SHOW-AUTOMAT and SHOW-RADMAT: one line describing the matrix, e.g.
 *   "RECTMAT base X ... deg  step X    +0.7500 Y    -1.2500 Z    +0.5000 in"
 *   "RADMAT base X ... deg  inc +0.200000 rad  ring    +0.5000 Z    +1.0000 in
 *    radius   +10.0000 in  angle +0.000000 rad"   (one line)
 * Lengths in cm when metric != 0. FBRL_MATRIX_TEXT_SIZE holds it for components below 1e9;
 * FBRL_ENOSPC (truncated, terminated text) if buf is too small. */
#define FBRL_MATRIX_TEXT_SIZE 320
FBRL_API fbrl_status fbrl_rectmat_format(const fbrl_rectmat *m, int metric, char *buf, size_t size);
FBRL_API fbrl_status fbrl_radmat_format(const fbrl_radmat *m, int metric, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
