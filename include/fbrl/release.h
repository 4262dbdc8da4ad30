/* SPDX-License-Identifier: MIT */
/* release.h - method versions and their release (docs/compliance.md, "Released methods").
 *
 * A method's version is the SHA-256 of its file and of every file it includes (INCLUDE,
 * REQUIRE, S" ..." INCLUDED/REQUIRED, followed from file to file), each under the name it
 * is included by, so a copy elsewhere is the same version and a one-character edit of any
 * of them is another. A version's state is read from the audit chain's "method" records:
 *
 *   Draft       a version no record names, or one recorded "draft"
 *   In review   "submit" by a method developer
 *   Released    "release" by a reviewer, followed by that reviewer's signature of it with the
 *               meaning "approved for use" (another user than the one who submitted it)
 *   Retired     "retire" by a reviewer
 *
 * Operators run only Released versions; a lab setting lets method developers run Drafts
 * (recorded in each run). A method with a Released version whose files now differ is
 * refused, naming the file. The files go through the store (src/audit_store.h); nothing
 * is allocated. */
#ifndef FBRL_RELEASE_H
#define FBRL_RELEASE_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/audit.h"
#include "fbrl/status.h"
#include "fbrl/users.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_RELEASE_MAX_FILES 32
#define FBRL_RELEASE_PATH_MAX 256
#define FBRL_RELEASE_NAME_MAX 64
#define FBRL_RELEASE_WHY_MAX 320

typedef enum fbrl_release_state {
    FBRL_RELEASE_DRAFT = 0,
    FBRL_RELEASE_IN_REVIEW,
    FBRL_RELEASE_RELEASED,
    FBRL_RELEASE_RETIRED
} fbrl_release_state;

typedef struct fbrl_release_file {
    char name[FBRL_RELEASE_PATH_MAX]; /* as included ("../asps_cell.fbrl"); the top file: its base name */
    char path[FBRL_RELEASE_PATH_MAX]; /* where it was read */
    unsigned char sha256[FBRL_AUDIT_HASH_SIZE];
} fbrl_release_file;

/* A method version. Caller-owned. */
typedef struct fbrl_method_version {
    char method[FBRL_RELEASE_NAME_MAX]; /* the name on its METHOD line ("" if none) */
    size_t nfiles;
    fbrl_release_file file[FBRL_RELEASE_MAX_FILES];
    unsigned char version[FBRL_AUDIT_HASH_SIZE];
    char hex[2 * FBRL_AUDIT_HASH_SIZE + 1]; /* the version as text */
    /* what the chain says (fbrl_release_status) */
    fbrl_release_state state;
    char state_by[FBRL_AUDIT_NAME_MAX]; /* who put it in that state */
    char state_utc[32];
    int has_released;   /* the method has another version Released */
    char released_hex[2 * FBRL_AUDIT_HASH_SIZE + 1];
    char changed[FBRL_RELEASE_PATH_MAX]; /* the first file that differs from it, by the name it is included by */
    char why[FBRL_RELEASE_WHY_MAX];      /* a refusal in words */
} fbrl_method_version;

/* Hash the method file at path and everything it includes. FBRL_ENOENT names the file in
 * mv->why (a missing include too), FBRL_EFULL past FBRL_RELEASE_MAX_FILES. */
FBRL_API fbrl_status fbrl_release_identify(fbrl_method_version *mv, const char *path);
/* Read the version's state from the chain at chain_path (verified first: a broken chain
 * is FBRL_ECHECKSUM, mv->why says where). A missing chain: every version is a Draft. */
FBRL_API fbrl_status fbrl_release_status(fbrl_method_version *mv, const char *chain_path);
/* May this role run it? FBRL_OK (Released, or a Draft a developer may run with
 * allow_drafts); FBRL_EPERM with mv->why: a Draft or version in review for an operator,
 * a Released method whose files changed (which file), a Retired version. */
FBRL_API fbrl_status fbrl_release_check(fbrl_method_version *mv, fbrl_role role, int allow_drafts);
/* Record a state change of the version: "draft", "submit", "release", "retire" (the
 * release must then be signed by the same user: fbrl_audit_sign). */
FBRL_API fbrl_status fbrl_release_record(fbrl_audit *a, const fbrl_method_version *mv, const char *action);
/* "Draft", "In review", "Released", "Retired". */
FBRL_API const char *fbrl_release_state_name(fbrl_release_state s);

#ifdef __cplusplus
}
#endif
#endif
