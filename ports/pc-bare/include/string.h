/* SPDX-License-Identifier: MIT */
/* string.h - the freestanding image's own: only what libc.c provides. */
#ifndef PCBARE_STRING_H
#define PCBARE_STRING_H
#include <stddef.h>
void *memcpy(void *dst, const void *src, size_t n);
void *memmove(void *dst, const void *src, size_t n);
void *memset(void *dst, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);
size_t strlen(const char *s);
#endif
