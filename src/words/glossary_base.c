/* SPDX-License-Identifier: MIT */
/* glossary_base.c - helpers every glossary word uses: throwing with a message, taking the
 * parameters, checked locations and structures in the VM's data space,
 * structures made with a magic cell, metric conversion of lengths. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "glossary_internal.h"

fbrl_status gl_throw(fbrl_vm *vm, int code, const char *fmt, ...)
{
    char msg[128];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return fbrl_vm_throw(vm, code, msg);
}

fbrl_status gl_throw_st(fbrl_vm *vm, fbrl_status st, const char *what)
{
    return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st), "%s: %s", what, fbrl_status_str(st));
}

fbrl_status gl_args(fbrl_vm *vm, const void *word, fbrl_cell *c, double *f)
{
    const char *spec = ((const gl_word *)word)->spec;
    fbrl_vmx_val v[FBRL_VMX_MAXARGS];
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    for (size_t k = 0, nc = 0, nf = 0; st == FBRL_OK && spec[k]; k++) {
        if (spec[k] == 'R')
            f[nf++] = v[k].f;
        else
            c[nc++] = v[k].i;
    }
    return st;
}

fbrl_status gl_push_flag(fbrl_vm *vm, int yes) { return fbrl_vm_push(vm, yes ? -1 : 0); }

fbrl_status gl_loc(fbrl_vm *vm, fbrl_cell a, int finite, const char *word, fbrl_loc **loc)
{
    if (!fbrl_vm_addr(vm, a, sizeof(fbrl_loc)))
        return gl_throw(vm, GL_BAD_ADDRESS, "%s: address is not a location in data space", word);
    if ((fbrl_ucell)a % sizeof(double))
        return gl_throw(vm, GL_ALIGNMENT, "%s: location address not aligned to 8 bytes", word);
    if (finite && fbrl_loc_check((fbrl_loc *)a) != FBRL_OK)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: not a location (a component is not a finite number)",
                        word);
    *loc = (fbrl_loc *)a;
    return FBRL_OK;
}

const fbrl_vmx_type gl_type_cal = {"calibration", (fbrl_cell)0x43414C33 /* "CAL3" */};
const fbrl_vmx_type gl_type_stru = {"calibration structure", (fbrl_cell)0x43414C53 /* "CALS" */};
const fbrl_vmx_type gl_type_rect = {"RECTMAT", (fbrl_cell)0x52454354 /* "RECT" */};
const fbrl_vmx_type gl_type_rad = {"RADMAT", (fbrl_cell)0x5241444D /* "RADM" */};
const fbrl_vmx_type gl_type_hndl = {"file handle", (fbrl_cell)0x484E444C /* "HNDL" */};

fbrl_status gl_make(fbrl_vm *vm, fbrl_vmx_fn run, const fbrl_vmx_type *type, size_t bytes, const char *stack,
                    const char *help, void **payload)
{
    return fbrl_vmx_create(vm, NULL, 0, type, bytes, run, NULL, stack, help, NULL, payload);
}

int gl_rigid(const fbrl_calib *c)
{
    /* The calib module's save accepts exactly the finite rigid motions. */
    unsigned char b[FBRL_CALIB_BYTES];
    return fbrl_calib_save(c, b, sizeof b) == FBRL_OK;
}

fbrl_status gl_stru(fbrl_vm *vm, fbrl_cell a, int rigid, const char *word, fbrl_calib **c)
{
    fbrl_calib *p = fbrl_vmx_data(vm, a, &gl_type_stru, sizeof(fbrl_calib));
    if (!p)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: not a calibration structure (use a CREATE-CAL-STRU name)",
                        word);
    if (rigid && !gl_rigid(p))
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ESTATE),
                        "%s: calibration structure is not a rigid motion (see CAL-STRU!)", word);
    *c = p;
    return FBRL_OK;
}

fbrl_status gl_in(fbrl_vm *vm, const fbrl_glossary *g, double user, double *inches)
{
    fbrl_status st = fbrl_units_in(&g->units, user, inches);
    return st == FBRL_OK ? st : gl_throw_st(vm, st, "length");
}

fbrl_status gl_out(fbrl_vm *vm, const fbrl_glossary *g, double inches, double *user)
{
    fbrl_status st = fbrl_units_out(&g->units, inches, user);
    return st == FBRL_OK ? st : gl_throw_st(vm, st, "length");
}

fbrl_status gl_map(const fbrl_glossary *g, fbrl_loc *loc, int out, const double axis[2], double *off)
{
    fbrl_loc res;
    fbrl_status st;
    double dev = 0.0;
    if (off)
        *off = 0.0;
    if (!g || g->magic != GL_INSTALLED || !g->vm || !loc)
        return FBRL_EINVAL;
    if (!g->map_on)
        return FBRL_OK;
    const fbrl_calib *c = fbrl_vmx_data(g->vm, g->with_cal, &gl_type_stru, sizeof(fbrl_calib));
    if (!c || !gl_rigid(c))
        return FBRL_ESTATE;
    st = out ? fbrl_calib_map_arm(c, axis, loc, &res, &dev) : fbrl_calib_unmap_arm(c, axis, loc, &res, &dev);
    if (off)
        *off = dev;
    if (st == FBRL_OK && out && dev > FBRL_CALIB_AXIS_MAX)
        st = FBRL_ERANGE;
    if (st == FBRL_OK)
        *loc = res;
    return st;
}
