/* SPDX-License-Identifier: MIT */
/* glossary_base.c - helpers every glossary word uses: defining a table, throwing with a
 * message, popping arguments, checked locations and structures in the VM's data space,
 * structures made with a magic cell, metric conversion of lengths. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "glossary_internal.h"

fbrl_status gl_define(fbrl_vm *vm, fbrl_glossary *g, const gl_word *w, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        fbrl_status st = fbrl_vm_define(vm, w[i].name, w[i].fn, g, FBRL_DOC_STACK(w[i]), FBRL_DOC_HELP(w[i]));
        if (st != FBRL_OK)
            return st;
    }
    return FBRL_OK;
}

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

fbrl_status gl_pop(fbrl_vm *vm, size_t n, fbrl_cell *v)
{
    if (fbrl_vm_depth(vm) < n)
        return fbrl_vm_throw(vm, GL_STACK_UNDERFLOW, NULL);
    while (n--)
        fbrl_vm_pop(vm, &v[n]);
    return FBRL_OK;
}

/* The words pop their cells first, so the reals given as integers are the cells just
 * beneath them: vmx.h's one rule. */
fbrl_status gl_fpop(fbrl_vm *vm, size_t n, double *v)
{
    static const char reals[FBRL_VMX_MAXARGS + 1] = "RRRRRRRR";
    fbrl_vmx_val val[FBRL_VMX_MAXARGS];
    if (n > FBRL_VMX_MAXARGS)
        return FBRL_EINVAL;
    fbrl_status st = fbrl_vmx_args(vm, NULL, reals + FBRL_VMX_MAXARGS - n, NULL, FBRL_VMX_STACKS, val);
    for (size_t k = 0; st == FBRL_OK && k < n; k++)
        v[k] = val[k].f;
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
