/* SPDX-License-Identifier: MIT */
/* robot_import.c - IMPORT-LOC: a location taught on the controller (its own teach
 * pendant's TEACH, HERE, POINT) becomes a host location of the same name, read with LISTL
 * and never by moving the arm there. */
#include <stdio.h>
#include <string.h>

#include "fbrl/rapl_reply.h"
#include "robot_internal.h"

/* The controller's location names are at most this long (DESIGN 5). */
#define CTRL_NAME_MAX 8
/* A precision point is converted to cartesian by the controller itself (SET), into this
 * scratch location, then listed. */
#define CONVERT_POINT "FBRLTI"

/* LISTL's line for one cartesian location: the name, then six numbers. */
typedef struct listing {
    const char *name;
    int got; /* 1 once the line was read, -1 if a line did not parse */
    double v[6];
} listing;

static void on_line(void *ctx, const char *line, size_t len, int flawed)
{
    listing *l = ctx;
    size_t k = 0, n = strlen(l->name), nv = 0;
    if (flawed || l->got)
        return;
    while (k < len && line[k] == ' ')
        k++;
    if (len - k < n || memcmp(line + k, l->name, n) != 0 || (k + n < len && line[k + n] != ' '))
        return;
    for (k += n; k < len && nv < 6;) {
        size_t e;
        while (k < len && line[k] == ' ')
            k++;
        for (e = k; e < len && line[e] != ' '; e++) {
        }
        if (e == k || fbrl_rapl_parse_real(line + k, e - k, &l->v[nv]) != FBRL_OK)
            break;
        nv++;
        k = e;
    }
    while (k < len && line[k] == ' ')
        k++;
    l->got = nv == 6 && k == len ? 1 : -1;
}

/* IMPORT-LOC ( "name" -- ) or ( c-addr u -- ): the controller's location name (#name for a
 * precision point) into the host location of that name (without the #), made if needed. */
static fbrl_status w_import_loc(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char name[CTRL_NAME_MAX + 2], line[64], msg[160];
    listing l;
    fbrl_loc arm, user;
    fbrl_cell xt;
    fbrl_status st;
    if ((st = rb_name_arg(r, w, &v[0], name, sizeof name)) != FBRL_OK)
        return st;
    for (char *p = name; *p; p++)
        if (*p >= 'a' && *p <= 'z')
            *p = (char)(*p - 'a' + 'A');
    int precision = name[0] == '#';
    const char *host = name + precision;
    size_t hlen = strlen(host);
    if (hlen == 0 || hlen > CTRL_NAME_MAX || strspn(host, "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != hlen) {
        snprintf(msg, sizeof msg, "%s: %s is not a controller location name (1..%d letters and digits)",
                 w->name, name, CTRL_NAME_MAX);
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ENAME), msg);
    }
    if (!r->g)
        return rb_fail(r, FBRL_THROW_UNSUPPORTED, "IMPORT-LOC: no glossary (host locations) in this VM");
    /* the host name first: a word of that name must be a location (nothing is asked of the arm otherwise) */
    fbrl_glossary_kind kind = FBRL_GLOSSARY_NONE;
    void *obj = NULL;
    int exists = fbrl_vmx_find(r->vm, host, hlen, &xt) == FBRL_OK;
    if (exists && (fbrl_glossary_object(r->g, xt, &kind, &obj) != FBRL_OK || kind != FBRL_GLOSSARY_LOC)) {
        snprintf(msg, sizeof msg, "%s: %s is defined here and is not a location (CREATE-LOC)", w->name, host);
        return rb_fail(r, FBRL_THROW_TYPE_MISMATCH, msg);
    }
    if (precision) {
        snprintf(line, sizeof line, "SET %s=%s", CONVERT_POINT, name);
        if ((st = rb_raw(r, w, line, 0)) != FBRL_OK)
            return st;
    }
    memset(&l, 0, sizeof l);
    l.name = precision ? CONVERT_POINT : host;
    snprintf(line, sizeof line, "LISTL %s", l.name);
    if ((st = rb_raw_lines(r, w, line, on_line, &l)) != FBRL_OK)
        return st;
    if (l.got != 1) {
        snprintf(msg, sizeof msg, "%s: LISTL %s gave no location line", w->name, l.name);
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_EPROTOCOL), msg);
    }
    arm.x = l.v[0], arm.y = l.v[1], arm.z = l.v[2], arm.o = l.v[3], arm.a = l.v[4], arm.t = l.v[5];
    /* the arm's coordinates into the user's frame, as every read-back (BASE-OFFSET, MAP-ON) */
    if ((st = rb_from_arm(r, w, &arm, &user, 1)) != FBRL_OK)
        return st;
    if (!exists && (st = fbrl_glossary_make(r->g, FBRL_GLOSSARY_LOC, host, hlen, &obj)) != FBRL_OK)
        return st;
    *(fbrl_loc *)obj = user;
    return FBRL_OK;
}

const rb_word rb_import_words[] = {
    {"IMPORT-LOC", w_import_loc, "S", 0, -1, 0,
     FBRL_DOC(
         "( \"name\" -- ) or ( c-addr u -- )",
         "the controller's location name (#name: precision point) into the host location name (made if new), "
         "read with LISTL: the arm does not move")},
};
const size_t rb_import_nwords = sizeof rb_import_words / sizeof rb_import_words[0];
