/* SPDX-License-Identifier: MIT */
/* workspace.h - a session's work kept in one data file: every named location (CREATE-LOC),
 * location matrix (RECTMAT / AUTOMAT, RADMAT), calibration (CREATE-CAL points,
 * CREATE-CAL-STRU motion) and named device (OUTPUT-DEVICE, INPUT-DEVICE), each with its
 * name, and the settings that decide where a stored location takes the arm (WITH-CAL's
 * structure, MAP-ON, BASE-OFFSET). docs/workspace.md tells how to use it.
 *
 * The file is a typed data file of the fileio module (magic, version, CRC-32s, written
 * through a temporary, fsync and rename): one user record per object, its name inside the
 * record. Loading is all or nothing: the whole file is verified, then every record checked
 * against the session (a name that is another kind of word here, a duplicate name, a
 * matrix or device the session could not hold) before the first object changes; a
 * refused file leaves the session exactly as it was.
 *
 * What a save would change in a workspace file, object by object, is fbrl_workspace_diff:
 * a program asks before it overwrites what was taught (fbrlmon's exit prompt).
 *
 * Words (fbrl_workspace_install): SAVE-WORKSPACE, LOAD-WORKSPACE, WORKSPACE,
 * WORKSPACE-CHANGED?. No allocation: the caller gives the file buffer. */
#ifndef FBRL_WORKSPACE_H
#define FBRL_WORKSPACE_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/fileio.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The workspace format this library writes (and the newest it reads). */
#define FBRL_WORKSPACE_VERSION 1u

/* User record tags (fileio FBRL_FT_USER). Each record: name length (1 byte), the name,
 * then little-endian IEEE doubles: the object's numbers (docs/workspace.md lists them). */
#define FBRL_WORKSPACE_TAG_HEAD    0x5748u /* "WH": first record, name FBRL-WORKSPACE, version */
#define FBRL_WORKSPACE_TAG_LOC     0x574Cu /* "WL": x y z o a t */
#define FBRL_WORKSPACE_TAG_RECTMAT 0x5752u /* "WR": base (6), dx dy dz */
#define FBRL_WORKSPACE_TAG_RADMAT  0x5744u /* "WD": base (6), inc-angle ring-dist z-off */
#define FBRL_WORKSPACE_TAG_CAL     0x5750u /* "WP": points 1 2 3 (6 each) */
#define FBRL_WORKSPACE_TAG_CALSTRU 0x5753u /* "WS": r (row by row, 9), t (3) */
#define FBRL_WORKSPACE_TAG_DEVICE  0x5756u /* "WV": port, output (1) / input (0), pulse ms */
#define FBRL_WORKSPACE_TAG_SET     0x5745u /* "WE": name = WITH-CAL's (may be empty); MAP-ON, BASE-OFFSET (4) */

/* Largest record payload (a calibration: 1 + 31 + 18 doubles) and the buffer bytes one
 * object needs in the file buffer. */
#define FBRL_WORKSPACE_RECORD_MAX   (1u + 31u + 18u * 8u)
#define FBRL_WORKSPACE_OBJECT_BYTES FBRL_FILE_RECORD_SIZE(FBRL_WORKSPACE_RECORD_MAX)

/* What a save or load carried. */
typedef struct fbrl_workspace_counts {
    unsigned locs, matrices, cals, devices;
} fbrl_workspace_counts;

/* Caller-owned; keep it at a fixed address while the VM runs. Fields private. */
typedef struct fbrl_workspace {
    uint32_t magic;
    fbrl_vm *vm;
    fbrl_glossary *g;
    fbrl_robot *r;      /* NULL: no devices, no BASE-OFFSET */
    unsigned char *buf; /* the file buffer */
    size_t cap;
    uint32_t mark;                 /* fingerprint of the session at the last save or load */
    char path[FBRL_FILE_PATH_MAX]; /* the file last saved or loaded ("" none) */
    fbrl_file file;
} fbrl_workspace;

/* Define the words in vm for the glossary g (and robot r, may be NULL), with buf[0..cap)
 * as the file buffer (FBRL_WORKSPACE_OBJECT_BYTES per object a workspace may hold). The
 * session as it is now counts as unchanged. FBRL_EINVAL for NULLs, FBRL_ENOMEM when the
 * dictionary is full. */
FBRL_API fbrl_status fbrl_workspace_install(fbrl_vm *vm, fbrl_workspace *ws, fbrl_glossary *g, fbrl_robot *r,
                                            void *buf, size_t cap);

/* Save every named object to path (atomically; an existing file is replaced only if it
 * is a workspace or an empty data file: FBRL_EFORMAT otherwise). n (may be NULL) gets the
 * counts. FBRL_ENOSPC if the buffer cannot hold them; the file is then untouched. */
FBRL_API fbrl_status fbrl_workspace_save(fbrl_workspace *ws, const char *path, fbrl_workspace_counts *n);

/* Load path into the session: objects of a saved name are made or overwritten, other
 * words are left alone, then WITH-CAL, MAP-ON and BASE-OFFSET are set. On any error
 * nothing changed and why[0..cap) (may be NULL) says what was wrong, e.g. "record 4 (P):
 * P is a RECTMAT here, a location in the file". Errors: those of fbrl_file_open (ENOENT,
 * EFORMAT, EVERSION, ECHECKSUM, ETRUNCATED, ENOSPC), EFORMAT (not a workspace or a bad
 * record), EVERSION (newer workspace), ETYPE (name conflict), EFULL (device table full),
 * ENOMEM (dictionary full). */
FBRL_API fbrl_status fbrl_workspace_load(fbrl_workspace *ws, const char *path, fbrl_workspace_counts *n,
                                         char *why, size_t cap);

/* *changed = 1 if the named objects or settings differ from the last save or load (or
 * from install, when neither happened). *n (may be NULL) gets the counts now. */
FBRL_API fbrl_status fbrl_workspace_changed(fbrl_workspace *ws, int *changed, fbrl_workspace_counts *n);

/* One difference between the session and a workspace file (fbrl_workspace_diff). */
typedef enum fbrl_workspace_change {
    FBRL_WORKSPACE_ADDED = 1, /* in the session, not in the file */
    FBRL_WORKSPACE_CHANGED,   /* in both, with other numbers */
    FBRL_WORKSPACE_DROPPED    /* in the file, not in the session (or another kind there): a save loses it */
} fbrl_workspace_change;

typedef struct fbrl_workspace_delta {
    fbrl_workspace_change change;
    const char *name;       /* "" for the settings (WITH-CAL, MAP-ON, BASE-OFFSET) */
    const char *kind;       /* "a location", "a RECTMAT" ... "the settings" */
    uint16_t tag;           /* FBRL_WORKSPACE_TAG_... */
    size_t n;               /* how many numbers */
    const double *was, *now; /* the file's and the session's numbers (NULL: none), as saved */
} fbrl_workspace_delta;

typedef void (*fbrl_workspace_diff_fn)(void *ctx, const fbrl_workspace_delta *d);

/* Compare the session with the workspace file path, as a save would write it: fn once per
 * difference (the session's objects in the order a save writes them, then what the file
 * holds and the session does not); *count (may be NULL) gets how many. Changes nothing.
 * Errors: those of fbrl_file_open (FBRL_ENOENT: no such file), FBRL_EFORMAT (not a
 * workspace, or a bad record). */
FBRL_API fbrl_status fbrl_workspace_diff(fbrl_workspace *ws, const char *path, fbrl_workspace_diff_fn fn,
                                         void *ctx, unsigned *count);

/* The file last saved or loaded ("" if none; never NULL). */
FBRL_API const char *fbrl_workspace_path(const fbrl_workspace *ws);

#ifdef __cplusplus
}
#endif
#endif
