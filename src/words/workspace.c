/* SPDX-License-Identifier: MIT */
/* workspace.c - a session's named work in one data file (include/fbrl/workspace.h):
 * SAVE-WORKSPACE, LOAD-WORKSPACE, WORKSPACE, WORKSPACE-CHANGED?, and what a save would
 * change in a file (fbrl_workspace_diff).
 *
 * Saving walks the dictionary (fbrl_vm_words: every visible name once) and asks the
 * glossary and the robot what each word is; each object becomes one fileio user record
 * holding its name and numbers. The same walk, fed to a CRC instead of the file, is the
 * session's fingerprint that tells whether anything changed since the last save or load.
 * Loading checks the whole file before it changes anything, then makes the missing words
 * (undone all together if the dictionary fills) and only then writes the values. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "fbrl/calib.h"
#include "fbrl/crc32.h"
#include "fbrl/matrix.h"
#include "fbrl/vmx.h"
#include "fbrl/workspace.h"

#define WS_INSTALLED 0x57535043u /* "WSPC" */
#define HEAD_NAME    "FBRL-WORKSPACE"
#define NAME_MAX_LEN 31
#define VALS_MAX     18

/* One record, decoded. */
typedef struct rec {
    uint16_t tag;
    size_t nlen;
    char name[NAME_MAX_LEN + 1];
    double v[VALS_MAX];
} rec;

static size_t nvals(uint16_t tag)
{
    switch (tag) {
    case FBRL_WORKSPACE_TAG_HEAD: return 1;
    case FBRL_WORKSPACE_TAG_LOC: return 6;
    case FBRL_WORKSPACE_TAG_RECTMAT: return 9;
    case FBRL_WORKSPACE_TAG_RADMAT: return 9;
    case FBRL_WORKSPACE_TAG_CAL: return 18;
    case FBRL_WORKSPACE_TAG_CALSTRU: return 12;
    case FBRL_WORKSPACE_TAG_DEVICE: return 3;
    case FBRL_WORKSPACE_TAG_SET: return 5;
    default: return 0;
    }
}

static const char *kind_name(uint16_t tag)
{
    switch (tag) {
    case FBRL_WORKSPACE_TAG_LOC: return "a location";
    case FBRL_WORKSPACE_TAG_RECTMAT: return "a RECTMAT";
    case FBRL_WORKSPACE_TAG_RADMAT: return "a RADMAT";
    case FBRL_WORKSPACE_TAG_CAL: return "a calibration (CREATE-CAL)";
    case FBRL_WORKSPACE_TAG_CALSTRU: return "a calibration structure";
    case FBRL_WORKSPACE_TAG_DEVICE: return "a device";
    default: return "another word";
    }
}

/* ---- records: name and little-endian doubles ---- */

static size_t encode(const rec *r, unsigned char *out)
{
    size_t n = nvals(r->tag), k = 0;
    out[k++] = (unsigned char)r->nlen;
    memcpy(out + k, r->name, r->nlen);
    k += r->nlen;
    for (size_t i = 0; i < n; i++) {
        uint64_t bits;
        memcpy(&bits, &r->v[i], sizeof bits);
        for (int b = 0; b < 8; b++)
            out[k++] = (unsigned char)(bits >> (8 * b));
    }
    return k;
}

static int name_ok(const char *s, size_t n)
{
    if (n < 1 || n > NAME_MAX_LEN)
        return 0;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)s[i] <= ' ' || (unsigned char)s[i] >= 0x7f)
            return 0;
    return 1;
}

/* 0, or a reason the bytes are not a record of that tag. */
static const char *decode(const unsigned char *b, size_t size, uint16_t tag, rec *r)
{
    size_t n = nvals(tag), k = 1;
    if (n == 0)
        return "unknown record";
    if (size < 1 || size != 1u + b[0] + 8u * n)
        return "wrong length";
    r->tag = tag;
    r->nlen = b[0];
    memcpy(r->name, b + 1, r->nlen);
    r->name[r->nlen] = 0;
    k += r->nlen;
    if (tag == FBRL_WORKSPACE_TAG_SET ? (r->nlen && !name_ok(r->name, r->nlen)) : !name_ok(r->name, r->nlen))
        return "bad name";
    for (size_t i = 0; i < n; i++, k += 8) {
        uint64_t bits = 0;
        for (int j = 0; j < 8; j++)
            bits |= (uint64_t)b[k + (size_t)j] << (8 * j);
        memcpy(&r->v[i], &bits, sizeof bits);
        if (!isfinite(r->v[i]))
            return "a number is not finite";
    }
    return NULL;
}

static void put_loc(double *v, const fbrl_loc *l)
{
    v[0] = l->x, v[1] = l->y, v[2] = l->z, v[3] = l->o, v[4] = l->a, v[5] = l->t;
}

static fbrl_loc get_loc(const double *v)
{
    fbrl_loc l;
    l.x = v[0], l.y = v[1], l.z = v[2], l.o = v[3], l.a = v[4], l.t = v[5];
    return l;
}

static int is_int(double v, double lo, double hi) { return v >= lo && v <= hi && floor(v) == v; }

/* The checks a record's numbers must pass before anything is made of them. */
static const char *values_ok(const rec *r)
{
    const double *v = r->v;
    fbrl_loc base = get_loc(v);
    fbrl_rectmat rm;
    fbrl_radmat dm;
    switch (r->tag) {
    case FBRL_WORKSPACE_TAG_RECTMAT:
        return fbrl_rectmat_init(&rm, &base, v[6], v[7], v[8]) == FBRL_OK ? NULL : "not a RECTMAT";
    case FBRL_WORKSPACE_TAG_RADMAT:
        return fbrl_radmat_init(&dm, &base, v[6], v[7], v[8]) == FBRL_OK
                   ? NULL
                   : "not a RADMAT (base on the centre axis?)";
    case FBRL_WORKSPACE_TAG_DEVICE:
        if (!is_int(v[0], 1, FBRL_ROBOT_IO_MAX))
            return "device port outside 1..16";
        if (v[1] != 0.0 && v[1] != 1.0)
            return "device neither input nor output";
        if (!is_int(v[2], FBRL_ROBOT_PULSE_MIN, FBRL_ROBOT_PULSE_MAX))
            return "pulse width out of range";
        return NULL;
    case FBRL_WORKSPACE_TAG_SET: return v[0] == 0.0 || v[0] == 1.0 ? NULL : "MAP-ON neither on nor off";
    default: return NULL;
    }
}

static int rigid(const double *v)
{
    fbrl_calib c;
    unsigned char b[FBRL_CALIB_BYTES];
    memcpy(c.r, v, sizeof c.r);
    memcpy(c.t, v + 9, sizeof c.t);
    return fbrl_calib_save(&c, b, sizeof b) == FBRL_OK; /* it accepts exactly the rigid motions */
}

/* ---- what a word is ---- */

typedef struct obj {
    uint16_t tag; /* 0: none of ours */
    void *p;      /* glossary object */
    fbrl_robot_device dev;
} obj;

static obj classify(fbrl_workspace *ws, fbrl_cell xt)
{
    obj o;
    fbrl_glossary_kind k = FBRL_GLOSSARY_NONE;
    memset(&o, 0, sizeof o);
    if (fbrl_glossary_object(ws->g, xt, &k, &o.p) != FBRL_OK)
        k = FBRL_GLOSSARY_NONE;
    switch (k) {
    case FBRL_GLOSSARY_LOC: o.tag = FBRL_WORKSPACE_TAG_LOC; break;
    case FBRL_GLOSSARY_RECTMAT: o.tag = FBRL_WORKSPACE_TAG_RECTMAT; break;
    case FBRL_GLOSSARY_RADMAT: o.tag = FBRL_WORKSPACE_TAG_RADMAT; break;
    case FBRL_GLOSSARY_CAL: o.tag = FBRL_WORKSPACE_TAG_CAL; break;
    case FBRL_GLOSSARY_CALSTRU: o.tag = FBRL_WORKSPACE_TAG_CALSTRU; break;
    default:
        if (ws->r && fbrl_robot_device_of(ws->r, xt, &o.dev) == FBRL_OK)
            o.tag = FBRL_WORKSPACE_TAG_DEVICE;
        break;
    }
    return o;
}

static const char *word_kind(fbrl_workspace *ws, fbrl_cell xt)
{
    obj o = classify(ws, xt);
    return o.tag ? kind_name(o.tag) : "another word";
}

/* The object's numbers into r->v. */
static void object_values(const obj *o, rec *r)
{
    double *v = r->v;
    r->tag = o->tag;
    switch (o->tag) {
    case FBRL_WORKSPACE_TAG_LOC: put_loc(v, o->p); break;
    case FBRL_WORKSPACE_TAG_RECTMAT: {
        const fbrl_rectmat *m = o->p;
        put_loc(v, &m->base);
        v[6] = m->dx, v[7] = m->dy, v[8] = m->dz;
        break;
    }
    case FBRL_WORKSPACE_TAG_RADMAT: {
        const fbrl_radmat *m = o->p;
        put_loc(v, &m->base);
        v[6] = m->inc_angle, v[7] = m->ring_dist, v[8] = m->z_off;
        break;
    }
    case FBRL_WORKSPACE_TAG_CAL: {
        const fbrl_calpts *c = o->p;
        for (int k = 0; k < 3; k++)
            put_loc(v + 6 * k, &c->p[k]);
        break;
    }
    case FBRL_WORKSPACE_TAG_CALSTRU: {
        const fbrl_calib *c = o->p;
        memcpy(v, c->r, sizeof c->r);
        memcpy(v + 9, c->t, sizeof c->t);
        break;
    }
    case FBRL_WORKSPACE_TAG_DEVICE:
        v[0] = o->dev.port, v[1] = o->dev.output ? 1.0 : 0.0, v[2] = o->dev.pulse_ms;
        break;
    default: break;
    }
}

/* Write r's numbers into the object (checked by values_ok before). */
static void set_values(fbrl_workspace *ws, const obj *o, const rec *r)
{
    const double *v = r->v;
    switch (r->tag) {
    case FBRL_WORKSPACE_TAG_LOC: *(fbrl_loc *)o->p = get_loc(v); break;
    case FBRL_WORKSPACE_TAG_RECTMAT: {
        fbrl_loc base = get_loc(v);
        fbrl_rectmat_init(o->p, &base, v[6], v[7], v[8]);
        break;
    }
    case FBRL_WORKSPACE_TAG_RADMAT: {
        fbrl_loc base = get_loc(v);
        fbrl_radmat_init(o->p, &base, v[6], v[7], v[8]);
        break;
    }
    case FBRL_WORKSPACE_TAG_CAL: {
        fbrl_calpts *c = o->p;
        for (int k = 0; k < 3; k++)
            c->p[k] = get_loc(v + 6 * k);
        break;
    }
    case FBRL_WORKSPACE_TAG_CALSTRU: {
        fbrl_calib *c = o->p;
        memcpy(c->r, v, sizeof c->r);
        memcpy(c->t, v + 9, sizeof c->t);
        break;
    }
    case FBRL_WORKSPACE_TAG_DEVICE:
        fbrl_robot_define_device(ws->r, r->name, r->nlen, (int)v[0], v[1] != 0.0, (uint32_t)v[2]);
        break;
    default: break;
    }
}

static void count(fbrl_workspace_counts *n, uint16_t tag)
{
    switch (tag) {
    case FBRL_WORKSPACE_TAG_LOC: n->locs++; break;
    case FBRL_WORKSPACE_TAG_RECTMAT:
    case FBRL_WORKSPACE_TAG_RADMAT: n->matrices++; break;
    case FBRL_WORKSPACE_TAG_CAL:
    case FBRL_WORKSPACE_TAG_CALSTRU: n->cals++; break;
    case FBRL_WORKSPACE_TAG_DEVICE: n->devices++; break;
    default: break;
    }
}

/* ---- the walk over the session: to the file, to the fingerprint, to the console ---- */

enum { TO_CRC, TO_FILE, TO_CONSOLE, TO_DIFF };

typedef struct walk {
    fbrl_workspace *ws;
    int to;
    uint32_t crc;
    fbrl_status st;
    fbrl_workspace_counts n;
    fbrl_cell with_cal; /* WITH-CAL's data field */
    rec set;            /* the settings record; its name found on the way */
    fbrl_workspace_diff_fn diff; /* TO_DIFF: told of each difference with the open file */
    void *diff_ctx;
    unsigned diffs;
} walk;

static void compare(walk *w, const rec *r);

static void emit(walk *w, const rec *r)
{
    unsigned char b[FBRL_WORKSPACE_RECORD_MAX];
    size_t size = encode(r, b);
    unsigned char tag[2] = {(unsigned char)(r->tag & 0xff), (unsigned char)(r->tag >> 8)};
    if (r->tag != FBRL_WORKSPACE_TAG_HEAD)
        w->crc = fbrl_crc32(fbrl_crc32(w->crc, tag, 2), b, size);
    if (w->to == TO_FILE && w->st == FBRL_OK)
        w->st = fbrl_file_write_user(&w->ws->file, r->tag, b, size);
}

static void show(walk *w, const rec *r)
{
    char line[160];
    const double *v = r->v;
    switch (r->tag) {
    case FBRL_WORKSPACE_TAG_LOC:
        snprintf(line, sizeof line, "  %-16s location     %.4f %.4f %.4f  %.2f %.2f %.2f\n", r->name, v[0],
                 v[1], v[2], v[3], v[4], v[5]);
        break;
    case FBRL_WORKSPACE_TAG_DEVICE:
        snprintf(line, sizeof line, "  %-16s %s device  port %d\n", r->name,
                 v[1] != 0.0 ? "output" : "input ", (int)v[0]);
        break;
    default: snprintf(line, sizeof line, "  %-16s %s\n", r->name, kind_name(r->tag) + 2); break;
    }
    fbrl_vmx_puts(w->ws->vm, line);
}

static int visit(void *ctx, const char *name, size_t len)
{
    walk *w = ctx;
    fbrl_cell xt;
    rec r;
    if (fbrl_vmx_find(w->ws->vm, name, len, &xt) != FBRL_OK)
        return 0;
    obj o = classify(w->ws, xt);
    if (!o.tag || !name_ok(name, len))
        return 0;
    memset(&r, 0, sizeof r);
    r.nlen = len;
    memcpy(r.name, name, len);
    object_values(&o, &r);
    if (o.tag == FBRL_WORKSPACE_TAG_CALSTRU && w->with_cal &&
        (unsigned char *)o.p == (unsigned char *)w->with_cal + FBRL_VMX_PAYLOAD) {
        w->set.nlen = len;
        memcpy(w->set.name, name, len);
    }
    count(&w->n, o.tag);
    if (w->to == TO_CONSOLE)
        show(w, &r);
    else if (w->to == TO_DIFF)
        compare(w, &r);
    else
        emit(w, &r);
    return w->st != FBRL_OK;
}

/* Every object of the session to `to` (TO_DIFF: fn told of each difference with the open file). */
static fbrl_status walk_all(fbrl_workspace *ws, int to, walk *w, fbrl_workspace_diff_fn fn, void *ctx)
{
    int map_on = 0;
    double base[4] = {0, 0, 0, 0};
    memset(w, 0, sizeof *w);
    w->ws = ws;
    w->to = to;
    w->diff = fn;
    w->diff_ctx = ctx;
    fbrl_glossary_mapping(ws->g, &w->with_cal, &map_on);
    if (ws->r)
        fbrl_robot_base_offset(ws->r, base);
    if (to == TO_FILE) {
        rec h;
        memset(&h, 0, sizeof h);
        h.tag = FBRL_WORKSPACE_TAG_HEAD;
        h.nlen = sizeof HEAD_NAME - 1;
        memcpy(h.name, HEAD_NAME, h.nlen);
        h.v[0] = FBRL_WORKSPACE_VERSION;
        emit(w, &h);
    }
    fbrl_vm_words(ws->vm, visit, w);
    w->set.tag = FBRL_WORKSPACE_TAG_SET;
    w->set.v[0] = map_on ? 1.0 : 0.0;
    memcpy(w->set.v + 1, base, sizeof base);
    if (to == TO_DIFF)
        compare(w, &w->set);
    else if (to != TO_CONSOLE)
        emit(w, &w->set);
    return w->st;
}

static uint32_t fingerprint(fbrl_workspace *ws, fbrl_workspace_counts *n)
{
    walk w;
    walk_all(ws, TO_CRC, &w, NULL, NULL);
    if (n)
        *n = w.n;
    return w.crc;
}

/* ---- the C interface ---- */

static int installed(const fbrl_workspace *ws) { return ws && ws->magic == WS_INSTALLED; }

static void set_path(fbrl_workspace *ws, const char *path)
{
    size_t n = strlen(path);
    if (n >= sizeof ws->path)
        n = sizeof ws->path - 1;
    memcpy(ws->path, path, n);
    ws->path[n] = 0;
}

fbrl_status fbrl_workspace_save(fbrl_workspace *ws, const char *path, fbrl_workspace_counts *n)
{
    fbrl_ftype t;
    walk w;
    if (!installed(ws) || !path)
        return FBRL_EINVAL;
    if (strlen(path) >= FBRL_FILE_PATH_MAX)
        return FBRL_ENAME;
    fbrl_status st = fbrl_file_open(&ws->file, path, ws->buf, ws->cap);
    if (st == FBRL_ENOENT) { /* a new file (nothing to lose by creating it first) */
        if ((st = fbrl_file_create(path)) != FBRL_OK)
            return st;
        st = fbrl_file_open(&ws->file, path, ws->buf, ws->cap);
    }
    if (st != FBRL_OK)
        return st;
    /* replace only a workspace (or an empty data file): never a user's other data */
    if (fbrl_file_peek(&ws->file, &t) == FBRL_OK &&
        (t.code != FBRL_FT_USER || t.tag != FBRL_WORKSPACE_TAG_HEAD)) {
        fbrl_file_discard(&ws->file);
        return FBRL_EFORMAT;
    }
    if ((st = fbrl_file_truncate(&ws->file)) == FBRL_OK)
        st = walk_all(ws, TO_FILE, &w, NULL, NULL);
    if (st == FBRL_OK)
        st = fbrl_file_close(&ws->file);
    if (st != FBRL_OK) {
        fbrl_file_discard(&ws->file);
        return st;
    }
    ws->mark = w.crc;
    set_path(ws, path);
    if (n)
        *n = w.n;
    return FBRL_OK;
}

/* Read the next record: 1 one read, 0 at the end, -1 not a workspace record (why set). */
static int next_rec(fbrl_workspace *ws, unsigned index, rec *r, char *why, size_t cap)
{
    fbrl_ftype t;
    unsigned char b[FBRL_WORKSPACE_RECORD_MAX];
    const char *bad;
    if (fbrl_file_peek(&ws->file, &t) != FBRL_OK)
        return 0;
    if (t.code != FBRL_FT_USER || nvals(t.tag) == 0 || t.size > sizeof b) {
        snprintf(why, cap, "record %u is not a workspace record", index);
        return -1;
    }
    if (fbrl_file_read_user(&ws->file, t.tag, b, t.size) != FBRL_OK) {
        snprintf(why, cap, "record %u cannot be read", index);
        return -1;
    }
    if ((bad = decode(b, t.size, t.tag, r)) != NULL) {
        snprintf(why, cap, "record %u: %s", index, bad);
        return -1;
    }
    return 1;
}

static fbrl_status fail(fbrl_workspace *ws, fbrl_status st)
{
    fbrl_file_discard(&ws->file);
    return st;
}

/* Is the structure named in the settings usable for MAP-ON: in the file (its record's
 * numbers) or else in the session? */
static const char *with_cal_ok(fbrl_workspace *ws, const rec *set)
{
    rec r;
    char why[8];
    unsigned i = 1;
    fbrl_cell xt;
    fbrl_file_reset(&ws->file);
    while (next_rec(ws, i++, &r, why, sizeof why) == 1)
        if (r.tag == FBRL_WORKSPACE_TAG_CALSTRU && r.nlen == set->nlen &&
            memcmp(r.name, set->name, r.nlen) == 0)
            return set->v[0] == 0.0 || rigid(r.v) ? NULL
                                                  : "MAP-ON with a calibration structure that is not rigid";
    if (fbrl_vmx_find(ws->vm, set->name, set->nlen, &xt) == FBRL_OK) {
        obj o = classify(ws, xt);
        if (o.tag == FBRL_WORKSPACE_TAG_CALSTRU) {
            object_values(&o, &r);
            return set->v[0] == 0.0 || rigid(r.v) ? NULL
                                                  : "MAP-ON with a calibration structure that is not rigid";
        }
    }
    return "WITH-CAL names no calibration structure of the file or the session";
}

fbrl_status fbrl_workspace_load(fbrl_workspace *ws, const char *path, fbrl_workspace_counts *n, char *why,
                                size_t cap)
{
    char scratch[160];
    rec r, set;
    fbrl_workspace_counts cnt;
    fbrl_vmx_mark mark;
    fbrl_cell xt;
    size_t new_devices = 0;
    unsigned i;
    int got, have_set = 0;
    if (!why || cap == 0)
        why = scratch, cap = sizeof scratch;
    why[0] = 0;
    if (!installed(ws) || !path)
        return FBRL_EINVAL;
    if (strlen(path) >= FBRL_FILE_PATH_MAX)
        return FBRL_ENAME;
    fbrl_status st = fbrl_file_open(&ws->file, path, ws->buf, ws->cap);
    if (st != FBRL_OK) {
        snprintf(why, cap, "%s", fbrl_status_str(st));
        return st;
    }
    /* 1. every record checked against the file's rules and the session's words */
    if (next_rec(ws, 0, &r, why, cap) != 1 || r.tag != FBRL_WORKSPACE_TAG_HEAD ||
        strcmp(r.name, HEAD_NAME) != 0) {
        snprintf(why, cap, "not a workspace (a data file without the workspace header)");
        return fail(ws, FBRL_EFORMAT);
    }
    if (!is_int(r.v[0], 1, 65535)) {
        snprintf(why, cap, "bad workspace version");
        return fail(ws, FBRL_EFORMAT);
    }
    if (r.v[0] > FBRL_WORKSPACE_VERSION) {
        snprintf(why, cap, "workspace version %d is newer than this fbrl reads (%u)", (int)r.v[0],
                 FBRL_WORKSPACE_VERSION);
        return fail(ws, FBRL_EVERSION);
    }
    memset(&cnt, 0, sizeof cnt);
    memset(&set, 0, sizeof set);
    for (i = 1; (got = next_rec(ws, i, &r, why, cap)) == 1; i++) {
        const char *bad;
        if (r.tag == FBRL_WORKSPACE_TAG_HEAD || (r.tag == FBRL_WORKSPACE_TAG_SET && have_set)) {
            snprintf(why, cap, "record %u: a second %s record", i,
                     r.tag == FBRL_WORKSPACE_TAG_HEAD ? "header" : "settings");
            return fail(ws, FBRL_EFORMAT);
        }
        if ((bad = values_ok(&r)) != NULL) {
            snprintf(why, cap, "record %u (%s): %s", i, r.name, bad);
            return fail(ws, FBRL_EFORMAT);
        }
        if (r.tag == FBRL_WORKSPACE_TAG_SET) {
            set = r;
            have_set = 1;
            continue;
        }
        if (r.tag == FBRL_WORKSPACE_TAG_DEVICE && !ws->r) {
            snprintf(why, cap, "record %u (%s): a device, and this session has no robot words", i, r.name);
            return fail(ws, FBRL_ETYPE);
        }
        if (fbrl_vmx_find(ws->vm, r.name, r.nlen, &xt) == FBRL_OK) {
            if (classify(ws, xt).tag != r.tag) {
                snprintf(why, cap, "record %u: %s is %s here, %s in the file", i, r.name, word_kind(ws, xt),
                         kind_name(r.tag));
                return fail(ws, FBRL_ETYPE);
            }
        } else if (r.tag == FBRL_WORKSPACE_TAG_DEVICE) {
            new_devices++;
        }
        count(&cnt, r.tag);
    }
    if (got < 0)
        return fail(ws, FBRL_EFORMAT);
    if (ws->r && new_devices > fbrl_robot_devices_free(ws->r)) {
        snprintf(why, cap, "%u new devices, room for %u", (unsigned)new_devices,
                 (unsigned)fbrl_robot_devices_free(ws->r));
        return fail(ws, FBRL_EFULL);
    }
    if (have_set && set.nlen) {
        const char *bad = with_cal_ok(ws, &set);
        if (bad) {
            snprintf(why, cap, "settings (WITH-CAL %s): %s", set.name, bad);
            return fail(ws, FBRL_EFORMAT);
        }
    } else if (have_set && set.v[0] != 0.0) {
        snprintf(why, cap, "settings: MAP-ON without a WITH-CAL structure");
        return fail(ws, FBRL_EFORMAT);
    }
    /* 2. the missing words, made all together or not at all */
    fbrl_vmx_mark_here(ws->vm, &mark);
    fbrl_file_reset(&ws->file);
    for (i = 1; next_rec(ws, i, &r, why, cap) == 1; i++) {
        void *p;
        if (r.tag == FBRL_WORKSPACE_TAG_HEAD || r.tag == FBRL_WORKSPACE_TAG_SET)
            continue;
        if (fbrl_vmx_find(ws->vm, r.name, r.nlen, &xt) == FBRL_OK) {
            if (classify(ws, xt).tag == r.tag)
                continue;
            snprintf(why, cap, "record %u: %s is in the file twice, as %s and as %s", i, r.name,
                     word_kind(ws, xt), kind_name(r.tag));
            st = FBRL_ETYPE;
        } else if (r.tag == FBRL_WORKSPACE_TAG_DEVICE) {
            st =
                fbrl_robot_define_device(ws->r, r.name, r.nlen, (int)r.v[0], r.v[1] != 0.0, (uint32_t)r.v[2]);
        } else {
            fbrl_glossary_kind k = r.tag == FBRL_WORKSPACE_TAG_LOC       ? FBRL_GLOSSARY_LOC
                                   : r.tag == FBRL_WORKSPACE_TAG_RECTMAT ? FBRL_GLOSSARY_RECTMAT
                                   : r.tag == FBRL_WORKSPACE_TAG_RADMAT  ? FBRL_GLOSSARY_RADMAT
                                   : r.tag == FBRL_WORKSPACE_TAG_CAL     ? FBRL_GLOSSARY_CAL
                                                                         : FBRL_GLOSSARY_CALSTRU;
            st = fbrl_glossary_make(ws->g, k, r.name, r.nlen, &p);
        }
        if (st != FBRL_OK) {
            if (!why[0] || st != FBRL_ETYPE)
                snprintf(why, cap, "the dictionary is full (record %u, %s)", i, r.name);
            fbrl_vmx_forget(ws->vm, &mark);
            return fail(ws, st == FBRL_ETYPE ? st : FBRL_ENOMEM);
        }
    }
    /* 3. the values (every one checked above: nothing here can fail) */
    fbrl_file_reset(&ws->file);
    for (i = 1; next_rec(ws, i, &r, why, cap) == 1; i++) {
        if (r.tag == FBRL_WORKSPACE_TAG_HEAD || r.tag == FBRL_WORKSPACE_TAG_SET)
            continue;
        if (fbrl_vmx_find(ws->vm, r.name, r.nlen, &xt) != FBRL_OK)
            continue;
        obj o = classify(ws, xt);
        set_values(ws, &o, &r);
    }
    if (have_set) {
        fbrl_cell with_cal = 0;
        if (set.nlen && fbrl_vmx_find(ws->vm, set.name, set.nlen, &xt) == FBRL_OK) {
            obj o = classify(ws, xt);
            with_cal = (fbrl_cell)((unsigned char *)o.p - FBRL_VMX_PAYLOAD);
        }
        fbrl_glossary_set_mapping(ws->g, with_cal, set.v[0] != 0.0);
        if (ws->r)
            fbrl_robot_set_base_offset(ws->r, set.v + 1);
    }
    fbrl_file_discard(&ws->file);
    why[0] = 0;
    ws->mark = fingerprint(ws, NULL);
    set_path(ws, path);
    if (n)
        *n = cnt;
    return FBRL_OK;
}

/* ---- what a save would change in a file ---- */

static void tell(walk *w, fbrl_workspace_change change, const rec *was, const rec *now)
{
    const rec *r = now ? now : was;
    fbrl_workspace_delta d;
    d.change = change;
    d.name = r->tag == FBRL_WORKSPACE_TAG_SET ? "" : r->name;
    d.kind = r->tag == FBRL_WORKSPACE_TAG_SET ? "the settings" : kind_name(r->tag);
    d.tag = r->tag;
    d.n = nvals(r->tag);
    d.was = was ? was->v : NULL;
    d.now = now ? now->v : NULL;
    w->diffs++;
    if (w->diff)
        w->diff(w->diff_ctx, &d);
}

/* The file's record of r's name (and kind, for the settings), if it has one. */
static int find_rec(fbrl_workspace *ws, const rec *r, rec *out)
{
    char why[8];
    int got;
    if (fbrl_file_reset(&ws->file) != FBRL_OK || next_rec(ws, 0, out, why, sizeof why) != 1)
        return 0;
    for (unsigned i = 1; (got = next_rec(ws, i, out, why, sizeof why)) == 1; i++) {
        if (r->tag == FBRL_WORKSPACE_TAG_SET ? out->tag == FBRL_WORKSPACE_TAG_SET
                                             : out->tag != FBRL_WORKSPACE_TAG_SET && strcasecmp(out->name, r->name) == 0)
            return 1;
    }
    return 0;
}

/* One object of the session against the file. */
static void compare(walk *w, const rec *r)
{
    rec f;
    if (!find_rec(w->ws, r, &f)) {
        if (r->tag != FBRL_WORKSPACE_TAG_SET) /* a file without settings: nothing to lose there */
            tell(w, FBRL_WORKSPACE_ADDED, NULL, r);
        return;
    }
    if (f.tag != r->tag) { /* the file's object goes, the session's comes */
        tell(w, FBRL_WORKSPACE_DROPPED, &f, NULL);
        tell(w, FBRL_WORKSPACE_ADDED, NULL, r);
    } else if (memcmp(f.v, r->v, nvals(r->tag) * sizeof r->v[0]) != 0 ||
               (r->tag == FBRL_WORKSPACE_TAG_SET && strcasecmp(f.name, r->name) != 0)) {
        tell(w, FBRL_WORKSPACE_CHANGED, &f, r);
    }
}

fbrl_status fbrl_workspace_diff(fbrl_workspace *ws, const char *path, fbrl_workspace_diff_fn fn, void *ctx,
                                unsigned *count)
{
    char why[8];
    rec r;
    walk w;
    fbrl_cell xt;
    int got;
    if (!installed(ws) || !path)
        return FBRL_EINVAL;
    if (strlen(path) >= FBRL_FILE_PATH_MAX)
        return FBRL_ENAME;
    fbrl_status st = fbrl_file_open(&ws->file, path, ws->buf, ws->cap);
    if (st != FBRL_OK)
        return st;
    if (next_rec(ws, 0, &r, why, sizeof why) != 1 || r.tag != FBRL_WORKSPACE_TAG_HEAD ||
        strcmp(r.name, HEAD_NAME) != 0)
        return fail(ws, FBRL_EFORMAT);
    /* the session's objects, as a save writes them; each looked up in the file */
    st = walk_all(ws, TO_DIFF, &w, fn, ctx);
    /* what the file holds and the session does not: a save would drop it */
    if (st == FBRL_OK && (st = fbrl_file_reset(&ws->file)) == FBRL_OK && next_rec(ws, 0, &r, why, sizeof why) == 1)
        for (unsigned i = 1; (got = next_rec(ws, i, &r, why, sizeof why)) == 1; i++) {
            if (r.tag == FBRL_WORKSPACE_TAG_SET)
                continue;
            if (fbrl_vmx_find(ws->vm, r.name, r.nlen, &xt) != FBRL_OK || classify(ws, xt).tag != r.tag)
                tell(&w, FBRL_WORKSPACE_DROPPED, &r, NULL);
        }
    fbrl_file_discard(&ws->file);
    if (count)
        *count = w.diffs;
    return st;
}

fbrl_status fbrl_workspace_changed(fbrl_workspace *ws, int *changed, fbrl_workspace_counts *n)
{
    if (!installed(ws) || !changed)
        return FBRL_EINVAL;
    *changed = fingerprint(ws, n) != ws->mark;
    return FBRL_OK;
}

const char *fbrl_workspace_path(const fbrl_workspace *ws) { return installed(ws) ? ws->path : ""; }

/* ---- the words ---- */

static fbrl_status parse_path(fbrl_vm *vm, const char *word, char *path)
{
    const char *p;
    size_t n;
    int q = fbrl_vmx_parse_quoted(vm, &p, &n);
    if (q == 0)
        return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NUMBER, "%s: the file name has no closing \"", word);
    if (q < 0)
        fbrl_vm_parse_name(vm, &p, &n);
    if (n == 0)
        return fbrl_vmx_throwf(vm, FBRL_THROW_NO_NAME, "%s: file name missing (%s FILE)", word, word);
    if (n >= FBRL_FILE_PATH_MAX)
        return fbrl_vmx_throwf(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ENAME), "%s: file name too long", word);
    memcpy(path, p, n);
    path[n] = 0;
    return FBRL_OK;
}

static void counts_text(const fbrl_workspace_counts *n, char *buf, size_t cap)
{
    snprintf(buf, cap, "%u location%s, %u matri%s, %u calibration%s, %u device%s", n->locs,
             n->locs == 1 ? "" : "s", n->matrices, n->matrices == 1 ? "x" : "ces", n->cals,
             n->cals == 1 ? "" : "s", n->devices, n->devices == 1 ? "" : "s");
}

static fbrl_status w_save(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_workspace *ws = ctx;
    char path[FBRL_FILE_PATH_MAX], what[128], line[FBRL_FILE_PATH_MAX + 160];
    fbrl_workspace_counts n;
    fbrl_status st;
    (void)word;
    if ((st = parse_path(vm, "SAVE-WORKSPACE", path)) != FBRL_OK)
        return st;
    st = fbrl_workspace_save(ws, path, &n);
    if (st == FBRL_EFORMAT)
        return fbrl_vmx_throwf(
            vm, FBRL_VM_THROW_OF_STATUS(st),
            "SAVE-WORKSPACE %.60s: the file is another kind of data, not a workspace: not replaced", path);
    if (st == FBRL_ENOSPC)
        return fbrl_vmx_throwf(
            vm, FBRL_VM_THROW_OF_STATUS(st),
            "SAVE-WORKSPACE %.60s: more objects than the buffer holds (%lu bytes); nothing written", path,
            (unsigned long)ws->cap);
    if (st != FBRL_OK)
        return fbrl_vmx_throwf(vm, FBRL_VM_THROW_OF_STATUS(st),
                               "SAVE-WORKSPACE %.60s: %s; the file is unchanged", path, fbrl_status_str(st));
    counts_text(&n, what, sizeof what);
    snprintf(line, sizeof line, "saved %s to %s\n", what, path);
    fbrl_vmx_puts(vm, line);
    return FBRL_OK;
}

static fbrl_status w_load(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_workspace *ws = ctx;
    char path[FBRL_FILE_PATH_MAX], why[128], what[128], line[FBRL_FILE_PATH_MAX + 160];
    fbrl_workspace_counts n;
    fbrl_status st;
    (void)word;
    if ((st = parse_path(vm, "LOAD-WORKSPACE", path)) != FBRL_OK)
        return st;
    if ((st = fbrl_workspace_load(ws, path, &n, why, sizeof why)) != FBRL_OK)
        return fbrl_vmx_throwf(vm, FBRL_VM_THROW_OF_STATUS(st), "LOAD-WORKSPACE %.40s: %s; nothing loaded",
                               path, why);
    counts_text(&n, what, sizeof what);
    snprintf(line, sizeof line, "loaded %s from %s\n", what, path);
    fbrl_vmx_puts(vm, line);
    return FBRL_OK;
}

static fbrl_status w_workspace(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_workspace *ws = ctx;
    walk w;
    char what[128], line[FBRL_FILE_PATH_MAX + 200];
    int changed = 0;
    (void)word;
    walk_all(ws, TO_CONSOLE, &w, NULL, NULL);
    fbrl_workspace_changed(ws, &changed, NULL);
    counts_text(&w.n, what, sizeof what);
    if (ws->path[0])
        snprintf(line, sizeof line, "%s; %s %s\n", what, changed ? "changed since" : "as in", ws->path);
    else
        snprintf(line, sizeof line, "%s%s\n", what, changed ? "; not saved" : "");
    fbrl_vmx_puts(vm, line);
    return FBRL_OK;
}

static fbrl_status w_changed_q(fbrl_vm *vm, void *ctx, const void *word)
{
    int changed = 0;
    (void)word;
    fbrl_workspace_changed(ctx, &changed, NULL);
    return fbrl_vmx_push(vm, changed ? -1 : 0);
}

fbrl_status fbrl_workspace_install(fbrl_vm *vm, fbrl_workspace *ws, fbrl_glossary *g, fbrl_robot *r,
                                   void *buf, size_t cap)
{
    static const fbrl_vmx_reg words[] = {
        {"SAVE-WORKSPACE", w_save, "", 0, 0, 0,
         FBRL_DOC("( \"file\" -- )", "save every named location, matrix, calibration and device (and WITH-CAL, "
                                     "MAP-ON, BASE-OFFSET) to file")},
        {"LOAD-WORKSPACE", w_load, "", 0, 0, 0,
         FBRL_DOC("( \"file\" -- )",
                  "load a saved workspace: its objects made or overwritten by name; a bad file changes nothing")},
        {"WORKSPACE", w_workspace, "", 0, 0, 0,
         FBRL_DOC("( -- )", "list what SAVE-WORKSPACE would save, and whether it changed")},
        {"WORKSPACE-CHANGED?", w_changed_q, "", 0, 0, 0,
         FBRL_DOC("( -- flag )", "true if the workspace changed since the last save or load")},
    };
    if (!vm || !ws || !g || !buf || cap == 0)
        return FBRL_EINVAL;
    memset(ws, 0, sizeof *ws);
    ws->vm = vm;
    ws->g = g;
    ws->r = r;
    ws->buf = buf;
    ws->cap = cap;
    fbrl_status st = fbrl_vmx_define_table(vm, words, sizeof words / sizeof words[0], ws);
    if (st != FBRL_OK)
        return st;
    ws->magic = WS_INSTALLED;
    ws->mark = fingerprint(ws, NULL);
    return FBRL_OK;
}
