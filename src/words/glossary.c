/* glossary.c - the data glossary in the language: installation and the C interface the
 * robot words use (locations in VM memory, mapping, units, PRINT-LOC's port). The words are
 * in glossary_loc.c (locations, matrices, metric), glossary_cal.c (calibration) and
 * glossary_file.c (data files); their shared helpers in glossary_base.c.
 *
 * Every word receives its VM's fbrl_glossary as arg. */
#include <string.h>
#include "glossary_internal.h"

fbrl_status fbrl_glossary_install(fbrl_vm *vm, fbrl_glossary *g)
{
    fbrl_status st;
    if (!vm || !g) return FBRL_EINVAL;
    memset(g, 0, sizeof *g);
    g->vm = vm;
    fbrl_units_init(&g->units);
    if ((st = gl_install_loc(vm, g)) != FBRL_OK || (st = gl_install_cal(vm, g)) != FBRL_OK ||
        (st = gl_install_file(vm, g)) != FBRL_OK)
        return st;
    g->magic = GL_INSTALLED;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_loc(fbrl_vm *vm, fbrl_cell addr, fbrl_loc **out)
{
    if (!vm || !out) return FBRL_EINVAL;
    if (!fbrl_vm_addr(vm, addr, sizeof(fbrl_loc)) || (fbrl_ucell)addr % sizeof(double)) return FBRL_ERANGE;
    *out = (fbrl_loc *)addr;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_calpts(fbrl_vm *vm, fbrl_cell addr, fbrl_calpts **out)
{
    if (!vm || !out) return FBRL_EINVAL;
    if (!fbrl_vm_addr(vm, addr, GL_PAYLOAD + sizeof(fbrl_calpts))) return FBRL_ERANGE;
    fbrl_calpts *c = fbrl_vmx_data(vm, addr, &gl_type_cal, sizeof(fbrl_calpts));
    if (!c) return FBRL_ETYPE;
    *out = c;
    return FBRL_OK;
}

const fbrl_units *fbrl_glossary_units(const fbrl_glossary *g) { return g ? &g->units : NULL; }

void fbrl_glossary_set_port_writer(fbrl_glossary *g, void (*write)(void *ctx, const char *s, size_t n),
                                   void *ctx)
{
    if (!g) return;
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
