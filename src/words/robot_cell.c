/* SPDX-License-Identifier: MIT */
/* robot_cell.c - the work cell's FBRL words (docs/workcell.md) and the guard they put on
 * every robot motion: before a motion sends its first byte, the path the arm will take (from
 * where it stands, read with W2 in the same step) is checked against the cell; a motion that
 * would hit is refused, naming the obstacle and the point, and one the guard cannot compute
 * is refused too. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/cell_words.h"
#include "fbrl/num.h"
#include "fbrl/vmx.h"
#include "cell_internal.h"

/* A CELL word's row (vmx.h's one row type; arg: the obstacle kind, the guard's switch). */
typedef fbrl_vmx_reg cw_word;

/* Every CELL word begins so: its state (ctx) and its row (word). */
#define CW_WORD(vm, ctx, word)        \
    fbrl_cell_words *cw = (ctx);      \
    const cw_word *w = (word);        \
    (void)(vm)

/* "12.3456" locale-free (the picture's numbers too). */
const char *cw_num(char *buf, size_t cap, double v)
{
    if (fbrl_num_fixed(buf, cap, v, 0, 4, 0, NULL) != FBRL_OK)
        snprintf(buf, cap, "?");
    return buf;
}
#define num cw_num

/* The word's real parameters (its row's spec, fbrl_vmx_check), each finite. */
static fbrl_status pop_reals(fbrl_cell_words *cw, const cw_word *w, double *out)
{
    fbrl_vmx_val v[FBRL_VMX_MAXARGS];
    size_t n = strlen(w->spec);
    fbrl_status st = fbrl_vmx_check(cw->vm, w, v);
    if (st != FBRL_OK)
        return st;
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(v[k].f))
            return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_ENONFINITE),
                                   "%s: a size or position is NaN or infinite", w->name);
        out[k] = v[k].f;
    }
    return FBRL_OK;
}

static fbrl_status parse_name(fbrl_cell_words *cw, const cw_word *w, char *name)
{
    const char *t;
    size_t len;
    int found;
    fbrl_status st = fbrl_vmx_parse(cw->vm, ' ', &t, &len, &found);
    if (st != FBRL_OK)
        return st;
    if (len == 0)
        return fbrl_vmx_throwf(cw->vm, FBRL_THROW_NO_NAME, "%s: a name must follow", w->name);
    if (len > FBRL_CELL_NAME_MAX)
        return fbrl_vmx_throwf(cw->vm, FBRL_THROW_NAME_TOO_LONG, "%s: name longer than %d characters",
                               w->name, FBRL_CELL_NAME_MAX);
    for (size_t k = 0; k < len; k++)
        name[k] = (char)(t[k] >= 'a' && t[k] <= 'z' ? t[k] - 'a' + 'A' : t[k]);
    name[len] = '\0';
    return FBRL_OK;
}

/* ---- named locations inside an obstacle ---- */

typedef struct loc_scan {
    fbrl_cell_words *cw;
    const fbrl_cell_obj *o;
    char bad[FBRL_CELL_NAME_MAX + 1];
} loc_scan;

static int scan_one(void *ctx, const char *name, size_t len)
{
    loc_scan *s = ctx;
    fbrl_cell xt;
    fbrl_glossary_kind kind;
    void *obj;
    fbrl_cell_model one;
    fbrl_cell_obj slot;
    double d;
    if (fbrl_vmx_find(s->cw->vm, name, len, &xt) != FBRL_OK ||
        fbrl_glossary_object(s->cw->g, xt, &kind, &obj) != FBRL_OK || kind != FBRL_GLOSSARY_LOC)
        return 0;
    const fbrl_loc *l = obj;
    double p[3] = {l->x, l->y, l->z};
    fbrl_cell_obj copy = *s->o;
    copy.block = -1; /* as taught: a block's locations and obstacles share its original frame */
    if (fbrl_cell_init(&one, &slot, 1) != FBRL_OK || fbrl_cell_add(&one, &copy) != FBRL_OK ||
        fbrl_cell_point_clearance(&one, p, -2, &d, NULL) != FBRL_OK)
        return 0;
    if (d < 0) {
        size_t n = len < FBRL_CELL_NAME_MAX ? len : FBRL_CELL_NAME_MAX;
        memcpy(s->bad, name, n);
        s->bad[n] = '\0';
        return 1;
    }
    return 0;
}

static fbrl_status add_obstacle(fbrl_cell_words *cw, const cw_word *w, fbrl_cell_obj *o)
{
    size_t dup;
    char a[24], b[24], c[24];
    o->block = cw->block;
    if (fbrl_cell_find(&cw->model, o->name, strlen(o->name), &dup) == FBRL_OK)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_ENAME),
                               "%s: %s is already an obstacle of the cell", w->name, o->name);
    if (cw->g) {
        loc_scan s;
        memset(&s, 0, sizeof s);
        s.cw = cw;
        s.o = o;
        fbrl_vm_words(cw->vm, scan_one, &s);
        if (s.bad[0]) {
            const fbrl_loc *l = NULL;
            fbrl_cell xt;
            fbrl_glossary_kind kind;
            void *obj = NULL;
            if (fbrl_vmx_find(cw->vm, s.bad, strlen(s.bad), &xt) == FBRL_OK &&
                fbrl_glossary_object(cw->g, xt, &kind, &obj) == FBRL_OK)
                l = obj;
            return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE),
                                   "%s: location %s (X %s Y %s Z %s) lies inside %s", w->name, s.bad,
                                   num(a, sizeof a, l ? l->x : NAN), num(b, sizeof b, l ? l->y : NAN),
                                   num(c, sizeof c, l ? l->z : NAN), o->name);
        }
    }
    fbrl_status st = fbrl_cell_add(&cw->model, o);
    if (st == FBRL_ERANGE)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(st),
                               "%s: %s: every size must be positive (a corner beyond the other, a "
                               "radius or height above zero)",
                               w->name, o->name);
    if (st == FBRL_EFULL)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(st), "%s: the cell is full (%d obstacles)",
                               w->name, FBRL_CELL_MAX_OBJ);
    if (st != FBRL_OK)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(st), "%s: %s: %s", w->name, o->name,
                               fbrl_status_str(st));
    return FBRL_OK;
}

/* CELL-BOX / CELL-KEEPOUT ( F: x0 y0 z0 x1 y1 z1 -- ) name */
static fbrl_status w_box(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    double v[6];
    fbrl_cell_obj o;
    memset(&o, 0, sizeof o);
    fbrl_status st = pop_reals(cw, w, v);
    if (st == FBRL_OK)
        st = parse_name(cw, w, o.name);
    if (st != FBRL_OK)
        return st;
    o.kind = (fbrl_cell_kind)w->arg;
    for (int k = 0; k < 3; k++)
        o.lo[k] = v[k], o.hi[k] = v[k + 3];
    return add_obstacle(cw, w, &o);
}

/* CELL-CYLINDER ( F: x y z radius height -- ) name: upright, its base centred at x y z */
static fbrl_status w_cylinder(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    double v[5];
    fbrl_cell_obj o;
    memset(&o, 0, sizeof o);
    fbrl_status st = pop_reals(cw, w, v);
    if (st == FBRL_OK)
        st = parse_name(cw, w, o.name);
    if (st != FBRL_OK)
        return st;
    o.kind = FBRL_CELL_CYLINDER;
    o.c[0] = v[0], o.c[1] = v[1], o.lo[2] = v[2], o.r = v[3], o.hi[2] = v[2] + v[4];
    if (!(v[4] > 0)) /* a negative height would still give hi > lo after the sum: refuse it here */
        o.hi[2] = o.lo[2];
    return add_obstacle(cw, w, &o);
}

/* CELL-TABLE ( F: z -- ) */
static fbrl_status w_table(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    double z;
    fbrl_status st = pop_reals(cw, w, &z);
    return st == FBRL_OK ? fbrl_cell_set_table(&cw->model, z) : st;
}

/* CELL-TOOL ( F: length radius -- ) */
static fbrl_status w_tool(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    double v[2];
    fbrl_status st = pop_reals(cw, w, v);
    if (st != FBRL_OK)
        return st;
    if (fbrl_cell_set_tool(&cw->model, v[0], v[1]) != FBRL_OK)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE),
                               "%s: the tool's length and radius must not be negative", w->name);
    return FBRL_OK;
}

/* CELL-BLOCK name: later obstacles ride on the CREATE-CAL-STRU name (its calibration). */
static fbrl_status w_block(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    char name[FBRL_CELL_NAME_MAX + 1];
    int index;
    fbrl_status st = parse_name(cw, w, name);
    if (st != FBRL_OK)
        return st;
    st = fbrl_cell_block(&cw->model, name, strlen(name), &index);
    if (st != FBRL_OK)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(st), "%s: %s: at most %d blocks", w->name,
                               name, FBRL_CELL_BLOCKS);
    memcpy(cw->block_cal[index], name, sizeof name);
    cw->block = index;
    return FBRL_OK;
}

static fbrl_status w_world(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    (void)w;
    cw->block = -1;
    return FBRL_OK;
}

static fbrl_status w_guard(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    cw->guard = w->arg;
    return FBRL_OK;
}

static fbrl_status w_clear(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    (void)w;
    fbrl_cell_clear(&cw->model);
    cw->block = -1;
    memset(&cw->stats, 0, sizeof cw->stats);
    cw->stats.clearance = INFINITY;
    cw->stats.near_obj = FBRL_CELL_NONE;
    cw->npath = 0;
#if FBRL_CELL_PICTURE
    cw->nrefused = 0; /* the racks stay: they describe the places, not the cell */
#endif
    return FBRL_OK;
}

/* CELL-RACK ( rows cols -- ) ( PAR: matrix ): the picture draws every position of that
 * RECTMAT (i < rows, j < cols) or RADMAT (rings, radials), not only its base. */
static fbrl_status w_rack(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    fbrl_vmx_val v[2];
    char name[FBRL_CELL_NAME_MAX + 1];
    fbrl_cell xt;
    fbrl_glossary_kind kind;
    void *obj;
    size_t k;
    fbrl_status st = fbrl_vmx_check(cw->vm, w, v);
    if (st == FBRL_OK)
        st = parse_name(cw, w, name);
    if (st != FBRL_OK)
        return st;
    if (v[0].i < 1 || v[0].i > FBRL_CELL_RACK_MAX || v[1].i < 1 || v[1].i > FBRL_CELL_RACK_MAX)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE),
                               "%s: %s: rows and columns must be 1 to %d", w->name, name, FBRL_CELL_RACK_MAX);
    if (!cw->g || fbrl_vmx_find(cw->vm, name, strlen(name), &xt) != FBRL_OK ||
        fbrl_glossary_object(cw->g, xt, &kind, &obj) != FBRL_OK ||
        (kind != FBRL_GLOSSARY_RECTMAT && kind != FBRL_GLOSSARY_RADMAT))
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_ENAME), "%s: %s is no RECTMAT or RADMAT",
                               w->name, name);
#if FBRL_CELL_PICTURE
    for (k = 0; k < cw->nracks && strcmp(cw->racks[k].name, name) != 0; k++)
        ;
    if (k == FBRL_CELL_RACKS)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "%s: at most %d racks", w->name,
                               FBRL_CELL_RACKS);
    memcpy(cw->racks[k].name, name, sizeof name);
    cw->racks[k].rows = (int)v[0].i;
    cw->racks[k].cols = (int)v[1].i;
    if (k == cw->nracks)
        cw->nracks++;
#else
    (void)k;
#endif
    return FBRL_OK;
}

static void say(fbrl_cell_words *cw, const char *s) { fbrl_vmx_puts(cw->vm, s); }

/* .CELL: the cell, and what the guard saw */
static fbrl_status w_show(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    char line[256], a[24], b[24], c[24], d[24], e[24], f[24];
    (void)w;
    snprintf(line, sizeof line, "cell: guard %s, table %s, tool length %s radius %s in, %zu obstacles\n",
             cw->guard ? "on" : "OFF", cw->model.have_table ? num(a, sizeof a, cw->model.table_z) : "none",
             num(b, sizeof b, cw->model.tool_len), num(c, sizeof c, cw->model.tool_r), cw->model.n);
    say(cw, line);
    for (size_t k = 0; k < cw->model.n; k++) {
        const fbrl_cell_obj *o = &cw->model.obj[k];
        if (o->kind == FBRL_CELL_CYLINDER)
            snprintf(line, sizeof line, "  %-16s cylinder x %s y %s z %s..%s radius %s%s%s\n", o->name,
                     num(a, sizeof a, o->c[0]), num(b, sizeof b, o->c[1]), num(c, sizeof c, o->lo[2]),
                     num(d, sizeof d, o->hi[2]), num(e, sizeof e, o->r), o->block >= 0 ? " on " : "",
                     o->block >= 0 ? cw->block_cal[o->block] : "");
        else
            snprintf(line, sizeof line, "  %-16s %s %s %s %s .. %s %s %s%s%s\n", o->name,
                     o->kind == FBRL_CELL_KEEPOUT ? "keep-out" : "box", num(a, sizeof a, o->lo[0]),
                     num(b, sizeof b, o->lo[1]), num(c, sizeof c, o->lo[2]), num(d, sizeof d, o->hi[0]),
                     num(e, sizeof e, o->hi[1]), num(f, sizeof f, o->hi[2]), o->block >= 0 ? " on " : "",
                     o->block >= 0 ? cw->block_cal[o->block] : "");
        say(cw, line);
    }
    if (isfinite(cw->stats.clearance)) {
        snprintf(line, sizeof line, "closest: %s in to %s (%s)\n", num(a, sizeof a, cw->stats.clearance),
                 fbrl_cell_obj_name(&cw->model, cw->stats.near_obj), cw->stats.near_word);
        say(cw, line);
    }
    return FBRL_OK;
}

/* CELL-SVG ( c-addr u -- ) or ( PAR: file ): the picture, through the host's file */
static fbrl_status w_svg(fbrl_vm *vm, void *ctx, const void *word)
{
    CW_WORD(vm, ctx, word);
    fbrl_vmx_val v[1];
    char path[256];
    fbrl_status st = fbrl_vmx_check(cw->vm, w, v);
    if (st != FBRL_OK)
        return st;
    if (!cw->save)
        return fbrl_vmx_throwf(cw->vm, FBRL_THROW_UNSUPPORTED, "%s: no file output in this host", w->name);
    if (v[0].n == 0 || v[0].n >= sizeof path)
        return fbrl_vmx_throwf(cw->vm, FBRL_THROW_BAD_NUMBER, "%s: a file name must follow", w->name);
    memcpy(path, v[0].s, v[0].n);
    path[v[0].n] = '\0';
    st = cw->save(cw->save_ctx, path, cw);
    if (st != FBRL_OK)
        return fbrl_vmx_throwf(cw->vm, FBRL_VM_THROW_OF_STATUS(st), "%s: %s: %s", w->name, path,
                               fbrl_status_str(st));
    return FBRL_OK;
}

static const cw_word words[] = {
    {"CELL-TABLE", w_table, "R", 0, 0, 0, FBRL_DOC("( F: z -- )", "the work cell's table top is at height z (in)")},
    {"CELL-TOOL", w_tool, "RR", 0, 0, 0,
     FBRL_DOC("( F: length radius -- )",
              "the tool envelope: reaches length (in) past the tool point, this thick")},
    {"CELL-BOX", w_box, "RRRRRR", 0, 0, FBRL_CELL_BOX,
     FBRL_DOC("( F: x0 y0 z0 x1 y1 z1 -- ) ( PAR: name )", "a solid box obstacle between two corners (in)")},
    {"CELL-KEEPOUT", w_box, "RRRRRR", 0, 0, FBRL_CELL_KEEPOUT,
     FBRL_DOC("( F: x0 y0 z0 x1 y1 z1 -- ) ( PAR: name )",
              "a keep-out zone: a box of space the tool must not enter")},
    {"CELL-CYLINDER", w_cylinder, "RRRRR", 0, 0, 0,
     FBRL_DOC("( F: x y z radius height -- ) ( PAR: name )",
              "an upright cylinder obstacle standing at x y z")},
    {"CELL-BLOCK", w_block, "", 0, 0, 0,
     FBRL_DOC("( PAR: cal-stru )", "later obstacles move with that CREATE-CAL-STRU's calibration")},
    {"CELL-WORLD", w_world, "", 0, 0, 0, FBRL_DOC("( -- )", "later obstacles stand fixed in the cell")},
    {"CELL-GUARD-ON", w_guard, "", 0, 0, 1, FBRL_DOC("( -- )", "check every motion against the cell (the default)")},
    {"CELL-GUARD-OFF", w_guard, "", 0, 0, 0,
     FBRL_DOC("( -- )", "send motions unchecked (the guard is off until CELL-GUARD-ON)")},
    {"CELL-CLEAR", w_clear, "", 0, 0, 0, FBRL_DOC("( -- )", "forget the cell's table, obstacles and blocks")},
    {"CELL-RACK", w_rack, "II", 0, 0, 0,
     FBRL_DOC(
         "( rows cols -- ) ( PAR: matrix )",
         "the picture draws every position of that RECTMAT or RADMAT (rows or rings x columns or radials)")},
    {".CELL", w_show, "", 0, 0, 0, FBRL_DOC("( -- )", "list the cell and the closest approach so far")},
    {"CELL-SVG", w_svg, "S", FBRL_VMX_PARSE, 0, 0,
     FBRL_DOC("( c-addr u -- ) or ( PAR: file )", "write an SVG picture of the cell and the tool's path")},
};

/* ---- the guard ---- */

/* Carry every block's obstacles to where its calibration puts the block now. */
void cw_place_blocks(fbrl_cell_words *cw)
{
    for (size_t k = 0; cw->g && k < cw->model.nblocks; k++) {
        fbrl_cell xt;
        fbrl_glossary_kind kind;
        void *obj;
        const char *n = cw->block_cal[k];
        if (fbrl_vmx_find(cw->vm, n, strlen(n), &xt) == FBRL_OK &&
            fbrl_glossary_object(cw->g, xt, &kind, &obj) == FBRL_OK && kind == FBRL_GLOSSARY_CALSTRU)
            (void)fbrl_cell_set_block(&cw->model, (int)k, obj);
    }
}

static int active(const fbrl_cell_words *cw)
{
    return cw->guard && (cw->model.have_table || cw->model.n > 0);
}

static fbrl_robot_guard_state guard_state(void *ctx)
{
    const fbrl_cell_words *cw = ctx;
    if (!cw->model.have_table && cw->model.n == 0)
        return FBRL_ROBOT_GUARD_EMPTY;
    return cw->guard ? FBRL_ROBOT_GUARD_ON : FBRL_ROBOT_GUARD_OFF;
}

/* A refused motion for the picture: the tool point from p0 (joints q0) towards target (q1
 * for a joint move, NULL along a line) up to fraction f of the way, and the contact h. */
static void keep_refusal(fbrl_cell_words *cw, const fbrl_robot_move *m, const double *q0, const double *q1,
                         const double p0[3], const double target[3], double f, const fbrl_cell_hit *h)
{
#if FBRL_CELL_PICTURE
    fbrl_cell_refusal *rf;
    if (cw->nrefused >= FBRL_CELL_LOG_MAX)
        return;
    rf = &cw->refused[cw->nrefused++];
    memset(rf, 0, sizeof *rf);
    for (unsigned k = 0; k < FBRL_CELL_REFUSED_PTS; k++) {
        double t = f * k / (FBRL_CELL_REFUSED_PTS - 1), pose[6], q[FBRL_CELL_AXES];
        for (int i = 0; q1 && i < FBRL_CELL_AXES; i++)
            q[i] = q0[i] + (q1[i] - q0[i]) * t;
        if (q1)
            fbrl_arm_fk(cw->model.arm, q, cw->model.tcp, pose);
        for (int i = 0; !q1 && i < 3; i++)
            pose[i] = p0[i] + (target[i] - p0[i]) * t;
        memcpy(rf->pts[k], pose, sizeof rf->pts[k]);
    }
    rf->npts = FBRL_CELL_REFUSED_PTS;
    rf->hit = h != NULL;
    rf->obj = h ? h->obj : FBRL_CELL_NONE;
    if (h)
        memcpy(rf->at, h->at, sizeof rf->at);
    snprintf(rf->word, sizeof rf->word, "%s", m->word);
#else
    (void)cw, (void)m, (void)q0, (void)q1, (void)p0, (void)target, (void)f, (void)h;
#endif
}

/* A refusal; ck (NULL: the start was not read) is what the check knew, for the observer. */
static fbrl_status refuse(fbrl_cell_words *cw, const fbrl_robot_move *m, const char *what, fbrl_cell_check *ck)
{
    char msg[FBRL_CELL_MSG_MAX];
    snprintf(msg, sizeof msg, "%s: %s; nothing was sent", m->word, what);
    if (cw->observe) {
        fbrl_cell_check none;
        if (!ck) {
            memset(&none, 0, sizeof none);
            ck = &none;
        }
        ck->word = m->word;
        ck->message = msg;
        cw->observe(cw->observe_ctx, ck);
    }
    if (cw->stats.nrefusals < FBRL_CELL_LOG_MAX) { /* the report keeps its head */
        char *keep = cw->stats.refusals[cw->stats.nrefusals++];
        size_t n =
            strlen(msg) < sizeof cw->stats.refusals[0] ? strlen(msg) : sizeof cw->stats.refusals[0] - 1;
        memcpy(keep, msg, n);
        keep[n] = '\0';
    }
    cw->stats.refused++;
    return fbrl_robot_fail(cw->r, FBRL_ROBOT_THROW_REFUSED, msg);
}

static void note_path(fbrl_cell_words *cw, const double q[FBRL_CELL_AXES])
{
    double pose[6];
    if (cw->npath >= FBRL_CELL_PATH_MAX)
        return;
    fbrl_arm_fk(cw->model.arm, q, cw->model.tcp, pose);
    memcpy(cw->path[cw->npath++], pose, 3 * sizeof(double));
}

/* Where the arm stands (it stands: robot_gate.c waited for it), read from the controller
 * for every check: a stop the guard did not command (HALT, power off, an E-stop, the
 * pendant, a lost connection) or a motion sent around it never leaves the guard checking
 * from the wrong place. One W1 line (motor pulses) once a W2 has shown that pulses are
 * joints times the arm's pulses per degree on this controller (again after anything that
 * changes the where-epoch: a link set, HALT, ...); else, or when that line was not clean,
 * the whole W2. The last motion's end counts as the start only when the pulses show the
 * arm there (within a pulse on every axis): seen to end there. *n: the axes read. */
/* Two pulse counts within one pulse of each other. */
static int near_pulse(long a, long b) { return a - b <= 1 && b - a <= 1; }

static fbrl_status where(fbrl_cell_words *cw, fbrl_robot *r, const char *word, double *q, unsigned *n)
{
    const fbrl_arm *arm = cw->model.arm;
    fbrl_rapl_pos p;
    fbrl_status st;
    int expect = cw->expect;
    cw->expect = 0;
    if (cw->pulses_ok && cw->epoch == fbrl_robot_where_epoch(r)) {
        long pulses[FBRL_RAPL_MAX_AXES];
        st = fbrl_robot_pulses(r, word, pulses, n);
        if (st == FBRL_OK && *n == arm->naxes) {
            for (unsigned k = 0; k < *n; k++) {
                q[k] = fbrl_arm_degrees(arm, k, pulses[k]);
                expect = expect && near_pulse(pulses[k], fbrl_arm_pulses(arm, k, cw->pending[k]));
            }
            if (expect)
                memcpy(q, cw->pending, arm->naxes * sizeof q[0]);
            return FBRL_OK;
        }
        if (st != FBRL_OK && st != FBRL_EPROTOCOL)
            return st;
    }
    if ((st = fbrl_robot_position(r, word, &p)) != FBRL_OK)
        return st;
    *n = p.njoints;
    for (unsigned k = 0; k < p.njoints; k++)
        q[k] = p.joints[k];
    cw->pulses_ok = p.njoints == arm->naxes && p.npulses == arm->naxes;
    for (unsigned k = 0; cw->pulses_ok && k < arm->naxes; k++) /* 4 decimals: within a pulse */
        cw->pulses_ok = near_pulse(p.pulses[k], fbrl_arm_pulses(arm, k, p.joints[k]));
    cw->epoch = fbrl_robot_where_epoch(r);
    return FBRL_OK;
}

/* The check, one step with the motion's send (robot_gate.c): nothing else runs between. */
static fbrl_status guard_check(void *ctx, fbrl_robot *r, const fbrl_robot_move *m)
{
    fbrl_cell_words *cw = ctx;
    const fbrl_arm *arm = cw->model.arm;
    double q0[FBRL_CELL_AXES], q1[FBRL_CELL_AXES], p0[6], target[6];
    fbrl_cell_hit *h = &cw->last;
    fbrl_status st;
    int line = m->straight;
    char what[FBRL_CELL_MSG_MAX - 32], a[24], b[24], c[24];
    cw->checked = 0;
    if (!active(cw) || m->kind == FBRL_ROBOT_MOVE_HOME)
        return FBRL_OK;
    if (m->kind == FBRL_ROBOT_MOVE_OTHER)
        return refuse(cw, m, "the guard cannot follow this motion (CELL-GUARD-OFF sends it unchecked)", NULL);
    double q[FBRL_RAPL_MAX_AXES] = {0};
    unsigned n = 0;
    if ((st = where(cw, r, m->word, q, &n)) != FBRL_OK)
        return st;
    if (n != arm->naxes) { /* the controller is not the arm the guard computes */
        snprintf(what, sizeof what,
                 "%s: the guard computes the %s (%u axes); this controller reports %u (fbrlmon --arm names "
                 "the arm; CELL-GUARD-OFF sends the motion unchecked)",
                 m->word, arm->name, arm->naxes, n);
        return fbrl_robot_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_EUNSUPPORTED), what);
    }
    memcpy(cw->q, q, sizeof cw->q);
    cw_place_blocks(cw);
    fbrl_cell_check ck;
    memset(&ck, 0, sizeof ck);
    ck.naxes = arm->naxes;
    memcpy(ck.q0, cw->q, sizeof ck.q0);
    memcpy(ck.q1, cw->q, sizeof ck.q1);
    memcpy(q0, cw->q, sizeof q0);
    memcpy(q1, q0, sizeof q1);
    fbrl_arm_fk(arm, q0, cw->model.tcp, p0);
    memcpy(target, p0, sizeof target);
    switch (m->kind) {
    case FBRL_ROBOT_MOVE_POSE:
        memcpy(target, m->v, sizeof target);
        if (m->dist != 0.0)
            fbrl_arm_back_off(arm, m->v, q0[0], m->dist, target);
        break;
    case FBRL_ROBOT_MOVE_DEPART: fbrl_arm_back_off(arm, p0, q0[0], m->dist, target); break;
    case FBRL_ROBOT_MOVE_JOG:
        for (int k = 0; k < 3; k++)
            target[k] += m->v[k];
        line = 1;
        break;
    case FBRL_ROBOT_MOVE_JOINTS: memcpy(q1, m->v, sizeof q1); break;
    case FBRL_ROBOT_MOVE_DJOINTS:
        for (unsigned k = 0; k < arm->naxes; k++)
            q1[k] += m->v[k];
        break;
    case FBRL_ROBOT_MOVE_MOTOR:
        if (m->v[0] >= 1 && m->v[0] <= arm->naxes)
            q1[(int)m->v[0] - 1] += fbrl_arm_degrees(arm, (unsigned)m->v[0] - 1, 1) * m->v[1];
        break;
    case FBRL_ROBOT_MOVE_READY: memcpy(q1, arm->ready, sizeof q1); break;
    default: break;
    }
    int to_pose = m->kind == FBRL_ROBOT_MOVE_POSE || m->kind == FBRL_ROBOT_MOVE_DEPART ||
                  m->kind == FBRL_ROBOT_MOVE_JOG;
    ck.line = line;
    /* a target or a line the guard cannot compute cannot be checked: refused while a cell is
     * described (a controller in millimetres reads such a target as another, reachable one) */
    if (to_pose && !line && fbrl_arm_ik(arm, target, cw->model.tcp, q0, q1, NULL) != FBRL_OK) {
        snprintf(what, sizeof what, "the guard cannot check it: X %s Y %s Z %s in is beyond the arm's reach",
                 num(a, sizeof a, target[0]), num(b, sizeof b, target[1]), num(c, sizeof c, target[2]));
        keep_refusal(cw, m, q0, NULL, p0, target, 1.0, NULL);
        return refuse(cw, m, what, &ck);
    }
    if (!to_pose && line)
        fbrl_arm_fk(arm, q1, cw->model.tcp, target);
    st = line ? fbrl_cell_check_line(&cw->model, q0, target, h)
              : fbrl_cell_check_joints(&cw->model, q0, q1, h);
    if (st != FBRL_OK) {
        keep_refusal(cw, m, q0, line ? NULL : q1, p0, target, 1.0, NULL);
        return refuse(cw, m,
                      "the guard cannot check it: the straight line leaves the arm's reach (move in steps, "
                      "or joint-interpolated)",
                      &ck);
    }
    if (h->hit) {
        snprintf(what, sizeof what, "would hit %s with the %s at X %s Y %s Z %s in (%d%% of the way)",
                 fbrl_cell_obj_name(&cw->model, h->obj), fbrl_arm_part_name(h->part),
                 num(a, sizeof a, h->at[0]), num(b, sizeof b, h->at[1]), num(c, sizeof c, h->at[2]),
                 (int)(h->fraction * 100.0 + 0.5));
        keep_refusal(cw, m, q0, line ? NULL : q1, p0, target, h->fraction, h);
        ck.path = 1;
        ck.hit = h;
        memcpy(ck.q1, h->q_end, sizeof ck.q1);
        return refuse(cw, m, what, &ck);
    }
    memcpy(cw->pending, h->q_end, sizeof cw->pending);
    cw->line = line;
    cw->checked = 1;
    return FBRL_OK;
}

/* After the motion line, in the same step as its check: the record and the picture. Where
 * the arm ends is not taken from here (the next check reads it). */
static void guard_done(void *ctx, fbrl_robot *r, const fbrl_robot_move *m, fbrl_status result)
{
    fbrl_cell_words *cw = ctx;
    (void)r;
    if (!cw->checked || result != FBRL_OK) {
        cw->checked = 0;
        return;
    }
    cw->checked = 0;
    cw->expect = 1; /* the next check sees whether it ended there */
    cw->stats.moves++;
    if (cw->last.clearance < cw->stats.clearance) {
        cw->stats.clearance = cw->last.clearance;
        cw->stats.near_obj = cw->last.near_obj;
        memcpy(cw->stats.near, cw->last.near, sizeof cw->stats.near);
        snprintf(cw->stats.near_word, sizeof cw->stats.near_word, "%s", m->word);
    }
    if (cw->observe) {
        fbrl_cell_check ck;
        memset(&ck, 0, sizeof ck);
        ck.word = m->word;
        ck.sent = ck.path = 1;
        ck.line = cw->line;
        ck.naxes = cw->model.arm->naxes;
        memcpy(ck.q0, cw->q, sizeof ck.q0);
        memcpy(ck.q1, cw->pending, sizeof ck.q1);
        ck.hit = &cw->last;
        cw->observe(cw->observe_ctx, &ck);
    }
    /* the path for the picture: a few points along a joint move, its ends */
    for (int k = 1; k <= 8; k++) {
        double q[FBRL_CELL_AXES];
        for (int i = 0; i < FBRL_CELL_AXES; i++)
            q[i] = cw->q[i] + (cw->pending[i] - cw->q[i]) * k / 8.0;
        note_path(cw, q);
    }
}

fbrl_status fbrl_cell_install(fbrl_vm *vm, fbrl_cell_words *cw, fbrl_robot *r, fbrl_glossary *g)
{
    fbrl_robot_guard gd;
    if (!vm || !cw || !r)
        return FBRL_EINVAL;
    memset(cw, 0, sizeof *cw);
    fbrl_cell_init(&cw->model, cw->obj, FBRL_CELL_MAX_OBJ);
    cw->vm = vm;
    cw->r = r;
    cw->g = g;
    cw->guard = 1;
    cw->block = -1;
    cw->stats.clearance = INFINITY;
    cw->stats.near_obj = FBRL_CELL_NONE;
    fbrl_status st = fbrl_vmx_define_table(vm, words, sizeof words / sizeof words[0], cw);
    if (st != FBRL_OK)
        return st;
    memset(&gd, 0, sizeof gd);
    gd.check = guard_check;
    gd.done = guard_done;
    gd.ctx = cw;
    gd.state = guard_state;
    return fbrl_robot_set_guard(r, &gd);
}

void fbrl_cell_set_save(fbrl_cell_words *cw, fbrl_cell_save_fn fn, void *ctx)
{
    if (!cw)
        return;
    cw->save = fn;
    cw->save_ctx = ctx;
}

void fbrl_cell_set_observer(fbrl_cell_words *cw, fbrl_cell_observe_fn fn, void *ctx)
{
    if (!cw)
        return;
    cw->observe = fn;
    cw->observe_ctx = ctx;
}

const fbrl_cell_stats *fbrl_cell_stats_get(const fbrl_cell_words *cw) { return cw ? &cw->stats : NULL; }
