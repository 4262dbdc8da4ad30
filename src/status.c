/* SPDX-License-Identifier: MIT */
/* status.c - texts for fbrl_status codes. */
#include "fbrl/status.h"

static const struct {
    const char *name, *text;
} entries[] = {
    {"FBRL_OK", "ok"},
    {"FBRL_EINVAL", "invalid argument"},
    {"FBRL_ERANGE", "value or index out of range"},
    {"FBRL_ENONFINITE", "number is not finite"},
    {"FBRL_ENOSPC", "buffer too small"},
    {"FBRL_EEMPTY", "empty"},
    {"FBRL_EFULL", "full"},
    {"FBRL_EDEGENERATE", "calibration points are coincident or collinear"},
    {"FBRL_EIO", "input/output error"},
    {"FBRL_ENOENT", "no such file, port or name"},
    {"FBRL_EFORMAT", "not a libfbrl data file"},
    {"FBRL_EVERSION", "unsupported file version"},
    {"FBRL_ECHECKSUM", "checksum mismatch (data corrupted)"},
    {"FBRL_ETRUNCATED", "data ends early (truncated)"},
    {"FBRL_ETYPE", "wrong data type"},
    {"FBRL_EEOF", "end of file"},
    {"FBRL_ETIMEOUT", "timed out"},
    {"FBRL_EBUSY", "port is in use"},
    {"FBRL_ENOTTY", "not a terminal device"},
    {"FBRL_EUNSUPPORTED", "setting not supported"},
    {"FBRL_EDISCONNECTED", "peer disconnected"},
    {"FBRL_ECONTROLLER", "controller reported an error"},
    {"FBRL_EECHO", "controller echo did not match"},
    {"FBRL_EPROTOCOL", "unexpected reply from controller"},
    {"FBRL_ENAME", "illegal name"},
    {"FBRL_ESTATE", "not valid in the current state"},
    {"FBRL_ESYNTAX", "syntax error"},
    {"FBRL_EOVERFLOW", "arithmetic overflow"},
    {"FBRL_ETHROW", "uncaught exception"},
    {"FBRL_ENOMEM", "out of memory space"},
    {"FBRL_EOFFLINE", "no controller connected"},
    {"FBRL_ENOTFILE", "not a regular file (a device, FIFO or directory)"},
    {"FBRL_EPERM", "permission denied"},
    {"FBRL_EMAYBE", "the command may have run (the link cannot tell)"},
};

#define NENTRIES ((int)(sizeof entries / sizeof entries[0]))

static int idx(fbrl_status st)
{
    int i = -(int)st;
    return (i >= 0 && i < NENTRIES) ? i : -1;
}

const char *fbrl_status_str(fbrl_status st)
{
    int i = idx(st);
    return i < 0 ? "unknown status" : entries[i].text;
}

const char *fbrl_status_name(fbrl_status st)
{
    int i = idx(st);
    return i < 0 ? "FBRL_E?" : entries[i].name;
}
