/* SPDX-License-Identifier: MIT */
/* glossary.c - the data glossary in the language: installation and the C interface the
 * robot words use (locations in VM memory, mapping, units, PRINT-LOC's port). The words are
 * in glossary_loc.c (locations, matrices, metric), glossary_cal.c (calibration) and
 * glossary_file.c (data files); their shared helpers in glossary_base.c.
 *
 * Every word receives its VM's fbrl_glossary as arg. */
#include <stdint.h>
#include <string.h>
#include "fbrl/matrix.h"
#include "glossary_internal.h"

fbrl_status fbrl_glossary_install(fbrl_vm *vm, fbrl_glossary *g)
{
    fbrl_status st;
    if (!vm || !g)
        return FBRL_EINVAL;
    memset(g, 0, sizeof *g);
    g->vm = vm;
    fbrl_units_init(&g->units);
    /* the glossary stands on the data words (thesis I-1 .. I-3: LOCATION, ARRAY ...) */
    if ((st = fbrl_vmx_data_words(vm)) != FBRL_OK || (st = gl_install_loc(vm, g)) != FBRL_OK ||
        (st = gl_install_cal(vm, g)) != FBRL_OK || (st = gl_install_file(vm, g)) != FBRL_OK)
        return st;
    g->magic = GL_INSTALLED;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_loc(fbrl_vm *vm, fbrl_cell addr, fbrl_loc **out)
{
    if (!vm || !out)
        return FBRL_EINVAL;
    if (!fbrl_vm_addr(vm, addr, sizeof(fbrl_loc)) || (fbrl_ucell)addr % sizeof(double))
        return FBRL_ERANGE;
    *out = (fbrl_loc *)addr;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_calpts(fbrl_vm *vm, fbrl_cell addr, fbrl_calpts **out)
{
    if (!vm || !out)
        return FBRL_EINVAL;
    if (!fbrl_vm_addr(vm, addr, GL_PAYLOAD + sizeof(fbrl_calpts)))
        return FBRL_ERANGE;
    fbrl_calpts *c = fbrl_vmx_data(vm, addr, &gl_type_cal, sizeof(fbrl_calpts));
    if (!c)
        return FBRL_ETYPE;
    *out = c;
    return FBRL_OK;
}

const fbrl_units *fbrl_glossary_units(const fbrl_glossary *g) { return g ? &g->units : NULL; }

void fbrl_glossary_set_port_writer(fbrl_glossary *g, void (*write)(void *ctx, const char *s, size_t n),
                                   void *ctx)
{
    if (!g)
        return;
    g->port_write = write;
    g->port_ctx = write ? ctx : NULL;
}

fbrl_status fbrl_glossary_map_out(const fbrl_glossary *g, fbrl_loc *loc, const double axis[2], double *off)
{
    return gl_map(g, loc, 1, axis, off);
}
fbrl_status fbrl_glossary_map_in(const fbrl_glossary *g, fbrl_loc *loc, const double axis[2])
{
    return gl_map(g, loc, 0, axis, NULL);
}

fbrl_status fbrl_glossary_object(fbrl_glossary *g, fbrl_cell xt, fbrl_glossary_kind *kind, void **obj)
{
    const void *tag;
    fbrl_cell a;
    void *p = NULL;
    if (!g || g->magic != GL_INSTALLED || !kind || !obj)
        return FBRL_EINVAL;
    fbrl_vm *vm = g->vm;
    *kind = FBRL_GLOSSARY_NONE;
    *obj = NULL;
    if (fbrl_vmx_tag(vm, xt, &tag, &a) == FBRL_OK) {
        if (tag == gl_loc_tag && fbrl_glossary_loc(vm, a, (fbrl_loc **)&p) == FBRL_OK)
            *kind = FBRL_GLOSSARY_LOC;
        else if ((p = fbrl_vmx_data(vm, a, &gl_type_cal, sizeof(fbrl_calpts))) != NULL)
            *kind = FBRL_GLOSSARY_CAL;
        else if ((p = fbrl_vmx_data(vm, a, &gl_type_stru, sizeof(fbrl_calib))) != NULL)
            *kind = FBRL_GLOSSARY_CALSTRU;
    } else if (fbrl_vmx_created(vm, xt, gl_rect_run, &a) == FBRL_OK) {
        if ((p = fbrl_vmx_data(vm, a, &gl_type_rect, sizeof(fbrl_rectmat))) != NULL)
            *kind = FBRL_GLOSSARY_RECTMAT;
    } else if (fbrl_vmx_created(vm, xt, gl_rad_run, &a) == FBRL_OK) {
        if ((p = fbrl_vmx_data(vm, a, &gl_type_rad, sizeof(fbrl_radmat))) != NULL)
            *kind = FBRL_GLOSSARY_RADMAT;
    }
    if (*kind != FBRL_GLOSSARY_NONE)
        *obj = p;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_make(fbrl_glossary *g, fbrl_glossary_kind kind, const char *name, size_t len,
                               void **obj)
{
    fbrl_cell a;
    void *p = NULL;
    fbrl_status st;
    if (!g || g->magic != GL_INSTALLED || !name || !obj)
        return FBRL_EINVAL;
    fbrl_vm *vm = g->vm;
    switch (kind) {
    case FBRL_GLOSSARY_LOC:
        st = fbrl_vmx_create(vm, name, len, NULL, sizeof(fbrl_loc), NULL, (void *)(uintptr_t)gl_loc_tag,
                             GL_LOC_STACK, GL_LOC_HELP, &a, &p);
        break;
    case FBRL_GLOSSARY_RECTMAT:
        st = fbrl_vmx_create(vm, name, len, &gl_type_rect, sizeof(fbrl_rectmat), gl_rect_run, NULL,
                             GL_RECT_STACK, GL_RECT_HELP, &a, &p);
        break;
    case FBRL_GLOSSARY_RADMAT:
        st = fbrl_vmx_create(vm, name, len, &gl_type_rad, sizeof(fbrl_radmat), gl_rad_run, NULL, GL_RAD_STACK,
                             GL_RAD_HELP, &a, &p);
        break;
    case FBRL_GLOSSARY_CAL:
        st = fbrl_vmx_create(vm, name, len, &gl_type_cal, sizeof(fbrl_calpts), NULL, NULL, GL_CAL_STACK,
                             GL_CAL_HELP, &a, &p);
        break;
    case FBRL_GLOSSARY_CALSTRU:
        st = fbrl_vmx_create(vm, name, len, &gl_type_stru, sizeof(fbrl_calib), NULL, NULL, GL_STRU_STACK,
                             GL_STRU_HELP, &a, &p);
        if (st == FBRL_OK)
            st = fbrl_calib_identity(p);
        break;
    default: return FBRL_EINVAL;
    }
    if (st == FBRL_OK)
        *obj = p;
    return st;
}

fbrl_status fbrl_glossary_mapping(const fbrl_glossary *g, fbrl_cell *with_cal, int *map_on)
{
    if (!g || g->magic != GL_INSTALLED || !with_cal || !map_on)
        return FBRL_EINVAL;
    *with_cal = g->with_cal;
    *map_on = g->map_on;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_set_mapping(fbrl_glossary *g, fbrl_cell with_cal, int map_on)
{
    if (!g || g->magic != GL_INSTALLED)
        return FBRL_EINVAL;
    const fbrl_calib *c = with_cal ? fbrl_vmx_data(g->vm, with_cal, &gl_type_stru, sizeof(fbrl_calib)) : NULL;
    if (with_cal && !c)
        return FBRL_ETYPE;
    if (map_on && (!c || !gl_rigid(c)))
        return FBRL_ESTATE;
    g->with_cal = with_cal;
    g->map_on = map_on != 0;
    return FBRL_OK;
}
