/* SPDX-License-Identifier: MIT */
/* status.h - result codes shared by every libfbrl module. */
#ifndef FBRL_STATUS_H
#define FBRL_STATUS_H

#include "fbrl/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 0 is success; every failure is negative so `if (st < 0)` works everywhere.
 * Codes are stable: never renumber, only append. */
typedef enum fbrl_status {
    FBRL_OK = 0,
    FBRL_EINVAL = -1,         /* null pointer, zero size or malformed argument */
    FBRL_ERANGE = -2,         /* index or value outside its allowed range */
    FBRL_ENONFINITE = -3,     /* NaN or infinity where a finite number is needed */
    FBRL_ENOSPC = -4,         /* caller's storage is too small */
    FBRL_EEMPTY = -5,         /* nothing to take (empty queue) */
    FBRL_EFULL = -6,          /* no room to put (full queue or table) */
    FBRL_EDEGENERATE = -7,    /* calibration points coincident or collinear */
    FBRL_EIO = -8,            /* operating-system I/O error */
    FBRL_ENOENT = -9,         /* no such file, port or name */
    FBRL_EFORMAT = -10,       /* not a libfbrl file / bad magic */
    FBRL_EVERSION = -11,      /* file version not supported */
    FBRL_ECHECKSUM = -12,     /* checksum mismatch: data corrupted */
    FBRL_ETRUNCATED = -13,    /* file or message ends early */
    FBRL_ETYPE = -14,         /* record type differs from the one asked for */
    FBRL_EEOF = -15,          /* no more records */
    FBRL_ETIMEOUT = -16,      /* deadline passed */
    FBRL_EBUSY = -17,         /* in use: a port or file another program holds, or still busy */
    FBRL_ENOTTY = -18,        /* path is not a terminal device */
    FBRL_EUNSUPPORTED = -19,  /* setting (baud, parity, ...) not supported */
    FBRL_EDISCONNECTED = -20, /* peer went away (pty closed, TCP reset) */
    FBRL_ECONTROLLER = -21,   /* controller reported an error (code in the link) */
    FBRL_EECHO = -22,         /* echo never matched after all retries */
    FBRL_EPROTOCOL = -23,     /* reply not understood */
    FBRL_ENAME = -24,         /* name too long or has illegal characters */
    FBRL_ESTATE = -25,        /* call not valid in the object's current state */
    FBRL_ESYNTAX = -26,       /* text could not be parsed */
    FBRL_EOVERFLOW = -27,     /* arithmetic result does not fit */
    FBRL_ETHROW = -28,        /* language: uncaught THROW (code in the VM) */
    FBRL_ENOMEM = -29,        /* language: dictionary or stack space exhausted */
    FBRL_EOFFLINE = -30,      /* no controller connected */
    FBRL_ENOTFILE = -31,      /* not a regular file (a device, FIFO or directory) */
    FBRL_EPERM = -32,         /* the operating system refused access (e.g. a port's mode) */
    FBRL_EMAYBE = -33,        /* link: the command may have run; the link cannot prove
                                * either way (docs/link.md 3.9): do not repeat it blindly */
    FBRL_EAUTH = -34,         /* users: unknown name or wrong password */
    FBRL_ELOCKED = -35,       /* users: account locked (too many wrong passwords) or disabled */
    FBRL_EDISKFULL = -36,     /* no room left for the file: the disk (or quota) is full, or
                                * the file may grow no more (a size limit) */
    FBRL_ELOOP = -37,         /* symbolic links that lead round in a loop (or too many) */
    FBRL_EREADONLY = -38,     /* a read-only file, or a file system mounted read-only */
    FBRL_EGUARD = -39,        /* a motion the work cell's guard refused, or one that did not
                                * pass it (docs/workcell.md "The guard"): nothing was sent */
    FBRL_EUNITS = -40         /* link: the controller works in millimetres (METRIC), the
                                * host's lengths are inches (docs/link.md 1) */
} fbrl_status;

#define FBRL_STATUS_MIN FBRL_EUNITS

/* Short English text for a code; never NULL (unknown codes give "unknown status"). */
FBRL_API const char *fbrl_status_str(fbrl_status st);

/* Symbolic name, e.g. "FBRL_EINVAL"; never NULL. */
FBRL_API const char *fbrl_status_name(fbrl_status st);

#ifdef __cplusplus
}
#endif
#endif
