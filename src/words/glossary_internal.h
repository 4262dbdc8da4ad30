/* SPDX-License-Identifier: MIT */
/* glossary_internal.h - helpers shared by the data glossary's sources (private).
 *
 * The glossary words make their structures in the VM's data space, where a program can
 * overwrite them. Each structure therefore starts with a magic cell, its C payload follows
 * at GL_PAYLOAD bytes (16-aligned), and every use re-checks the magic and the payload's
 * extent before the C modules see it: a wrong or corrupted address throws, it never lets a
 * module touch memory outside the VM. */
#ifndef FBRL_LANG_GLOSSARY_INTERNAL_H
#define FBRL_LANG_GLOSSARY_INTERNAL_H

#include "internal_names.h"

#include "fbrl/glossary.h"
#include "fbrl/calib.h"
#include "fbrl/vmx.h"

#define GL_INSTALLED 0x474C4F53u /* g->magic once installed: "GLOS" */

/* The structures' types (vmx.h typed data): CREATE-CAL, CREATE-CAL-STRU, RECTMAT, RADMAT,
 * OPEN-FILE's handle. */
extern const fbrl_vmx_type gl_type_cal, gl_type_stru, gl_type_rect, gl_type_rad, gl_type_hndl;
#define GL_PAYLOAD FBRL_VMX_PAYLOAD

/* A location template's tag (fbrl_vmx_tag): how the glossary knows its CREATE-LOC words. */
extern const char gl_loc_tag[];
/* The HELP of the words the defining words make (one text each, for the words made by
 * fbrl_glossary_make too; NULL under FBRL_NO_HELP). */
#define GL_LOC_STACK  FBRL_DOC_TEXT("( -- loc )")
#define GL_LOC_HELP   FBRL_DOC_TEXT("location template (X Y Z O A T)")
#define GL_RECT_STACK FBRL_DOC_TEXT("( i j k loc -- )")
#define GL_RECT_HELP  FBRL_DOC_TEXT("store location (i, j, k) of this RECTMAT into loc")
#define GL_RAD_STACK  FBRL_DOC_TEXT("( ring idx k loc -- )")
#define GL_RAD_HELP   FBRL_DOC_TEXT("store location (ring, idx, k) of this RADMAT into loc")
#define GL_CAL_STACK  FBRL_DOC_TEXT("( -- cal )")
#define GL_CAL_HELP   FBRL_DOC_TEXT("calibration: three location slots 1 2 3")
#define GL_STRU_STACK FBRL_DOC_TEXT("( -- cal-stru )")
#define GL_STRU_HELP  FBRL_DOC_TEXT("calibration structure: the block's motion (identity until CALIBRATE)")
/* The run functions of RECTMAT and RADMAT words (glossary_loc.c). */
fbrl_status gl_rect_run(fbrl_vm *vm, void *ctx, const void *body);
fbrl_status gl_rad_run(fbrl_vm *vm, void *ctx, const void *body);

/* Forth THROW codes used besides FBRL_THROW_STATUS(st). */
#define GL_STACK_UNDERFLOW  (FBRL_THROW_STACK_UNDERFLOW)
#define GL_BAD_ADDRESS      (FBRL_THROW_BAD_ADDRESS)
#define GL_TYPE_MISMATCH    (FBRL_THROW_TYPE_MISMATCH)
#define GL_NO_NAME          (FBRL_THROW_NO_NAME)
#define GL_ALIGNMENT        (FBRL_THROW_ALIGNMENT)
#define GL_BAD_NUMBER       (FBRL_THROW_BAD_NUMBER)
#define GL_FSTACK_UNDERFLOW (FBRL_THROW_FSTACK_UNDERFLOW)

/* A glossary word's row: vmx.h's one row type; ctx is the glossary. */
typedef fbrl_vmx_reg gl_word;

/* Throw `code` with a formatted message (at most 127 characters are kept). */
fbrl_status gl_throw(fbrl_vm *vm, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Throw FBRL_THROW_STATUS(st) with "what: <status text>". */
fbrl_status gl_throw_st(fbrl_vm *vm, fbrl_status st, const char *what);

/* The parameters of the word whose row is word, by its spec (fbrl_vmx_check: the stacks,
 * integers accepted for reals by vmx.h's one rule): its cells into c[] and its reals into f[],
 * each in spec order (the deepest first; either may be NULL when the spec has none). */
fbrl_status gl_args(fbrl_vm *vm, const void *word, fbrl_cell *c, double *f);
fbrl_status gl_push_flag(fbrl_vm *vm, int yes);

/* The location at a (48 bytes in data space, 8-aligned); with finite, also refuse one
 * whose components are not all finite ("not a location"). Throws, naming `word`. */
fbrl_status gl_loc(fbrl_vm *vm, fbrl_cell a, int finite, const char *word, fbrl_loc **loc);

/* Parse a name and make a word whose data field holds a structure of this type (NULL: bare
 * bytes) with `bytes` zeroed payload bytes (fbrl_vmx_create); *payload = their address. With
 * run NULL the word pushes its data field address; otherwise it is a C word running
 * run(vm, NULL, data field). Throws on error, leaving no half-made word. */
fbrl_status gl_make(fbrl_vm *vm, fbrl_vmx_fn run, const fbrl_vmx_type *type, size_t bytes, const char *stack,
                    const char *help, void **payload);

/* A calibration structure (CREATE-CAL-STRU) at a, or throw naming `word`. With rigid, also
 * refuse one that CAL-STRU! left not a rigid motion. */
fbrl_status gl_stru(fbrl_vm *vm, fbrl_cell a, int rigid, const char *word, fbrl_calib **c);
int gl_rigid(const fbrl_calib *c);

/* Metric: user value <-> inches through g's switch; throw on a non-finite value. */
fbrl_status gl_in(fbrl_vm *vm, const fbrl_glossary *g, double user, double *inches);
fbrl_status gl_out(fbrl_vm *vm, const fbrl_glossary *g, double inches, double *user);

/* MAP-ON mapping of loc through the WITH-CAL structure: out = 1 maps to the moved block,
 * 0 unmaps (fbrl_glossary_map_out / _map_in); axis and *off as there. */
fbrl_status gl_map(const fbrl_glossary *g, fbrl_loc *loc, int out, const double axis[2], double *off);

/* The word groups. */
fbrl_status gl_install_loc(fbrl_vm *vm, fbrl_glossary *g);
fbrl_status gl_install_cal(fbrl_vm *vm, fbrl_glossary *g);
fbrl_status gl_install_file(fbrl_vm *vm, fbrl_glossary *g);

#endif
