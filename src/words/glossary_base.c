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
        fbrl_status st = fbrl_vm_define(vm, w[i].name, w[i].fn, g, w[i].stack, w[i].help);
        if (st != FBRL_OK) return st;
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
    return gl_throw(vm, FBRL_THROW_STATUS(st), "%s: %s", what, fbrl_status_str(st));
}

fbrl_status gl_pop(fbrl_vm *vm, size_t n, fbrl_cell *v)
{
    if (fbrl_vm_depth(vm) < n) return fbrl_vm_throw(vm, GL_STACK_UNDERFLOW, NULL);
    while (n--) fbrl_vm_pop(vm, &v[n]);
    return FBRL_OK;
}

fbrl_status gl_fpop(fbrl_vm *vm, size_t n, double *v)
{
    if (fbrl_vm_fdepth(vm) < n) return fbrl_vm_throw(vm, GL_FSTACK_UNDERFLOW, NULL);
    while (n--) fbrl_vm_fpop(vm, &v[n]);
    return FBRL_OK;
}

fbrl_status gl_push_flag(fbrl_vm *vm, int yes) { return fbrl_vm_push(vm, yes ? -1 : 0); }

fbrl_status gl_loc(fbrl_vm *vm, fbrl_cell a, int finite, const char *word, fbrl_loc **loc)
{
    if (!fbrl__addr_ok(vm, a, (fbrl_cell)sizeof(fbrl_loc)))
        return gl_throw(vm, GL_BAD_ADDRESS, "%s: address is not a location in data space", word);
    if ((fbrl_ucell)a % sizeof(double))
        return gl_throw(vm, GL_ALIGNMENT, "%s: location address not aligned to 8 bytes", word);
    if (finite && fbrl_loc_check((fbrl_loc *)a) != FBRL_OK)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: not a location (a component is not a finite number)",
                        word);
    *loc = (fbrl_loc *)a;
    return FBRL_OK;
}

static fbrl_cell align16(fbrl_cell a) { return (fbrl_cell)(((fbrl_ucell)a + 15) & ~(fbrl_ucell)15); }

fbrl_status gl_make(fbrl_vm *vm, fbrl_vm_prim run, fbrl_cell magic, size_t bytes, const char *stack,
                    const char *help, void **payload)
{
    unsigned char *here0 = vm->here;
    uint32_t nwords0 = vm->nwords;
    size_t total = (magic ? GL_PAYLOAD : 0) + bytes;
    fbrl_hdr *h;
    int r = fbrl__create(vm, run ? K_CFUNC : K_VAR, stack, help, &h);
    if (!r) r = fbrl__allot(vm, align16((fbrl_cell)vm->here) - (fbrl_cell)vm->here);
    if (!r) {
        h->body = (fbrl_cell)vm->here;
        r = fbrl__allot(vm, (fbrl_cell)total);
    }
    if (r) { /* no half-made word is left behind */
        if (vm->nwords != nwords0) fbrl__forget(vm, here0, nwords0, vm->req_used);
        return fbrl_vm_throw(vm, r, NULL);
    }
    memset((void *)h->body, 0, total);
    if (magic) memcpy((void *)h->body, &magic, sizeof magic);
    if (run) {
        h->fn = run;
        h->arg = (void *)h->body;
    }
    *payload = (void *)(h->body + (magic ? GL_PAYLOAD : 0));
    return FBRL_OK;
}

void *gl_struct(fbrl_vm *vm, fbrl_cell a, fbrl_cell magic, size_t bytes)
{
    fbrl_cell m;
    if ((fbrl_ucell)a % 16 || !fbrl__addr_ok(vm, a, GL_PAYLOAD + (fbrl_cell)bytes)) return NULL;
    memcpy(&m, (void *)a, sizeof m);
    return m == magic ? (void *)(a + GL_PAYLOAD) : NULL;
}

int gl_rigid(const fbrl_calib *c)
{
    /* The calib module's save accepts exactly the finite rigid motions. */
    unsigned char b[FBRL_CALIB_BYTES];
    return fbrl_calib_save(c, b, sizeof b) == FBRL_OK;
}

fbrl_status gl_stru(fbrl_vm *vm, fbrl_cell a, int rigid, const char *word, fbrl_calib **c)
{
    fbrl_calib *p = gl_struct(vm, a, MAGIC_STRU, sizeof(fbrl_calib));
    if (!p)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: not a calibration structure (use a CREATE-CAL-STRU name)",
                        word);
    if (rigid && !gl_rigid(p))
        return gl_throw(vm, FBRL_THROW_STATUS(FBRL_ESTATE),
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
    if (off) *off = 0.0;
    if (!g || g->magic != GL_INSTALLED || !g->vm || !loc) return FBRL_EINVAL;
    if (!g->map_on) return FBRL_OK;
    const fbrl_calib *c = gl_struct(g->vm, g->with_cal, MAGIC_STRU, sizeof(fbrl_calib));
    if (!c || !gl_rigid(c)) return FBRL_ESTATE;
    st = out ? fbrl_calib_map_arm(c, axis, loc, &res, &dev) : fbrl_calib_unmap_arm(c, axis, loc, &res, &dev);
    if (off) *off = dev;
    if (st == FBRL_OK && out && dev > FBRL_CALIB_AXIS_MAX) st = FBRL_ERANGE;
    if (st == FBRL_OK) *loc = res;
    return st;
}
