/* SPDX-License-Identifier: MIT */
/* matrix.c - arrays over caller storage and location matrices (thesis 5.1, 5.4). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include "fbrl/num.h"
#include "fbrl/units.h"
#include "fbrl/matrix.h"

fbrl_status fbrl_array_bytes(size_t cell_size, size_t rows, size_t cols, size_t *bytes)
{
    if (!bytes || cell_size == 0 || rows == 0 || cols == 0)
        return FBRL_EINVAL;
    if (rows > SIZE_MAX / cols || cell_size > SIZE_MAX / (rows * cols))
        return FBRL_EOVERFLOW;
    *bytes = cell_size * rows * cols;
    return FBRL_OK;
}

fbrl_status fbrl_array2_init(fbrl_array *a, void *storage, size_t storage_size, size_t cell_size, size_t rows,
                             size_t cols)
{
    size_t need;
    fbrl_status st;
    if (!a || !storage)
        return FBRL_EINVAL;
    if ((st = fbrl_array_bytes(cell_size, rows, cols, &need)) != FBRL_OK)
        return st;
    if (storage_size < need)
        return FBRL_ENOSPC;
    a->data = storage;
    a->cell_size = cell_size;
    a->rows = rows;
    a->cols = cols;
    return FBRL_OK;
}

fbrl_status fbrl_array_init(fbrl_array *a, void *storage, size_t storage_size, size_t cell_size, size_t count)
{
    return fbrl_array2_init(a, storage, storage_size, cell_size, count, 1);
}

/* A descriptor that init did not produce (zeroed, or fields changed) is refused rather
 * than trusted, so a cell address can never leave the storage init checked. */
static int array_ok(const fbrl_array *a)
{
    size_t bytes;
    return a && a->data && fbrl_array_bytes(a->cell_size, a->rows, a->cols, &bytes) == FBRL_OK;
}

fbrl_status fbrl_array_cell(const fbrl_array *a, size_t index, void **cell)
{
    if (!array_ok(a) || !cell)
        return FBRL_EINVAL;
    if (index >= a->rows * a->cols)
        return FBRL_ERANGE;
    *cell = a->data + index * a->cell_size;
    return FBRL_OK;
}

fbrl_status fbrl_array2_cell(const fbrl_array *a, size_t row, size_t col, void **cell)
{
    if (!array_ok(a) || !cell)
        return FBRL_EINVAL;
    if (row >= a->rows || col >= a->cols)
        return FBRL_ERANGE;
    *cell = a->data + (row * a->cols + col) * a->cell_size;
    return FBRL_OK;
}

/* ---- RECTMAT ---- */

fbrl_status fbrl_rectmat_init(fbrl_rectmat *m, const fbrl_loc *base, double dx, double dy, double dz)
{
    fbrl_status st;
    if (!m || !base)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(base)) != FBRL_OK)
        return st;
    if (!isfinite(dx) || !isfinite(dy) || !isfinite(dz))
        return FBRL_ENONFINITE;
    m->base = *base;
    m->dx = dx;
    m->dy = dy;
    m->dz = dz;
    return FBRL_OK;
}

fbrl_status fbrl_rectmat_loc(const fbrl_rectmat *m, long i, long j, long k, fbrl_loc *out)
{
    fbrl_loc r;
    fbrl_status st;
    if (!m || !out)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(&m->base)) != FBRL_OK)
        return st;
    if (!isfinite(m->dx) || !isfinite(m->dy) || !isfinite(m->dz))
        return FBRL_ENONFINITE;
    r = m->base;
    r.x += (double)i * m->dx;
    r.y += (double)j * m->dy;
    r.z += (double)k * m->dz;
    if (fbrl_loc_check(&r) != FBRL_OK)
        return FBRL_EOVERFLOW;
    *out = r;
    return FBRL_OK;
}

/* ---- RADMAT ---- */

fbrl_status fbrl_radmat_init(fbrl_radmat *m, const fbrl_loc *base, double inc_angle, double ring_dist,
                             double z_off)
{
    fbrl_status st;
    double r0;
    if (!m || !base)
        return FBRL_EINVAL;
    if ((st = fbrl_loc_check(base)) != FBRL_OK)
        return st;
    if (!isfinite(inc_angle) || !isfinite(ring_dist) || !isfinite(z_off))
        return FBRL_ENONFINITE;
    r0 = hypot(base->x, base->y);
    if (r0 == 0.0)
        return FBRL_ERANGE;
    if (!isfinite(r0))
        return FBRL_EOVERFLOW;
    m->base = *base;
    m->inc_angle = inc_angle;
    m->ring_dist = ring_dist;
    m->z_off = z_off;
    m->r0 = r0;
    m->a0 = atan2(base->y, base->x);
    return FBRL_OK;
}

fbrl_status fbrl_radmat_loc(const fbrl_radmat *m, long ring, long idx, long k, fbrl_loc *out)
{
    fbrl_loc r;
    double radius, turn, s, c, scale;
    if (!m || !out)
        return FBRL_EINVAL;
    if (fbrl_loc_check(&m->base) != FBRL_OK || !(m->r0 > 0.0) || !isfinite(m->r0) ||
        !isfinite(m->inc_angle) || !isfinite(m->ring_dist) || !isfinite(m->z_off))
        return FBRL_EINVAL; /* not a descriptor fbrl_radmat_init produced */
    radius = m->r0 + (double)ring * m->ring_dist;
    if (radius < 0.0)
        return FBRL_ERANGE;
    /* Turning the base's own (x, y) by the index angle and scaling it to the ring is
     * a0 + idx*inc at radius r0 + ring*ring_dist, and gives (0,0,k) the base's x and y
     * to the last bit (cos 0 = 1, sin 0 = 0, r0/r0 = 1). */
    turn = (double)idx * m->inc_angle;
    c = cos(turn);
    s = sin(turn);
    scale = radius / m->r0;
    r = m->base;
    r.x = scale * (m->base.x * c - m->base.y * s);
    r.y = scale * (m->base.x * s + m->base.y * c);
    r.z = m->base.z + (double)k * m->z_off;
    r.o = m->base.o + FBRL_DEG(turn);
    if (fbrl_loc_check(&r) != FBRL_OK)
        return FBRL_EOVERFLOW;
    *out = r;
    return FBRL_OK;
}

/* ---- SHOW-AUTOMAT, SHOW-RADMAT ---- */

/* The three lengths in the user's unit into shown (a conversion overflow is reported,
 * not printed), then "<name> base <loc text>  " into buf; the caller appends the rest. */
/* One number as printf's "%+W.Df" would write it in the C locale, whatever locale the
 * host has set (fbrl_num); 0 if it does not fit. */
#define MAT_NUM_CHARS 64
static int num_text(char out[MAT_NUM_CHARS], double v, int width, int decimals)
{
    return fbrl_num_fixed(out, MAT_NUM_CHARS, v, width, decimals, FBRL_NUM_PLUS, NULL) == FBRL_OK;
}

static fbrl_status format_head(const char *name, const fbrl_loc *base, int metric, const double len[3],
                               double shown[3], char *buf, size_t size, size_t *used)
{
    char loc[FBRL_LOC_TEXT_SIZE];
    fbrl_units u = FBRL_UNITS_INIT;
    fbrl_status st;
    int i, n;
    if (metric)
        fbrl_units_metric_on(&u);
    for (i = 0; i < 3; i++)
        if ((st = fbrl_units_out(&u, len[i], &shown[i])) != FBRL_OK)
            return st;
    if ((st = fbrl_loc_format(base, metric, loc, sizeof loc)) != FBRL_OK)
        return st;
    n = snprintf(buf, size, "%s base %s  ", name, loc);
    if (n < 0 || (size_t)n >= size)
        return FBRL_ENOSPC;
    *used = (size_t)n;
    return FBRL_OK;
}

fbrl_status fbrl_rectmat_format(const fbrl_rectmat *m, int metric, char *buf, size_t size)
{
    char f[3][MAT_NUM_CHARS];
    double len[3], shown[3];
    size_t used;
    fbrl_status st;
    int n;
    if (!m || !buf || size == 0)
        return FBRL_EINVAL;
    buf[0] = '\0';
    len[0] = m->dx;
    len[1] = m->dy;
    len[2] = m->dz;
    if ((st = format_head("RECTMAT", &m->base, metric, len, shown, buf, size, &used)) != FBRL_OK)
        return st;
    if (!num_text(f[0], shown[0], 10, 4) || !num_text(f[1], shown[1], 10, 4) ||
        !num_text(f[2], shown[2], 10, 4))
        return FBRL_ENOSPC;
    n = snprintf(buf + used, size - used, "step X %s Y %s Z %s %s", f[0], f[1], f[2], metric ? "cm" : "in");
    return n >= 0 && (size_t)n < size - used ? FBRL_OK : FBRL_ENOSPC;
}

fbrl_status fbrl_radmat_format(const fbrl_radmat *m, int metric, char *buf, size_t size)
{
    char f[5][MAT_NUM_CHARS];
    double len[3], shown[3];
    size_t used;
    fbrl_status st;
    int n;
    if (!m || !buf || size == 0)
        return FBRL_EINVAL;
    buf[0] = '\0';
    if (!isfinite(m->inc_angle) || !isfinite(m->a0))
        return FBRL_ENONFINITE;
    len[0] = m->ring_dist;
    len[1] = m->z_off;
    len[2] = m->r0;
    if ((st = format_head("RADMAT", &m->base, metric, len, shown, buf, size, &used)) != FBRL_OK)
        return st;
    if (!num_text(f[0], m->inc_angle, 0, 6) || !num_text(f[1], shown[0], 10, 4) ||
        !num_text(f[2], shown[1], 10, 4) || !num_text(f[3], shown[2], 10, 4) || !num_text(f[4], m->a0, 0, 6))
        return FBRL_ENOSPC;
    n = snprintf(buf + used, size - used, "inc %s rad  ring %s Z %s %s  radius %s %s  angle %s rad", f[0],
                 f[1], f[2], metric ? "cm" : "in", f[3], metric ? "cm" : "in", f[4]);
    return n >= 0 && (size_t)n < size - used ? FBRL_OK : FBRL_ENOSPC;
}
