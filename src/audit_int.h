/* SPDX-License-Identifier: MIT */
/* audit_int.h - what the audit chain's sources share (internal). */
#ifndef FBRL_AUDIT_INT_H
#define FBRL_AUDIT_INT_H

#include <stddef.h>
#include <stdint.h>
#include "fbrl/audit.h"

/* A record's last bytes: ,"hash":"<64 hex>"} */
#define FBRL__AUDIT_HASH_KEY ",\"hash\":\""
#define FBRL__AUDIT_TAIL (sizeof FBRL__AUDIT_HASH_KEY - 1 + 2 * FBRL_AUDIT_HASH_SIZE + 2)

void fbrl__audit_hex(const unsigned char *b, size_t n, char *out);
/* 2n hex digits s[0..len) into out[n]; 0, or -1 if they are not exactly that. */
int fbrl__audit_unhex(const char *s, size_t len, unsigned char *out, size_t n);
/* A user name: 1..FBRL_AUDIT_NAME_MAX-1 of A-Z a-z 0-9 . _ - */
int fbrl__audit_name_ok(const char *s);
/* s[0..n) is one JSON object and nothing else but blanks: 0, else -1. */
int fbrl__audit_json_object(const char *s, size_t n);
/* Skip the JSON value at s[*i] (blanks before it too); 0, or -1 if there is none. */
int fbrl__audit_json_skip(const char *s, size_t n, size_t *i);
/* A JSON string into the body being built. */
void fbrl__audit_json_str(fbrl_audit *a, const char *s);
/* Write a record with the utc and prev given, numbered seq. */
fbrl_status fbrl__audit_write(fbrl_audit *a, const char *utc, const char *inner, size_t n, uint64_t seq,
                              const unsigned char *prev);

#endif
