/* SPDX-License-Identifier: MIT */
/* glossary_cal.c - three-dimensional calibration and mapping words (thesis appendix II),
 * bound to the calib module.
 *
 * CREATE-CAL makes three location slots numbered 1 2 3 (P1 origin, P2 on the block's x
 * axis, P3 in its plane). CREATE-CAL-STRU makes a calibration structure: the rigid motion
 * p_moved = r p_original + t of the calib module (the thesis kept 11 intermediate angles
 * instead). CAL-STRU@ and CAL-STRU! address it as the 3x4 matrix [r | t] row by row:
 * index 1..3 = r row 1, 4 = t x, 5..7 = r row 2, 8 = t y, 9..11 = r row 3, 12 = t z
 * (inches). A new structure holds the identity (block not moved). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "fbrl/calib.h"
#include "fbrl/num.h"
#include "glossary_internal.h"

/* The three slots of a CREATE-CAL structure at a, or throw. */
static fbrl_status cal_at(fbrl_vm *vm, fbrl_cell a, const char *word, fbrl_calpts **c)
{
    *c = fbrl_vmx_data(vm, a, &gl_type_cal, sizeof(fbrl_calpts));
    if (!*c)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: not a calibration (use a CREATE-CAL name)", word);
    return FBRL_OK;
}

static fbrl_status slot_index(fbrl_vm *vm, fbrl_cell i, const char *word)
{
    if (i < 1 || i > 3)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "%s: slot must be 1, 2 or 3", word);
    return FBRL_OK;
}

/* ---- II-1 calibration abstraction ---- */
static fbrl_status w_map_on(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    fbrl_glossary *g = arg;
    fbrl_calib *c;
    fbrl_status st;
    if (!g->with_cal)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ESTATE),
                        "MAP-ON: no calibration selected (cal-stru WITH-CAL)");
    if ((st = gl_stru(vm, g->with_cal, 1, "MAP-ON", &c)))
        return st;
    g->map_on = 1;
    return FBRL_OK;
}

static fbrl_status w_map_off(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    (void)vm;
    ((fbrl_glossary *)arg)->map_on = 0;
    return FBRL_OK;
}

static fbrl_status w_mapping_q(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    return gl_push_flag(vm, ((fbrl_glossary *)arg)->map_on);
}

static fbrl_status w_with_cal(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_glossary *g = arg;
    fbrl_cell a;
    fbrl_calib *c;
    fbrl_status st;
    if ((st = gl_args(vm, word, &a, NULL)) || (st = gl_stru(vm, a, 0, "WITH-CAL", &c)))
        return st;
    g->with_cal = a;
    return FBRL_OK;
}

static fbrl_status w_create_cal(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    void *p;
    (void)arg;
    return gl_make(vm, NULL, &gl_type_cal, sizeof(fbrl_calpts), GL_CAL_STACK, GL_CAL_HELP, &p);
}

static fbrl_status w_cal_addr(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_cell a[2];
    fbrl_calpts *c;
    fbrl_status st;
    (void)arg;
    if ((st = gl_args(vm, word, a, NULL)) || (st = cal_at(vm, a[0], "CAL-ADDR", &c)) ||
        (st = slot_index(vm, a[1], "CAL-ADDR")))
        return st;
    return fbrl_vm_push(vm, (fbrl_cell)&c->p[a[1] - 1]);
}

/* SET-CAL (cal index loc --) and GET-CAL (cal index loc --) */
static fbrl_status set_get_cal(fbrl_vm *vm, const void *word_row, int set)
{
    const char *word = set ? "SET-CAL" : "GET-CAL";
    fbrl_cell a[3];
    fbrl_calpts *c;
    fbrl_loc *loc;
    fbrl_status st;
    if ((st = gl_args(vm, word_row, a, NULL)) || (st = cal_at(vm, a[0], word, &c)) ||
        (st = slot_index(vm, a[1], word)) || (st = gl_loc(vm, a[2], set, word, &loc)))
        return st;
    /* through a copy: loc may overlap a slot in part */
    fbrl_loc tmp;
    if (set) {
        tmp = *loc;
        st = fbrl_calpts_set(c, (int)a[1], &tmp);
    } else if ((st = fbrl_calpts_get(c, (int)a[1], &tmp)) == FBRL_OK) {
        *loc = tmp;
    }
    return st == FBRL_OK ? st : gl_throw_st(vm, st, word);
}
static fbrl_status w_set_cal(fbrl_vm *vm, void *arg, const void *word)
{
    (void)arg;
    return set_get_cal(vm, word, 1);
}
static fbrl_status w_get_cal(fbrl_vm *vm, void *arg, const void *word)
{
    (void)arg;
    return set_get_cal(vm, word, 0);
}

static fbrl_status w_create_cal_stru(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    void *p;
    fbrl_status st;
    (void)arg;
    if ((st = gl_make(vm, NULL, &gl_type_stru, sizeof(fbrl_calib), GL_STRU_STACK, GL_STRU_HELP, &p)))
        return st;
    return fbrl_calib_identity(p);
}

/* ( [F: r] cal-stru index -- ): the entry, and for CAL-STRU! its value *f */
static fbrl_status stru_entry(fbrl_vm *vm, const void *w, fbrl_calib **c, double **e, double *f)
{
    const char *word = ((const gl_word *)w)->name;
    fbrl_cell a[2];
    fbrl_status st;
    if ((st = gl_args(vm, w, a, f)) || (st = gl_stru(vm, a[0], 0, word, c)))
        return st;
    if (a[1] < 1 || a[1] > 12)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "%s: index must be 1..12", word);
    int row = (int)(a[1] - 1) / 4, col = (int)(a[1] - 1) % 4;
    *e = col < 3 ? &(*c)->r[row][col] : &(*c)->t[row];
    return FBRL_OK;
}

static fbrl_status w_cal_stru_fetch(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_calib *c;
    double *e = NULL;
    fbrl_status st;
    (void)arg;
    if ((st = stru_entry(vm, word, &c, &e, NULL)))
        return st;
    return fbrl_vm_fpush(vm, *e);
}

static fbrl_status w_cal_stru_store(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_calib *c;
    double *e = NULL, v = 0.0;
    fbrl_status st;
    (void)arg;
    if ((st = stru_entry(vm, word, &c, &e, &v)))
        return st;
    if (!isfinite(v))
        return gl_throw_st(vm, FBRL_ENONFINITE, "CAL-STRU!");
    *e = v;
    return FBRL_OK;
}

static fbrl_status w_num_cal_cells(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    (void)arg;
    return fbrl_vm_push(vm, 12);
}

/* ---- II-2 calibration transformation ---- */
static fbrl_status w_ang_from_origin(fbrl_vm *vm, void *arg, const void *word)
{
    double v[4], ang;
    fbrl_status st;
    (void)arg;
    if ((st = gl_args(vm, word, NULL, v)))
        return st;
    st = fbrl_calib_ang_from_origin(v[0], v[1], v[2], v[3], &ang);
    if (st == FBRL_EDEGENERATE)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st), "ANG-FROM-ORIGIN: the two points coincide");
    if (st != FBRL_OK)
        return gl_throw_st(vm, st, "ANG-FROM-ORIGIN");
    return fbrl_vm_fpush(vm, ang);
}

static fbrl_status w_rotate(fbrl_vm *vm, void *arg, const void *word)
{
    double v[3], x, y;
    fbrl_status st;
    (void)arg;
    if ((st = gl_args(vm, word, NULL, v)))
        return st;
    if ((st = fbrl_calib_rotate(v[0], v[1], v[2], &x, &y)) != FBRL_OK)
        return gl_throw_st(vm, st, "ROTATE");
    fbrl_vm_fpush(vm, x);
    return fbrl_vm_fpush(vm, y);
}

/* Name which point set is degenerate, so the user knows which block to re-teach. */
static fbrl_status degenerate(fbrl_vm *vm, const char *word, const char *which)
{
    return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EDEGENERATE),
                    "%s: %s points coincident or collinear (degenerate calibration)", word, which);
}

static fbrl_status w_calibrate(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_cell a[3];
    fbrl_calpts *recal, *cal;
    fbrl_calib *c, frame;
    fbrl_status st;
    (void)arg;
    if ((st = gl_args(vm, word, a, NULL)) || (st = cal_at(vm, a[0], "CALIBRATE", &recal)) ||
        (st = cal_at(vm, a[1], "CALIBRATE", &cal)) || (st = gl_stru(vm, a[2], 0, "CALIBRATE", &c)))
        return st;
    if (fbrl_calib_frame(cal, &frame) == FBRL_EDEGENERATE)
        return degenerate(vm, "CALIBRATE", "calibration");
    if (fbrl_calib_frame(recal, &frame) == FBRL_EDEGENERATE)
        return degenerate(vm, "CALIBRATE", "recalibration");
    if ((st = fbrl_calib_3point(c, cal, recal)) != FBRL_OK)
        return gl_throw_st(vm, st, "CALIBRATE");
    return FBRL_OK;
}

/* (MAP) and UNMAP ( cal-stru loc -- ) */
static fbrl_status map_word(fbrl_vm *vm, const void *row, int out)
{
    const char *word = out ? "(MAP)" : "UNMAP";
    fbrl_cell a[2];
    fbrl_calib *c;
    fbrl_loc *loc;
    fbrl_status st;
    if ((st = gl_args(vm, row, a, NULL)) || (st = gl_stru(vm, a[0], 1, word, &c)) ||
        (st = gl_loc(vm, a[1], 1, word, &loc)))
        return st;
    double off = 0.0;
    fbrl_loc res;
    st = out ? fbrl_calib_map_arm(c, NULL, loc, &res, &off) : fbrl_calib_unmap(c, loc, &res);
    if (st == FBRL_OK && off <= FBRL_CALIB_AXIS_MAX)
        *loc = res;
    if (st == FBRL_OK && off > FBRL_CALIB_AXIS_MAX) {
        char deg[32];
        fbrl_num_fixed(deg, sizeof deg, off, 0, 2, 0, NULL);
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE),
                        "%s: tool axis %s deg across the arm (a 5-axis arm cannot follow)", word, deg);
    }
    return st == FBRL_OK ? st : gl_throw_st(vm, st, word);
}
static fbrl_status w_map(fbrl_vm *vm, void *arg, const void *word)
{
    (void)arg;
    return map_word(vm, word, 1);
}
static fbrl_status w_unmap(fbrl_vm *vm, void *arg, const void *word)
{
    (void)arg;
    return map_word(vm, word, 0);
}

/* CALIBRATE-N ( n cal-locs recal-locs cal-stru -- worst ) ( F: -- rms ): least squares over
 * n point pairs held as n consecutive locations (an ARRAY of LOCATION cells: 0 PTS); prints
 * each pair's residual, the RMS and the worst point (indices from 0, as the ARRAY's). */
static fbrl_status w_calibrate_n(fbrl_vm *vm, void *arg, const void *word)
{
    fbrl_glossary *g = arg;
    const char *name = "CALIBRATE-N";
    fbrl_cell a[4];
    fbrl_calib *c;
    double res[FBRL_GLOSSARY_NPOINT_MAX], rms, v;
    size_t worst;
    char line[160], num[40], num2[40]; /* numbers through fbrl_num: locale-free */
    fbrl_status st;
    if ((st = gl_args(vm, word, a, NULL)))
        return st;
    if (a[0] < 3 || a[0] > FBRL_GLOSSARY_NPOINT_MAX)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "%s: n must be 3..%d", name,
                        FBRL_GLOSSARY_NPOINT_MAX);
    size_t n = (size_t)a[0];
    fbrl_cell bytes = (fbrl_cell)(n * sizeof(fbrl_loc));
    for (int k = 1; k <= 2; k++) {
        if (!fbrl_vm_addr(vm, a[k], (size_t)(bytes)))
            return gl_throw(vm, GL_BAD_ADDRESS, "%s: %d locations at that address leave data space", name,
                            (int)n);
        if ((fbrl_ucell)a[k] % sizeof(double))
            return gl_throw(vm, GL_ALIGNMENT, "%s: location address not aligned to 8 bytes", name);
        for (size_t i = 0; i < n; i++)
            if (fbrl_loc_check((const fbrl_loc *)a[k] + i) != FBRL_OK)
                return gl_throw(vm, GL_TYPE_MISMATCH, "%s: %s point %d is not a location", name,
                                k == 1 ? "calibration" : "recalibration", (int)i);
    }
    if ((st = gl_stru(vm, a[3], 0, name, &c)))
        return st;
    const fbrl_loc *cal = (const fbrl_loc *)a[1], *recal = (const fbrl_loc *)a[2];
    st = fbrl_calib_npoint(c, cal, recal, n, res, &rms, &worst);
    if (st == FBRL_EDEGENERATE) {
        fbrl_calib scratch;
        return degenerate(vm, name,
                          fbrl_calib_npoint(&scratch, cal, cal, n, NULL, NULL, NULL) == FBRL_EDEGENERATE
                              ? "calibration"
                              : "recalibration");
    }
    if (st != FBRL_OK)
        return gl_throw_st(vm, st, name);
    const char *unit = g->units.metric ? "cm" : "in";
    for (size_t i = 0; i < n; i++) {
        if ((st = gl_out(vm, g, res[i], &v)))
            return st;
        fbrl_num_fixed(num, sizeof num, v, 10, 4, 0, NULL);
        snprintf(line, sizeof line, "point %3d residual %s %s\n", (int)i, num, unit);
        fbrl_vmx_puts(vm, line);
    }
    double wv;
    if ((st = gl_out(vm, g, rms, &v)) || (st = gl_out(vm, g, res[worst], &wv)))
        return st;
    fbrl_num_fixed(num, sizeof num, v, 0, 4, 0, NULL);
    fbrl_num_fixed(num2, sizeof num2, wv, 0, 4, 0, NULL);
    snprintf(line, sizeof line, "RMS %s %s, worst point %d (%s %s)\n", num, unit, (int)worst, num2, unit);
    fbrl_vmx_puts(vm, line);
    if ((st = fbrl_vm_push(vm, (fbrl_cell)worst)))
        return st;
    return fbrl_vm_fpush(vm, v);
}

static const gl_word cal_words[] = {
    {"MAP-ON", w_map_on, "", 0, 0, 0,
     FBRL_DOC("( -- )", "map outgoing locations through the WITH-CAL structure (and unmap taught ones)")},
    {"MAP-OFF", w_map_off, "", 0, 0, 0, FBRL_DOC("( -- )", "stop mapping locations (the default)")},
    {"MAPPING?", w_mapping_q, "", 0, 0, 0, FBRL_DOC("( -- flag )", "true if MAP-ON")},
    {"WITH-CAL", w_with_cal, "A", 0, 0, 0,
     FBRL_DOC("( cal-stru -- )", "select the calibration structure mapping uses")},
    {"CREATE-CAL", w_create_cal, "", 0, 0, 0,
     FBRL_DOC("( \"name\" -- ) ( run: -- cal )",
              "make a calibration: three location slots 1 2 3 (P1 origin, P2 on x, P3 in the plane)")},
    {"CAL-ADDR", w_cal_addr, "AI", 0, 0, 0,
     FBRL_DOC("( cal index -- loc )", "address of location slot index (1..3)")},
    {"SET-CAL", w_set_cal, "AIA", 0, 0, 0,
     FBRL_DOC("( cal index loc -- )", "copy loc into slot index (1..3)")},
    {"GET-CAL", w_get_cal, "AIA", 0, 0, 0,
     FBRL_DOC("( cal index loc -- )", "copy slot index (1..3) into loc")},
    {"CREATE-CAL-STRU", w_create_cal_stru, "", 0, 0, 0,
     FBRL_DOC("( \"name\" -- ) ( run: -- cal-stru )",
              "make a calibration structure (the block's rigid motion; identity until CALIBRATE)")},
    {"CAL-STRU@", w_cal_stru_fetch, "AI", 0, 0, 0,
     FBRL_DOC("( cal-stru index -- ) ( F: -- v )",
              "entry 1..12 of the 3x4 motion [r | t], row by row (4 8 12 = shift, inches)")},
    {"CAL-STRU!", w_cal_stru_store, "RAI", 0, 0, 0,
     FBRL_DOC(
         "( cal-stru index -- ) ( F: v -- )",
         "store entry 1..12 of the 3x4 motion [r | t], row by row (mapping refuses a non-rigid result)")},
    {"NUM-CAL-CELLS", w_num_cal_cells, "", 0, 0, 0, FBRL_DOC("( -- 12 )", "number of CAL-STRU@ entries")},
    {"ANG-FROM-ORIGIN", w_ang_from_origin, "RRRR", 0, 0, 0,
     FBRL_DOC("( F: x1 y1 x2 y2 -- angle )",
              "angle in radians of the line (x1,y1)->(x2,y2) from the positive x axis (all quadrants)")},
    {"ROTATE", w_rotate, "RRR", 0, 0, 0,
     FBRL_DOC("( F: x y angle -- x' y' )", "turn the point about the origin by angle radians")},
    {"CALIBRATE", w_calibrate, "AAA", 0, 0, 0,
     FBRL_DOC("( recal-cal cal-cal cal-stru -- )",
              "compute the motion from the block taught in cal-cal to the block taught in recal-cal")},
    {"(MAP)", w_map, "AA", 0, 0, 0,
     FBRL_DOC("( cal-stru loc -- )", "map loc from the original block to the moved block")},
    {"UNMAP", w_unmap, "AA", 0, 0, 0,
     FBRL_DOC("( cal-stru loc -- )", "map loc from the moved block back to the original block")},
    {"CALIBRATE-N", w_calibrate_n, "IAAA", 0, 0, 0,
     FBRL_DOC(
         "( n cal-locs recal-locs cal-stru -- worst ) ( F: -- rms )",
         "least-squares calibration over n >= 3 point pairs; prints each residual, the RMS and the worst")},
};

fbrl_status gl_install_cal(fbrl_vm *vm, fbrl_glossary *g)
{
    return fbrl_vmx_define_table(vm, cal_words, sizeof cal_words / sizeof cal_words[0], g);
}
