/* SPDX-License-Identifier: MIT */
/* posix_io.h - what the POSIX stores share (internal; fileio_posix.c has them): a write that
 * goes on after EINTR and short writes, an fsync that goes on after EINTR. */
#ifndef FBRL_POSIX_IO_H
#define FBRL_POSIX_IO_H

#include <stddef.h>
#include "fbrl/status.h"

/* All n bytes of p to fd, or FBRL_EIO. */
fbrl_status fbrl__posix_write_full(int fd, const void *p, size_t n);
/* fsync(fd), or FBRL_EIO. */
fbrl_status fbrl__posix_sync(int fd);

#endif
