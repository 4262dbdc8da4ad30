/* SPDX-License-Identifier: MIT */
/* crc32.h - CRC-32 (IEEE 802.3, reflected, as zlib/PNG), the checksum of every
 * libfbrl byte format (data files, saved calibrations, emulator state). */
#ifndef FBRL_CRC32_H
#define FBRL_CRC32_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Start with crc = 0 and feed pieces in order: fbrl_crc32(0, "123456789", 9) == 0xCBF43926.
 * NULL data leaves crc unchanged. */
FBRL_API uint32_t fbrl_crc32(uint32_t crc, const void *data, size_t n);

#ifdef __cplusplus
}
#endif
#endif
