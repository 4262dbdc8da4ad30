/* SPDX-License-Identifier: MIT */
/* status.c - texts for fbrl_status codes. */
#include "fbrl/status.h"

/* Every status with its text: one list, so that a name is its constant's spelling. */
#define STATUSES(X)                                                       \
    X(FBRL_OK, "ok")                                                      \
    X(FBRL_EINVAL, "invalid argument")                                    \
    X(FBRL_ERANGE, "value or index out of range")                         \
    X(FBRL_ENONFINITE, "number is not finite")                            \
    X(FBRL_ENOSPC, "buffer too small")                                    \
    X(FBRL_EEMPTY, "empty")                                               \
    X(FBRL_EFULL, "full")                                                 \
    X(FBRL_EDEGENERATE, "calibration points are coincident or collinear") \
    X(FBRL_EIO, "input/output error")                                     \
    X(FBRL_ENOENT, "no such file, port or name")                          \
    X(FBRL_EFORMAT, "not a libfbrl data file")                            \
    X(FBRL_EVERSION, "unsupported file version")                          \
    X(FBRL_ECHECKSUM, "checksum mismatch (data corrupted)")               \
    X(FBRL_ETRUNCATED, "data ends early (truncated)")                     \
    X(FBRL_ETYPE, "wrong data type")                                      \
    X(FBRL_EEOF, "end of file")                                           \
    X(FBRL_ETIMEOUT, "timed out")                                         \
    X(FBRL_EBUSY, "busy: held by another program or command")             \
    X(FBRL_ENOTTY, "not a terminal device")                               \
    X(FBRL_EUNSUPPORTED, "setting not supported")                         \
    X(FBRL_EDISCONNECTED, "peer disconnected")                            \
    X(FBRL_ECONTROLLER, "controller reported an error")                   \
    X(FBRL_EECHO, "controller echo did not match")                        \
    X(FBRL_EPROTOCOL, "unexpected reply from controller")                 \
    X(FBRL_ENAME, "illegal name")                                         \
    X(FBRL_ESTATE, "not valid in the current state")                      \
    X(FBRL_ESYNTAX, "syntax error")                                       \
    X(FBRL_EOVERFLOW, "arithmetic overflow")                              \
    X(FBRL_ETHROW, "uncaught exception")                                  \
    X(FBRL_ENOMEM, "out of memory space")                                 \
    X(FBRL_EOFFLINE, "no controller connected")                           \
    X(FBRL_ENOTFILE, "not a regular file (a device, FIFO or directory)")  \
    X(FBRL_EPERM, "permission denied")                                    \
    X(FBRL_EMAYBE, "the command may have run (the link cannot tell)")    \
    X(FBRL_EAUTH, "name or password not accepted")                        \
    X(FBRL_ELOCKED, "account locked or disabled")                         \
    X(FBRL_EDISKFULL, "no space left on the disk (or the file may grow no more)") \
    X(FBRL_ELOOP, "a loop of symbolic links")                             \
    X(FBRL_EREADONLY, "read-only file or file system")                   \
    X(FBRL_EGUARD, "refused by the motion guard (nothing was sent)")       \
    X(FBRL_EUNITS, "the controller works in millimetres (METRIC); switch it to inches: NOMETRIC")

/* Two tables indexed by -st (a place given twice is a warning), so that a program that asks
 * only for texts (the firmware) links no names. */
#define STATUS_NAME(st, text) [-(st)] = #st,
#define STATUS_TEXT(st, text) [-(st)] = text,
static const char *const names[] = {STATUSES(STATUS_NAME)};
static const char *const texts[] = {STATUSES(STATUS_TEXT)};

#define NENTRIES ((int)(sizeof texts / sizeof texts[0]))

static int idx(fbrl_status st)
{
    int i = -(int)st;
    return (i >= 0 && i < NENTRIES) ? i : -1;
}

const char *fbrl_status_str(fbrl_status st)
{
    int i = idx(st);
    return i < 0 ? "unknown status" : texts[i];
}

const char *fbrl_status_name(fbrl_status st)
{
    int i = idx(st);
    return i < 0 ? "FBRL_E?" : names[i];
}
