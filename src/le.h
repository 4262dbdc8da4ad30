/* SPDX-License-Identifier: MIT */
/* le.h - little-endian fixed-width fields, encoded byte by byte so every byte
 * format is the same on every host (internal to the library). */
#ifndef FBRL_LE_H
#define FBRL_LE_H

#include <stdint.h>
#include <string.h>

static inline void fbrl_le_put(unsigned char *p, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

static inline uint64_t fbrl_le_get(const unsigned char *p, int bytes)
{
    uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; i--)
        v = (v << 8) | p[i];
    return v;
}

static inline void fbrl_le_put16(unsigned char *p, uint16_t v) { fbrl_le_put(p, v, 2); }
static inline void fbrl_le_put32(unsigned char *p, uint32_t v) { fbrl_le_put(p, v, 4); }
static inline void fbrl_le_put64(unsigned char *p, uint64_t v) { fbrl_le_put(p, v, 8); }
static inline uint16_t fbrl_le_get16(const unsigned char *p) { return (uint16_t)fbrl_le_get(p, 2); }
static inline uint32_t fbrl_le_get32(const unsigned char *p) { return (uint32_t)fbrl_le_get(p, 4); }
static inline uint64_t fbrl_le_get64(const unsigned char *p) { return fbrl_le_get(p, 8); }

/* IEEE-754 binary64 is assumed, as on every target libfbrl builds for. */
static inline void fbrl_le_put_double(unsigned char *p, double d)
{
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    fbrl_le_put64(p, v);
}

static inline double fbrl_le_get_double(const unsigned char *p)
{
    uint64_t v = fbrl_le_get64(p);
    double d;
    memcpy(&d, &v, sizeof d);
    return d;
}

#endif
