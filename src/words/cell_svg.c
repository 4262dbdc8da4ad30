/* SPDX-License-Identifier: MIT */
/* cell_svg.c - the work cell's picture (CELL-SVG, the dry run's; docs/workcell.md): a top
 * view (x across, y up) over a side view (x across, z up) at one scale, framed to fit the
 * obstacles, the places, the path and the refused motions; a legend and a scale bar below.
 * Labels are placed where they cover no other label and stay inside their view; one that
 * finds no such place is left to its element's tooltip (<title>), and the legend counts
 * those. Written through the caller's sink: no allocation, no file. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/cell_words.h"
#include "fbrl/matrix.h"
#include "fbrl/num.h"
#include "fbrl/vmx.h"
#include "cell_internal.h"

#define num cw_num

#if FBRL_CELL_PICTURE

#define SVG_FIT_W    760.0 /* px: the widest a view's drawing gets */
#define SVG_FIT_H    600.0 /* px: the tallest (a tall cell is drawn smaller) */
#define SVG_MIN_W    560.0 /* px: the page is never narrower (three legend columns) */
#define SVG_MARGIN   36.0  /* px around each view's drawing: room for its labels */
#define SVG_PAD      0.5   /* in: space around what is drawn */
#define SVG_MIN_SPAN 6.0   /* in: the least a view shows across and up (an empty cell is no dot) */
#define SVG_KEEPOUT  3.0   /* in: a keep-out zone is shown at most this far beyond the rest */
#define SVG_TITLE_H  22.0  /* px: a view's title line */
#define SVG_CHAR_W   7.0   /* px per character of a 10 px label: 0.7 em, wider than sans-serif capitals */
#define SVG_LINE_H   13.0  /* px: a label's box, 10 px and descenders */
#define SVG_LABELS   384   /* labels kept clear of each other; more are left to their tooltips */
#define SVG_STEPS    8     /* lines above and below the place a label may move */
#define SVG_LEG_COL  180.0 /* px: a legend column */
#define SVG_LEG_ROW  18.0  /* px: a legend row */
#define SVG_RED      "#d00000"

typedef struct bounds {
    double lo[3], hi[3];
} bounds;

/* A label's box on the page, whole px rounded outwards (small: the boxes live on the stack). */
typedef struct svg_box {
    short x0, y0, x1, y1;
} svg_box;

/* A view: x across; up = y (top view) or z (side view). ox, oy: the page's point of the
 * world origin; area: its part of the page, where its labels must stay. */
typedef struct view {
    double ox, oy;
    int side;
    struct {
        double x0, y0, x1, y1;
    } area;
} view;

typedef struct svg_ctx {
    fbrl_cell_words *cw;
    fbrl_cell_write_fn fn;
    void *ctx;
    double scale;        /* px per inch */
    struct bounds frame; /* in: what the views show */
    svg_box placed[SVG_LABELS];
    unsigned nplaced, dropped;
} svg_ctx;

static void out(svg_ctx *s, const char *t) { s->fn(s->ctx, t, strlen(t)); }

static double px(const svg_ctx *s, const view *v, double x) { return v->ox + x * s->scale; }
static double py(const svg_ctx *s, const view *v, const double p[3])
{
    return v->oy - (v->side ? p[2] : p[1]) * s->scale;
}

/* A name as SVG text: names are plain words, these four would break the markup. */
static void safe(char *dst, const char *src, size_t len)
{
    size_t n = len < FBRL_CELL_NAME_MAX ? len : FBRL_CELL_NAME_MAX;
    for (size_t k = 0; k < n; k++)
        dst[k] = src[k] == '<' || src[k] == '>' || src[k] == '&' || src[k] == '"' ? '_' : src[k];
    dst[n] = '\0';
}

static void rect_px(svg_ctx *s, const char *cls, double x0, double y0, double x1, double y1,
                    const char *title)
{
    char line[400], a[24], b[24], c[24], d[24];
    snprintf(
        line, sizeof line, "<rect class=\"%s\" x=\"%s\" y=\"%s\" width=\"%s\" height=\"%s\">%s%s%s</rect>\n",
        cls, num(a, sizeof a, fmin(x0, x1)), num(b, sizeof b, fmin(y0, y1)), num(c, sizeof c, fabs(x1 - x0)),
        num(d, sizeof d, fabs(y1 - y0)), title ? "<title>" : "", title ? title : "", title ? "</title>" : "");
    out(s, line);
}

static void circle_px(svg_ctx *s, const char *cls, double x, double y, double r, const char *title)
{
    char line[300], a[24], b[24], c[24];
    snprintf(line, sizeof line, "<circle class=\"%s\" cx=\"%s\" cy=\"%s\" r=\"%s\">%s%s%s</circle>\n", cls,
             num(a, sizeof a, x), num(b, sizeof b, y), num(c, sizeof c, r), title ? "<title>" : "",
             title ? title : "", title ? "</title>" : "");
    out(s, line);
}

static void line_px(svg_ctx *s, const char *cls, double x1, double y1, double x2, double y2,
                    const char *extra)
{
    char line[300], a[24], b[24], c[24], d[24];
    snprintf(line, sizeof line, "<line class=\"%s\" x1=\"%s\" y1=\"%s\" x2=\"%s\" y2=\"%s\"%s/>\n", cls,
             num(a, sizeof a, x1), num(b, sizeof b, y1), num(c, sizeof c, x2), num(d, sizeof d, y2), extra);
    out(s, line);
}

static void text_px(svg_ctx *s, const char *cls, double x, double y, const char *text, const char *extra)
{
    char line[300], a[24], b[24];
    snprintf(line, sizeof line, "<text class=\"%s\" x=\"%s\" y=\"%s\"%s>%s</text>\n", cls,
             num(a, sizeof a, x), num(b, sizeof b, y), extra, text);
    out(s, line);
}

/* The box of a label whose baseline starts at (x, y). */
static svg_box text_box(double x, double y, const char *text)
{
    svg_box b = {(short)floor(x), (short)floor(y - 10.0), (short)ceil(x + (double)strlen(text) * SVG_CHAR_W),
                 (short)ceil(y - 10.0 + SVG_LINE_H)};
    return b;
}

static int free_place(const svg_ctx *s, const view *v, const svg_box *b)
{
    if (b->x0 < v->area.x0 || b->y0 < v->area.y0 || b->x1 > v->area.x1 || b->y1 > v->area.y1)
        return 0;
    for (unsigned k = 0; k < s->nplaced; k++) {
        const svg_box *o = &s->placed[k];
        if (b->x0 < o->x1 && o->x0 < b->x1 && b->y0 < o->y1 && o->y0 < b->y1)
            return 0;
    }
    return 1;
}

/* A label for the point (ax, ay): above it to the right, below, to the left, then a line
 * further up or down at a time; where every place is taken it is not drawn. */
static void label(svg_ctx *s, const view *v, double ax, double ay, const char *cls, const char *text,
                  const char *extra)
{
    double w = (double)strlen(text) * SVG_CHAR_W;
    for (int k = 0; k <= SVG_STEPS && s->nplaced < SVG_LABELS; k++) {
        for (int c = 0; c < 4; c++) {
            double x = c & 1 ? ax - 4.0 - w : ax + 4.0;
            double y = c & 2 ? ay + 14.0 + k * SVG_LINE_H : ay - 4.0 - k * SVG_LINE_H;
            svg_box b = text_box(x, y, text);
            if (free_place(s, v, &b)) {
                s->placed[s->nplaced++] = b;
                if (k > 0) /* moved off its point: a leader to the box's nearest corner */
                    line_px(s, "leader", ax, ay, c & 1 ? b.x1 : b.x0, c & 2 ? b.y0 : b.y1, "");
                text_px(s, cls, x, y, text, extra);
                return;
            }
        }
    }
    s->dropped++;
}

/* An obstacle's corners where its block stands now: the box's eight corners carried along,
 * drawn by their extent (a turned block shows its bounding box). */
static void obj_extent(const fbrl_cell_words *cw, const fbrl_cell_obj *o, double lo[3], double hi[3])
{
    double l[3], h[3];
    if (o->kind == FBRL_CELL_CYLINDER) {
        l[0] = o->c[0] - o->r, l[1] = o->c[1] - o->r, h[0] = o->c[0] + o->r, h[1] = o->c[1] + o->r;
        l[2] = o->lo[2], h[2] = o->hi[2];
    } else {
        memcpy(l, o->lo, sizeof l);
        memcpy(h, o->hi, sizeof h);
    }
    for (int i = 0; i < 3; i++)
        lo[i] = INFINITY, hi[i] = -INFINITY;
    for (int k = 0; k < 8; k++) {
        double p[3] = {k & 1 ? h[0] : l[0], k & 2 ? h[1] : l[1], k & 4 ? h[2] : l[2]}, q[3];
        if (o->block >= 0) {
            const fbrl_calib *m = &cw->model.block[o->block];
            for (int i = 0; i < 3; i++)
                q[i] = m->r[i][0] * p[0] + m->r[i][1] * p[1] + m->r[i][2] * p[2] + m->t[i];
        } else {
            memcpy(q, p, sizeof q);
        }
        for (int i = 0; i < 3; i++)
            lo[i] = fmin(lo[i], q[i]), hi[i] = fmax(hi[i], q[i]);
    }
}

/* ---- the named places: locations, matrices and their racks ---- */

typedef struct place {
    char name[FBRL_CELL_NAME_MAX + 1];
    fbrl_glossary_kind kind;
    const void *obj;
    const fbrl_cell_rack *rack; /* its CELL-RACK, or NULL */
} place;

typedef void (*place_fn)(void *ctx, const place *pl);

typedef struct place_walk {
    fbrl_cell_words *cw;
    place_fn fn;
    void *ctx;
    unsigned n;
} place_walk;

static int same_name(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if ((*a >= 'a' && *a <= 'z' ? *a - 32 : *a) != (*b >= 'a' && *b <= 'z' ? *b - 32 : *b))
            return 0;
    return *a == *b;
}

static int walk_one(void *ctx, const char *name, size_t len)
{
    place_walk *w = ctx;
    fbrl_cell xt;
    void *obj;
    place pl;
    if (w->n >= 200 || fbrl_vmx_find(w->cw->vm, name, len, &xt) != FBRL_OK ||
        fbrl_glossary_object(w->cw->g, xt, &pl.kind, &obj) != FBRL_OK ||
        (pl.kind != FBRL_GLOSSARY_LOC && pl.kind != FBRL_GLOSSARY_RECTMAT && pl.kind != FBRL_GLOSSARY_RADMAT))
        return 0;
    const fbrl_loc *l = obj; /* a matrix starts with its base location */
    if (!isfinite(l->x) || !isfinite(l->y) || !isfinite(l->z))
        return 0;
    safe(pl.name, name, len);
    pl.obj = obj;
    pl.rack = NULL;
    for (size_t k = 0; pl.kind != FBRL_GLOSSARY_LOC && k < w->cw->nracks; k++)
        if (same_name(w->cw->racks[k].name, pl.name))
            pl.rack = &w->cw->racks[k];
    w->fn(w->ctx, &pl);
    w->n++;
    return 0;
}

static void each_place(fbrl_cell_words *cw, place_fn fn, void *ctx)
{
    place_walk w = {cw, fn, ctx, 0};
    if (cw->g)
        fbrl_vm_words(cw->vm, walk_one, &w);
}

/* Position (i, j) of a rack, as taught (FBRL_OK) */
static fbrl_status rack_pos(const place *pl, int i, int j, double p[3])
{
    fbrl_loc l;
    fbrl_status st = pl->kind == FBRL_GLOSSARY_RECTMAT ? fbrl_rectmat_loc(pl->obj, i, j, 0, &l)
                                                       : fbrl_radmat_loc(pl->obj, i, j, 0, &l);
    p[0] = l.x, p[1] = l.y, p[2] = l.z;
    return st == FBRL_OK && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) ? FBRL_OK : FBRL_ERANGE;
}

/* ---- the frame: everything drawn ---- */

static void grow(bounds *b, const double p[3])
{
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return;
    for (int i = 0; i < 3; i++)
        b->lo[i] = fmin(b->lo[i], p[i]), b->hi[i] = fmax(b->hi[i], p[i]);
}

static void grow_place(void *ctx, const place *pl)
{
    const fbrl_loc *l = pl->obj;
    double p[3] = {l->x, l->y, l->z};
    grow(ctx, p);
    for (int i = 0; pl->rack && i < pl->rack->rows; i++)
        for (int j = 0; j < pl->rack->cols; j++)
            if (rack_pos(pl, i, j, p) == FBRL_OK)
                grow(ctx, p);
}

static void frame(fbrl_cell_words *cw, bounds *b)
{
    double base[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++)
        b->lo[i] = INFINITY, b->hi[i] = -INFINITY;
    grow(b, base);
    if (cw->model.have_table) {
        double t[3] = {0, 0, cw->model.table_z};
        grow(b, t);
    }
    for (size_t k = 0; k < cw->model.n; k++) {
        bounds o;
        if (cw->model.obj[k].kind == FBRL_CELL_KEEPOUT)
            continue;
        obj_extent(cw, &cw->model.obj[k], o.lo, o.hi);
        grow(b, o.lo);
        grow(b, o.hi);
    }
    each_place(cw, grow_place, b);
    for (size_t k = 0; k < cw->npath; k++)
        grow(b, cw->path[k]);
    for (unsigned k = 0; k < cw->nrefused; k++) {
        for (unsigned i = 0; i < cw->refused[k].npts; i++)
            grow(b, cw->refused[k].pts[i]);
        if (cw->refused[k].hit)
            grow(b, cw->refused[k].at);
    }
    if (isfinite(cw->stats.clearance))
        grow(b, cw->stats.near);
    bounds in = *b;
    for (size_t k = 0; k < cw->model.n; k++) {
        bounds o;
        if (cw->model.obj[k].kind != FBRL_CELL_KEEPOUT)
            continue;
        obj_extent(cw, &cw->model.obj[k], o.lo, o.hi);
        /* the operator's side would shrink the cell to a corner: a zone wholly beyond the rest
         * shows its near SVG_KEEPOUT */
        for (int i = 0; i < 3; i++) {
            o.lo[i] = fmax(o.lo[i], fmin(in.lo[i], o.hi[i]) - SVG_KEEPOUT);
            o.hi[i] = fmin(o.hi[i], fmax(in.hi[i], o.lo[i]) + SVG_KEEPOUT);
        }
        grow(b, o.lo), grow(b, o.hi);
    }
    for (int i = 0; i < 3; i++) {
        double grow_by = fmax(0.0, SVG_MIN_SPAN - (b->hi[i] - b->lo[i])) / 2;
        b->lo[i] -= SVG_PAD + grow_by, b->hi[i] += SVG_PAD + grow_by;
    }
}

/* An obstacle's extent cut at the frame (only a keep-out zone reaches beyond it): 1 if cut. */
static int obj_in_frame(const svg_ctx *s, const fbrl_cell_obj *o, double lo[3], double hi[3])
{
    int cut = 0;
    obj_extent(s->cw, o, lo, hi);
    for (int i = 0; i < 3; i++) {
        cut |= lo[i] < s->frame.lo[i] || hi[i] > s->frame.hi[i];
        lo[i] = fmax(s->frame.lo[i], fmin(s->frame.hi[i], lo[i]));
        hi[i] = fmax(s->frame.lo[i], fmin(s->frame.hi[i], hi[i]));
    }
    return cut;
}

/* ---- a view ---- */

typedef struct place_draw {
    svg_ctx *s;
    const view *v;
    int labels; /* 0: the markers, 1: their labels */
} place_draw;

static void draw_place(void *ctx, const place *pl)
{
    place_draw *d = ctx;
    svg_ctx *s = d->s;
    const fbrl_loc *l = pl->obj;
    double p[3] = {l->x, l->y, l->z};
    char t[FBRL_CELL_NAME_MAX + 40];
    if (d->labels) {
        if (pl->rack)
            snprintf(t, sizeof t, "%s %dx%d", pl->name, pl->rack->rows, pl->rack->cols);
        else
            snprintf(t, sizeof t, "%s", pl->name);
        label(s, d->v, px(s, d->v, p[0]), py(s, d->v, p),
              pl->kind == FBRL_GLOSSARY_LOC ? "loclabel" : "matlabel", t, "");
        return;
    }
    for (int i = 0; pl->rack && i < pl->rack->rows; i++)
        for (int j = 0; j < pl->rack->cols; j++) {
            double q[3];
            if (rack_pos(pl, i, j, q) != FBRL_OK)
                continue;
            snprintf(t, sizeof t, "%s %d %d", pl->name, i, j);
            circle_px(s, "rackpos", px(s, d->v, q[0]), py(s, d->v, q), 2.5, t);
        }
    circle_px(s, pl->kind == FBRL_GLOSSARY_LOC ? "loc" : "matrix", px(s, d->v, p[0]), py(s, d->v, p), 3,
              pl->name);
}

static void polyline(svg_ctx *s, const view *v, const char *cls, const double (*pts)[3], size_t n,
                     const char *extra)
{
    char line[80], a[24], b[24];
    snprintf(line, sizeof line, "<polyline class=\"%s\"%s points=\"", cls, extra);
    out(s, line);
    for (size_t k = 0; k < n; k++) {
        snprintf(line, sizeof line, "%s,%s ", num(a, sizeof a, px(s, v, pts[k][0])),
                 num(b, sizeof b, py(s, v, pts[k])));
        out(s, line);
    }
    out(s, "\"/>\n");
}

static const char *obj_class(const fbrl_cell_obj *o)
{
    return o->kind == FBRL_CELL_KEEPOUT ? "keepout" : o->kind == FBRL_CELL_CYLINDER ? "cylinder" : "box";
}

static void draw_view(svg_ctx *s, const view *v)
{
    fbrl_cell_words *cw = s->cw;
    char t[FBRL_CELL_MSG_MAX], c[24];
    double base[3] = {0, 0, 0};
    place_draw d = {s, v, 0};
    rect_px(s, "frame", v->area.x0 + 0.5, v->area.y0 + 0.5, v->area.x1 - 0.5, v->area.y1 - 0.5, NULL);
    if (v->side && cw->model.have_table) {
        double p[3] = {0, 0, cw->model.table_z};
        line_px(s, "table", v->area.x0 + 1, py(s, v, p), v->area.x1 - 1, py(s, v, p), "");
    }
    circle_px(s, "base", px(s, v, 0), py(s, v, base), 6, "arm base");
    for (size_t k = 0; k < cw->model.n; k++) {
        const fbrl_cell_obj *o = &cw->model.obj[k];
        double lo[3], hi[3];
        snprintf(t, sizeof t, "%s%s", o->name, obj_in_frame(s, o, lo, hi) ? " (cut at the frame)" : "");
        rect_px(s, obj_class(o), px(s, v, lo[0]), py(s, v, lo), px(s, v, hi[0]), py(s, v, hi), t);
    }
    each_place(cw, draw_place, &d);
    if (cw->npath > 1)
        polyline(s, v, "path", (const double(*)[3])cw->path, cw->npath, "");
    if (isfinite(cw->stats.clearance))
        circle_px(s, "closest", px(s, v, cw->stats.near[0]), py(s, v, cw->stats.near), 6, NULL);
    for (unsigned k = 0; k < cw->nrefused; k++) {
        const fbrl_cell_refusal *rf = &cw->refused[k];
        polyline(s, v, "refused", (const double(*)[3])rf->pts, rf->npts,
                 " stroke=\"" SVG_RED "\" stroke-dasharray=\"5 3\"");
        if (rf->hit) { /* a cross where it would meet the obstacle */
            double x = px(s, v, rf->at[0]), y = py(s, v, rf->at);
            line_px(s, "refused", x - 5, y - 5, x + 5, y + 5, " stroke=\"" SVG_RED "\"");
            line_px(s, "refused", x - 5, y + 5, x + 5, y - 5, " stroke=\"" SVG_RED "\"");
        }
    }
    /* the labels, the most important first: each takes the first free place */
    label(s, v, v->area.x0 + 2, v->area.y0 + 14, "title",
          v->side ? "side view (x across, z up)" : "top view (x across, y up)", "");
    for (unsigned k = 0; k < cw->nrefused; k++) {
        const fbrl_cell_refusal *rf = &cw->refused[k];
        const double *at = rf->hit ? rf->at : rf->pts[rf->npts - 1];
        snprintf(t, sizeof t, "refused %s: %s %s", rf->word, rf->hit ? "would hit" : "cannot check",
                 rf->hit ? fbrl_cell_obj_name(&cw->model, rf->obj) : "it");
        label(s, v, px(s, v, at[0]) + 4, py(s, v, at), "refusedlabel", t, " fill=\"" SVG_RED "\"");
    }
    if (isfinite(cw->stats.clearance)) {
        snprintf(t, sizeof t, "closest %s in (%s)", num(c, sizeof c, cw->stats.clearance),
                 fbrl_cell_obj_name(&cw->model, cw->stats.near_obj));
        label(s, v, px(s, v, cw->stats.near[0]) + 4, py(s, v, cw->stats.near), "closestlabel", t, "");
    }
    for (size_t k = 0; k < cw->model.n; k++) {
        const fbrl_cell_obj *o = &cw->model.obj[k];
        double lo[3], hi[3];
        obj_in_frame(s, o, lo, hi);
        label(s, v, px(s, v, lo[0]), fmin(py(s, v, lo), py(s, v, hi)), "objlabel", o->name, "");
    }
    d.labels = 1;
    if (!v->side) /* the side view's places stand in rows at a few heights: the top view names them */
        each_place(cw, draw_place, &d);
}

/* ---- the legend and the scale bar ---- */

static void legend(svg_ctx *s, double w, double y0)
{
    static const char *const keys[][2] = {
        {"box", "solid obstacle"},       {"cylinder", "cylinder"},      {"keepout", "keep-out zone"},
        {"table", "table top"},          {"base", "arm base"},          {"loc", "named location"},
        {"matrix", "matrix base"},       {"rackpos", "rack position"},  {"path", "tool path"},
        {"closest", "closest approach"}, {"refused", "refused motion"},
    };
    char line[200], a[24], b[24];
    int cols = (int)((w - 2 * SVG_MARGIN) / SVG_LEG_COL);
    double lens[] = {100, 50, 20, 10, 5, 2, 1, 0.5, 0.25, 0.1}, len = lens[9];
    out(s, "<g id=\"legend\">\n");
    text_px(s, "title", SVG_MARGIN, y0 + 14, "legend", "");
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        double x = SVG_MARGIN + (double)(k % (size_t)cols) * SVG_LEG_COL;
        double y = y0 + 24 + (double)(k / (size_t)cols) * SVG_LEG_ROW;
        const char *cls = keys[k][0];
        if (!strcmp(cls, "table") || !strcmp(cls, "path") || !strcmp(cls, "refused"))
            line_px(s, cls, x, y + 6, x + 18, y + 6,
                    !strcmp(cls, "refused") ? " stroke=\"" SVG_RED "\" stroke-dasharray=\"5 3\"" : "");
        else if (!strcmp(cls, "box") || !strcmp(cls, "cylinder") || !strcmp(cls, "keepout"))
            rect_px(s, cls, x, y, x + 18, y + 12, NULL);
        else
            circle_px(s, cls, x + 9, y + 6, !strcmp(cls, "closest") || !strcmp(cls, "base") ? 5 : 3, NULL);
        text_px(s, "legendtext", x + 24, y + 10, keys[k][1], "");
    }
    double y =
        y0 + 24 + (double)((sizeof keys / sizeof keys[0] + (size_t)cols - 1) / (size_t)cols) * SVG_LEG_ROW;
    if (s->dropped) {
        snprintf(line, sizeof line, "%u labels had no free place: their names are in the tooltips",
                 s->dropped);
        text_px(s, "legendtext", SVG_MARGIN, y + 10, line, "");
        y += SVG_LEG_ROW;
    }
    out(s, "</g>\n<g id=\"scalebar\">\n");
    for (size_t k = 0; k < sizeof lens / sizeof lens[0]; k++) /* the longest round length up to 150 px */
        if (lens[k] * s->scale <= 150.0) {
            len = lens[k];
            break;
        }
    line_px(s, "scale", SVG_MARGIN, y + 8, SVG_MARGIN + len * s->scale, y + 8, "");
    line_px(s, "scale", SVG_MARGIN, y + 3, SVG_MARGIN, y + 13, "");
    line_px(s, "scale", SVG_MARGIN + len * s->scale, y + 3, SVG_MARGIN + len * s->scale, y + 13, "");
    if (fbrl_num_fixed(a, sizeof a, len, 0, len < 1 ? 2 : 0, 0, NULL) != FBRL_OK ||
        fbrl_num_fixed(b, sizeof b, s->scale, 0, 2, 0, NULL) != FBRL_OK)
        a[0] = b[0] = '\0';
    snprintf(line, sizeof line, "%s in (%s px per inch)", a, b);
    text_px(s, "legendtext", SVG_MARGIN + len * s->scale + 8, y + 12, line, "");
    out(s, "</g>\n");
}

/* Rows the legend takes (below the views). */
static double legend_h(double w)
{
    int cols = (int)((w - 2 * SVG_MARGIN) / SVG_LEG_COL);
    return 24 + (double)((11 + cols - 1) / cols) * SVG_LEG_ROW + 2 * SVG_LEG_ROW + 8;
}

fbrl_status fbrl_cell_svg(fbrl_cell_words *cw, fbrl_cell_write_fn fn, void *ctx)
{
    svg_ctx s;
    char line[300], w[24], h[24];
    bounds b;
    if (!cw || !fn)
        return FBRL_EINVAL;
    memset(&s, 0, sizeof s);
    s.cw = cw;
    s.fn = fn;
    s.ctx = ctx;
    cw_place_blocks(cw);
    frame(cw, &b);
    s.frame = b;
    double xr = b.hi[0] - b.lo[0], yr = b.hi[1] - b.lo[1], zr = b.hi[2] - b.lo[2];
    s.scale = fmin(SVG_FIT_W / xr, fmin(SVG_FIT_H / yr, SVG_FIT_H / zr));
    double width = fmax(SVG_MIN_W, xr * s.scale + 2 * SVG_MARGIN);
    double left = (width - xr * s.scale) / 2;
    double top_h = SVG_TITLE_H + yr * s.scale + 2 * SVG_MARGIN,
           side_h = SVG_TITLE_H + zr * s.scale + 2 * SVG_MARGIN;
    double height = top_h + side_h + legend_h(width);
    view top = {
        left - b.lo[0] * s.scale, SVG_TITLE_H + SVG_MARGIN + b.hi[1] * s.scale, 0, {0, 0, width, top_h}};
    view side = {
        top.ox, top_h + SVG_TITLE_H + SVG_MARGIN + b.hi[2] * s.scale, 1, {0, top_h, width, top_h + side_h}};
    snprintf(line, sizeof line,
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
             "width=\"%s\" height=\"%s\" viewBox=\"0 0 %s %s\">\n",
             num(w, sizeof w, width), num(h, sizeof h, height), num(w + 12, sizeof w - 12, width),
             num(h + 12, sizeof h - 12, height));
    out(&s, line);
    out(&s, "<style>rect.box{fill:#c8c8c8;stroke:#333}rect.cylinder{fill:#d8c8a8;stroke:#333}"
            "rect.keepout{fill:#f4b0b0;fill-opacity:0.5;stroke:#c00;stroke-dasharray:4 2}"
            ".frame{fill:none;stroke:#bbb}.leader{stroke:#999;stroke-width:0.5}.table{stroke:#630;stroke-"
            "width:3}.base{fill:#333}.loc{fill:#06c}"
            ".matrix{fill:#0a0}.rackpos{fill:none;stroke:#0a0;stroke-width:1}"
            ".path{fill:none;stroke:#f80;stroke-width:1.5}.closest{fill:none;stroke:#d00;stroke-width:2}"
            ".refused{fill:none;stroke-width:2}.scale{stroke:#000;stroke-width:2}"
            "text{font:10px sans-serif}.title{font-weight:bold}</style>\n");
    out(&s, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    out(&s, "<g id=\"top\">\n");
    draw_view(&s, &top);
    out(&s, "</g>\n<g id=\"side\">\n");
    draw_view(&s, &side);
    out(&s, "</g>\n");
    legend(&s, width, top_h + side_h);
    out(&s, "</svg>\n");
    return FBRL_OK;
}
#else
fbrl_status fbrl_cell_svg(fbrl_cell_words *cw, fbrl_cell_write_fn fn, void *ctx)
{
    (void)cw, (void)fn, (void)ctx;
    return FBRL_EUNSUPPORTED;
}
#endif
