/* SPDX-License-Identifier: MIT */
/* fuzz_util.h - helpers every fuzz target may use: failing loudly, a private
 * temporary directory for the files an input becomes, and input splitting. */
#ifndef FBRL_FUZZ_UTIL_H
#define FBRL_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

/* Prints "fuzz: ..." and aborts, so libFuzzer keeps the input as a crash. */
void fuzz_fail(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2), noreturn))
#endif
    ;

/* A private directory made once per process (under /dev/shm when it exists,
 * so fsync costs nothing), removed at exit; out gets DIR/name. */
void fuzz_path(char *out, size_t cap, const char *name);
void fuzz_write_file(const char *path, const void *data, size_t n);
/* The whole file into a malloc'ed buffer (*n bytes), or NULL if it is missing. */
unsigned char *fuzz_read_file(const char *path, size_t *n);

/* Splits an input at its first "%%" line: head, then what follows (may be empty). */
void fuzz_split(const uint8_t *d, size_t n, size_t *head, const uint8_t **tail, size_t *tail_n);

#endif
