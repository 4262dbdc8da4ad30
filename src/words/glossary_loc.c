/* SPDX-License-Identifier: MIT */
/* glossary_loc.c - thesis appendix III location templates and matrices, and I-7 metric
 * conversion. Stored locations are always inches; with METRIC-ON the words that take or
 * give location lengths (GETX/SETX and Y Z, DEFINE-LOC, DISPLAY-LOC, PRINT-LOC, RECTMAT and
 * RADMAT distances, SHOW-AUTOMAT, SHOW-RADMAT) work in centimetres at the user side, as
 * thesis chapter 5.6 prescribes. */
#include <stdio.h>
#include <string.h>
#include "fbrl/matrix.h"
#include "glossary_internal.h"

/* ---- III-1 location templates ---- */
const char gl_loc_tag[] = "location";

fbrl_status fbrl_glossary_loc_word(const fbrl_vm *vm, fbrl_cell xt, fbrl_cell *addr)
{
    const void *tag = NULL;
    fbrl_cell a = 0;
    if (vm == NULL || addr == NULL)
        return FBRL_EINVAL;
    if (fbrl_vmx_tag(vm, xt, &tag, &a) != FBRL_OK || tag != (const void *)gl_loc_tag)
        return FBRL_ETYPE;
    *addr = a;
    return FBRL_OK;
}

static fbrl_status w_create_loc(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    (void)arg;
    return fbrl_vmx_create(vm, NULL, 0, NULL, sizeof(fbrl_loc), NULL, (void *)(uintptr_t)gl_loc_tag,
                           GL_LOC_STACK, GL_LOC_HELP, NULL, NULL);
}

static fbrl_status get_axis(fbrl_vm *vm, fbrl_glossary *g, const void *row, fbrl_loc_axis ax,
                            const char *word)
{
    fbrl_cell a;
    fbrl_loc *loc;
    double v;
    fbrl_status st;
    if ((st = gl_args(vm, row, &a, NULL)) || (st = gl_loc(vm, a, 1, word, &loc)))
        return st;
    fbrl_loc_get(loc, ax, &v);
    if (ax <= FBRL_LOC_Z && (st = gl_out(vm, g, v, &v)))
        return st;
    return fbrl_vm_fpush(vm, v);
}

static fbrl_status set_axis(fbrl_vm *vm, fbrl_glossary *g, const void *row, fbrl_loc_axis ax,
                            const char *word)
{
    fbrl_cell a;
    fbrl_loc *loc;
    double v;
    fbrl_status st;
    if ((st = gl_args(vm, row, &a, &v)) || (st = gl_loc(vm, a, 0, word, &loc)))
        return st;
    if (ax <= FBRL_LOC_Z && (st = gl_in(vm, g, v, &v)))
        return st;
    if ((st = fbrl_loc_set(loc, ax, v)) != FBRL_OK)
        return gl_throw_st(vm, st, word);
    return FBRL_OK;
}

#define AXIS(L, AX)                                                     \
    static fbrl_status w_get##L(fbrl_vm *vm, void *g, const void *word) \
    {                                                                   \
        return get_axis(vm, g, word, AX, "GET" #L);                     \
    }                                                                   \
    static fbrl_status w_set##L(fbrl_vm *vm, void *g, const void *word) \
    {                                                                   \
        return set_axis(vm, g, word, AX, "SET" #L);                     \
    }
AXIS(X, FBRL_LOC_X)
AXIS(Y, FBRL_LOC_Y)
AXIS(Z, FBRL_LOC_Z)
AXIS(O, FBRL_LOC_O)
AXIS(A, FBRL_LOC_A)
AXIS(T, FBRL_LOC_T)
#undef AXIS

static fbrl_status w_set_loc(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_cell a[2];
    fbrl_loc *dst, *src;
    fbrl_status st;
    (void)arg;
    if ((st = gl_args(vm, word, a, NULL)) || (st = gl_loc(vm, a[0], 0, "SET-LOC", &dst)) ||
        (st = gl_loc(vm, a[1], 1, "SET-LOC", &src)))
        return st;
    fbrl_loc tmp = *src; /* the two may overlap in part */
    fbrl_loc_copy(dst, &tmp);
    return FBRL_OK;
}

static fbrl_status w_define_loc(fbrl_vm *vm, void *g, const void *word)
{
    fbrl_cell a;
    fbrl_loc *loc;
    double v[6];
    fbrl_status st;
    if ((st = gl_args(vm, word, &a, v)) || (st = gl_loc(vm, a, 0, "DEFINE-LOC", &loc)))
        return st;
    for (int i = 0; i < 3; i++)
        if ((st = gl_in(vm, g, v[i], &v[i])))
            return st;
    if ((st = fbrl_loc_define(loc, v[0], v[1], v[2], v[3], v[4], v[5])) != FBRL_OK)
        return gl_throw_st(vm, st, "DEFINE-LOC");
    return FBRL_OK;
}

static fbrl_status w_shifta(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_cell a[2];
    fbrl_loc *loc, *by;
    fbrl_status st;
    (void)arg;
    if ((st = gl_args(vm, word, a, NULL)) || (st = gl_loc(vm, a[0], 1, "SHIFTA", &loc)) ||
        (st = gl_loc(vm, a[1], 1, "SHIFTA", &by)))
        return st;
    if ((st = fbrl_loc_shift(loc, by)) != FBRL_OK)
        return gl_throw_st(vm, st, "SHIFTA");
    return FBRL_OK;
}

/* DISPLAY-LOC / PRINT-LOC text: the location as the arm will see it (mapped when MAP-ON),
 * in the user's units. */
static fbrl_status loc_text(fbrl_vm *vm, fbrl_glossary *g, const void *row, char *buf, size_t size)
{
    const char *word = ((const gl_word *)row)->name;
    fbrl_cell a;
    fbrl_loc *loc, shown;
    fbrl_status st;
    if ((st = gl_args(vm, row, &a, NULL)) || (st = gl_loc(vm, a, 1, word, &loc)))
        return st;
    shown = *loc;
    if ((st = gl_map(g, &shown, 1, NULL, NULL)) != FBRL_OK) {
        if (st == FBRL_ESTATE)
            return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st),
                            "%s: mapping on but the WITH-CAL structure is unusable", word);
        return gl_throw_st(vm, st, word);
    }
    if ((st = fbrl_loc_format(&shown, g->units.metric, buf, size)) != FBRL_OK)
        return gl_throw_st(vm, st, word);
    return FBRL_OK;
}

static fbrl_status w_display_loc(fbrl_vm *vm, void *g, const void *word)
{
    char buf[FBRL_LOC_TEXT_SIZE * 2];
    fbrl_status st = loc_text(vm, g, word, buf, sizeof buf - 1);
    if (st)
        return st;
    strcat(buf, "\n");
    fbrl_vmx_puts(vm, buf);
    return FBRL_OK;
}

static fbrl_status w_print_loc(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_glossary *g = arg;
    char buf[FBRL_LOC_TEXT_SIZE * 2];
    fbrl_status st;
    if (!g->port_write) {
        fbrl_cell a;
        if ((st = gl_args(vm, word, &a, NULL)))
            return st;
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE), "PRINT-LOC: no communication port");
    }
    if ((st = loc_text(vm, g, word, buf, sizeof buf - 2)))
        return st;
    strcat(buf, "\r\n");
    g->port_write(g->port_ctx, buf, strlen(buf));
    return FBRL_OK;
}

/* ---- III-2 location matrices ---- */

static fbrl_status index3(fbrl_vm *vm, const char *word, long *idx, fbrl_loc **loc)
{
    fbrl_vmx_val a[4]; /* a matrix word runs without a row: its parameters by the same parser */
    fbrl_status st;
    if ((st = fbrl_vmx_args(vm, word, "IIIA", NULL, FBRL_VMX_STACKS, a)) ||
        (st = gl_loc(vm, a[3].i, 0, word, loc)))
        return st;
    for (int i = 0; i < 3; i++) {
        if (a[i].i < -1000000 || a[i].i > 1000000)
            return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "%s: matrix index out of range", word);
        idx[i] = (long)a[i].i;
    }
    return FBRL_OK;
}

fbrl_status gl_rect_run(fbrl_vm *vm, void *ctx, const void *body)
{
    (void)ctx;
    long i[3];
    fbrl_loc *loc, out;
    fbrl_status st;
    const fbrl_rectmat *m = fbrl_vmx_data(vm, (fbrl_cell)body, &gl_type_rect, sizeof(fbrl_rectmat));
    if (!m)
        return gl_throw(vm, GL_BAD_ADDRESS, "RECTMAT: matrix structure overwritten");
    if ((st = index3(vm, "RECTMAT", i, &loc)))
        return st;
    if ((st = fbrl_rectmat_loc(m, i[0], i[1], i[2], &out)) != FBRL_OK)
        return gl_throw_st(vm, st, "RECTMAT");
    *loc = out; /* through a copy: loc could lie over the matrix itself */
    return FBRL_OK;
}

fbrl_status gl_rad_run(fbrl_vm *vm, void *ctx, const void *body)
{
    (void)ctx;
    long i[3];
    fbrl_loc *loc, out;
    fbrl_status st;
    const fbrl_radmat *m = fbrl_vmx_data(vm, (fbrl_cell)body, &gl_type_rad, sizeof(fbrl_radmat));
    if (!m)
        return gl_throw(vm, GL_BAD_ADDRESS, "RADMAT: matrix structure overwritten");
    if ((st = index3(vm, "RADMAT", i, &loc)))
        return st;
    if ((st = fbrl_radmat_loc(m, i[0], i[1], i[2], &out)) != FBRL_OK)
        return gl_throw_st(vm, st, "RADMAT");
    *loc = out;
    return FBRL_OK;
}

/* base-loc ( F: a b c ) "name": the base and three numbers, the two lengths (d... or
 * ring-dist, z-off) in user units. */
static fbrl_status mat_args(fbrl_vm *vm, fbrl_glossary *g, const void *row, int first_len, fbrl_loc **base,
                            double *v)
{
    const char *word = ((const gl_word *)row)->name;
    fbrl_cell a;
    fbrl_status st;
    if ((st = gl_args(vm, row, &a, v)) || (st = gl_loc(vm, a, 1, word, base)))
        return st;
    for (int i = first_len; i < 3; i++)
        if ((st = gl_in(vm, g, v[i], &v[i])))
            return st;
    return FBRL_OK;
}

static fbrl_status w_rectmat(fbrl_vm *vm, void *g, const void *word)
{
    fbrl_loc *base;
    double v[3];
    fbrl_rectmat m;
    void *p;
    fbrl_status st;
    if ((st = mat_args(vm, g, word, 0, &base, v)))
        return st;
    if ((st = fbrl_rectmat_init(&m, base, v[0], v[1], v[2])) != FBRL_OK)
        return gl_throw_st(vm, st, "RECTMAT");
    if ((st = gl_make(vm, gl_rect_run, &gl_type_rect, sizeof m, GL_RECT_STACK, GL_RECT_HELP, &p)))
        return st;
    memcpy(p, &m, sizeof m);
    return FBRL_OK;
}

static fbrl_status w_radmat(fbrl_vm *vm, void *g, const void *word)
{
    fbrl_loc *base;
    double v[3];
    fbrl_radmat m;
    void *p;
    fbrl_status st;
    if ((st = mat_args(vm, g, word, 1, &base, v)))
        return st;
    st = fbrl_radmat_init(&m, base, v[0], v[1], v[2]);
    if (st == FBRL_ERANGE)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st),
                        "RADMAT: base location on the centre axis has no angle");
    if (st != FBRL_OK)
        return gl_throw_st(vm, st, "RADMAT");
    if ((st = gl_make(vm, gl_rad_run, &gl_type_rad, sizeof m, GL_RAD_STACK, GL_RAD_HELP, &p)))
        return st;
    memcpy(p, &m, sizeof m);
    return FBRL_OK;
}

/* SHOW-AUTOMAT / SHOW-RADMAT ( xt -- ): a matrix name runs the matrix, so it is named by its
 * execution token (' MAT). */
static fbrl_status w_show(fbrl_vm *vm, fbrl_glossary *g, const void *row, int rad)
{
    const char *word = rad ? "SHOW-RADMAT" : "SHOW-AUTOMAT";
    char buf[FBRL_MATRIX_TEXT_SIZE * 2];
    fbrl_cell xt;
    fbrl_status st;
    if ((st = gl_args(vm, row, &xt, NULL)))
        return st;
    fbrl_cell body;
    if (fbrl_vmx_created(vm, xt, rad ? gl_rad_run : gl_rect_run, &body) != FBRL_OK)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: not a %s (pass its execution token: ' name)", word,
                        rad ? "RADMAT" : "RECTMAT");
    const void *m = fbrl_vmx_data(vm, body, rad ? &gl_type_rad : &gl_type_rect,
                                  rad ? sizeof(fbrl_radmat) : sizeof(fbrl_rectmat));
    if (!m)
        return gl_throw(vm, GL_BAD_ADDRESS, "%s: matrix structure overwritten", word);
    st = rad ? fbrl_radmat_format(m, g->units.metric, buf, sizeof buf - 1)
             : fbrl_rectmat_format(m, g->units.metric, buf, sizeof buf - 1);
    if (st != FBRL_OK)
        return gl_throw_st(vm, st, word);
    strcat(buf, "\n");
    fbrl_vmx_puts(vm, buf);
    return FBRL_OK;
}
static fbrl_status w_show_automat(fbrl_vm *vm, void *g, const void *word) { return w_show(vm, g, word, 0); }
static fbrl_status w_show_radmat(fbrl_vm *vm, void *g, const void *word) { return w_show(vm, g, word, 1); }

/* ---- I-7 metric conversion ---- */
static fbrl_status w_metric_on(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    (void)vm;
    return fbrl_units_metric_on(&((fbrl_glossary *)arg)->units);
}
static fbrl_status w_metric_off(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    (void)vm;
    return fbrl_units_metric_off(&((fbrl_glossary *)arg)->units);
}
static fbrl_status w_metric_q(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    return gl_push_flag(vm, ((fbrl_glossary *)arg)->units.metric);
}

enum { CONV_CM_IN, CONV_IN_CM, CONV_IN, CONV_OUT };
static fbrl_status convert(fbrl_vm *vm, fbrl_glossary *g, const void *row, int how, const char *word)
{
    double v;
    fbrl_status st;
    if ((st = gl_args(vm, row, NULL, &v)))
        return st;
    switch (how) {
    case CONV_CM_IN: st = fbrl_units_cm_to_in(v, &v); break;
    case CONV_IN_CM: st = fbrl_units_in_to_cm(v, &v); break;
    case CONV_IN: st = fbrl_units_in(&g->units, v, &v); break;
    default: st = fbrl_units_out(&g->units, v, &v); break;
    }
    if (st != FBRL_OK)
        return gl_throw_st(vm, st, word);
    return fbrl_vm_fpush(vm, v);
}
static fbrl_status w_cm_in(fbrl_vm *vm, void *g, const void *word)
{
    return convert(vm, g, word, CONV_CM_IN, "CM->IN");
}
static fbrl_status w_in_cm(fbrl_vm *vm, void *g, const void *word)
{
    return convert(vm, g, word, CONV_IN_CM, "IN->CM");
}
static fbrl_status w_metric_in(fbrl_vm *vm, void *g, const void *word)
{
    return convert(vm, g, word, CONV_IN, "METRIC-IN");
}
static fbrl_status w_metric_out(fbrl_vm *vm, void *g, const void *word)
{
    return convert(vm, g, word, CONV_OUT, "METRIC-OUT");
}

static const gl_word loc_words[] = {
    {"CREATE-LOC", w_create_loc, "", 0, 0, 0,
     FBRL_DOC("( \"name\" -- ) ( run: -- loc )",
              "make a location template (6 floats X Y Z O A T, 48 bytes, zeroed); name pushes its address")},
    {"GETX", w_getX, "A", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: -- x )", "x of the location (cm when METRIC-ON)")},
    {"GETY", w_getY, "A", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: -- y )", "y of the location (cm when METRIC-ON)")},
    {"GETZ", w_getZ, "A", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: -- z )", "z of the location (cm when METRIC-ON)")},
    {"GETO", w_getO, "A", 0, 0, 0, FBRL_DOC("( loc -- ) ( F: -- o )", "yaw (O) of the location, degrees")},
    {"GETA", w_getA, "A", 0, 0, 0, FBRL_DOC("( loc -- ) ( F: -- a )", "pitch (A) of the location, degrees")},
    {"GETT", w_getT, "A", 0, 0, 0, FBRL_DOC("( loc -- ) ( F: -- t )", "roll (T) of the location, degrees")},
    {"SETX", w_setX, "RA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: x -- )", "set x of the location (cm when METRIC-ON)")},
    {"SETY", w_setY, "RA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: y -- )", "set y of the location (cm when METRIC-ON)")},
    {"SETZ", w_setZ, "RA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: z -- )", "set z of the location (cm when METRIC-ON)")},
    {"SETO", w_setO, "RA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: o -- )", "set yaw (O) of the location, degrees")},
    {"SETA", w_setA, "RA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: a -- )", "set pitch (A) of the location, degrees")},
    {"SETT", w_setT, "RA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: t -- )", "set roll (T) of the location, degrees")},
    {"SET-LOC", w_set_loc, "AA", 0, 0, 0, FBRL_DOC("( loc1 loc2 -- )", "copy location loc2 into loc1")},
    {"DEFINE-LOC", w_define_loc, "RRRRRRA", 0, 0, 0,
     FBRL_DOC("( loc -- ) ( F: x y z o a t -- )",
              "set all six components (x y z in cm when METRIC-ON; angles in degrees)")},
    {"SHIFTA", w_shifta, "AA", 0, 0, 0, FBRL_DOC("( loc1 loc2 -- )", "add every component of loc2 to loc1")},
    {"DISPLAY-LOC", w_display_loc, "A", 0, 0, 0,
     FBRL_DOC("( loc -- )", "print the location on the console (mapped when MAP-ON, cm when METRIC-ON)")},
    {"PRINT-LOC", w_print_loc, "A", 0, 0, 0,
     FBRL_DOC("( loc -- )", "send DISPLAY-LOC's text (and CR LF) to the communication port")},
    {"RECTMAT", w_rectmat, "RRRA", 0, 0, 0,
     FBRL_DOC("( base-loc \"name\" -- ) ( F: dx dy dz -- ) ( run: i j k loc -- )",
              "make a rectangular matrix: name stores base + (i*dx, j*dy, k*dz) into loc")},
    {"AUTOMAT", w_rectmat, "RRRA", 0, 0, 0,
     FBRL_DOC("( base-loc \"name\" -- ) ( F: dx dy dz -- ) ( run: i j k loc -- )",
              "RECTMAT (the thesis's other name for it)")},
    {"RADMAT", w_radmat, "RRRA", 0, 0, 0,
     FBRL_DOC("( base-loc \"name\" -- ) ( F: inc-angle ring-dist z-off -- ) ( run: ring idx k loc -- )",
              "make a radial matrix about the arm's axis (inc-angle in radians)")},
    {"SHOW-AUTOMAT", w_show_automat, "I", 0, 0, 0,
     FBRL_DOC("( xt -- )", "print a RECTMAT's base and steps (' name SHOW-AUTOMAT)")},
    {"SHOW-RADMAT", w_show_radmat, "I", 0, 0, 0,
     FBRL_DOC("( xt -- )", "print a RADMAT's base, steps, radius and angle (' name SHOW-RADMAT)")},
    {"METRIC-ON", w_metric_on, "", 0, 0, 0,
     FBRL_DOC("( -- )", "location lengths in centimetres at the user side")},
    {"METRIC-OFF", w_metric_off, "", 0, 0, 0,
     FBRL_DOC("( -- )", "location lengths in inches at the user side (the default)")},
    {"METRIC?", w_metric_q, "", 0, 0, 0, FBRL_DOC("( -- flag )", "true if METRIC-ON")},
    {"CM->IN", w_cm_in, "R", 0, 0, 0, FBRL_DOC("( F: cm -- in )", "centimetres to inches")},
    {"IN->CM", w_in_cm, "R", 0, 0, 0, FBRL_DOC("( F: in -- cm )", "inches to centimetres")},
    {"METRIC-IN", w_metric_in, "R", 0, 0, 0,
     FBRL_DOC("( F: user -- in )", "a length the user gave (cm if METRIC-ON) to inches")},
    {"METRIC-OUT", w_metric_out, "R", 0, 0, 0,
     FBRL_DOC("( F: in -- user )", "inches to the user's unit (cm if METRIC-ON)")},
};

fbrl_status gl_install_loc(fbrl_vm *vm, fbrl_glossary *g)
{
    return fbrl_vmx_define_table(vm, loc_words, sizeof loc_words / sizeof loc_words[0], g);
}
