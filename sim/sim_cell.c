/* SPDX-License-Identifier: MIT */
/* sim_cell.c - the work cell fbrlsim knows (--cell FILE): the same description fbrlmon
 * INCLUDEs (docs/workcell.md), read here without a Forth engine: numbers, the CELL-* words
 * and comments; anything else is an error naming its line. A motion whose path meets the
 * cell runs up to the point of contact and stops there; its command then answers
 * SIM_E_COLLISION (docs/fbrlsim.md). Blocks stand where they were described. */
#include "sim_internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#define CELL_STACK 16

static int word_is(const char *w, const char *name) { return strcasecmp(w, name) == 0; }

/* A number as FBRL writes it: 12 -3.5 10E0 1.5e-1. */
static int number(const char *w, double *v)
{
    char buf[64], *end;
    size_t n = strlen(w);
    if (n == 0 || n >= sizeof buf)
        return 0;
    memcpy(buf, w, n + 1);
    if (toupper((unsigned char)buf[n - 1]) == 'E') /* "1E" is 1E0 in Forth */
        buf[n++] = '0', buf[n] = 0;
    errno = 0;
    *v = strtod(buf, &end);
    return *end == 0 && errno == 0 &&
           (isdigit((unsigned char)buf[0]) || buf[0] == '-' || buf[0] == '+' || buf[0] == '.');
}

static char *next_token(char **p)
{
    char *s = *p, *t;
    while (*s && isspace((unsigned char)*s))
        s++;
    if (!*s)
        return NULL;
    t = s;
    while (*s && !isspace((unsigned char)*s))
        s++;
    if (*s)
        *s++ = 0;
    *p = s;
    return t;
}

int sim_cell_load(fbrl_sim *s, const char *path, char *err, size_t errlen)
{
    FILE *f = fopen(path, "re");
    char line[512];
    unsigned long no = 0;
    double st[CELL_STACK];
    int n = 0, block = -1, paren = 0;
    if (!f) {
        sim_seterr(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    s->cell_obj = calloc(SIM_CELL_MAX, sizeof *s->cell_obj);
    if (!s->cell_obj || fbrl_cell_init(&s->cell, s->cell_obj, SIM_CELL_MAX) != FBRL_OK) {
        fclose(f);
        sim_seterr(err, errlen, "out of memory");
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        char *p = line, *w;
        no++;
        while ((w = next_token(&p)) != NULL) {
            double v;
            int need = -1;
            fbrl_cell_obj o;
            fbrl_status r = FBRL_OK;
            if (paren) {
                if (strchr(w, ')'))
                    paren = 0;
                continue;
            }
            if (!strcmp(w, "\\"))
                break;
            if (!strcmp(w, "(")) {
                paren = 1;
                continue;
            }
            if (number(w, &v)) {
                if (n == CELL_STACK)
                    goto bad_stack;
                st[n++] = v;
                continue;
            }
            memset(&o, 0, sizeof o);
            o.block = block;
            if (word_is(w, "CELL-TABLE"))
                need = 1;
            else if (word_is(w, "CELL-TOOL"))
                need = 2;
            else if (word_is(w, "CELL-BOX") || word_is(w, "CELL-KEEPOUT"))
                need = 6;
            else if (word_is(w, "CELL-CYLINDER"))
                need = 5;
            else if (word_is(w, "CELL-BLOCK") || word_is(w, "CELL-WORLD") || word_is(w, "CELL-GUARD-ON") ||
                     word_is(w, "CELL-GUARD-OFF") || word_is(w, "CELL-CLEAR"))
                need = 0;
            if (need < 0) {
                sim_seterr(err, errlen, "%s:%lu: %s is not a work-cell word", path, no, w);
                goto fail;
            }
            if (n != need) {
                sim_seterr(err, errlen, "%s:%lu: %s takes %d numbers, %d given", path, no, w, need, n);
                goto fail;
            }
            n = 0;
            if (word_is(w, "CELL-TABLE")) {
                r = fbrl_cell_set_table(&s->cell, st[0]);
            } else if (word_is(w, "CELL-TOOL")) {
                r = fbrl_cell_set_tool(&s->cell, st[0], st[1]);
            } else if (word_is(w, "CELL-WORLD")) {
                block = -1;
            } else if (word_is(w, "CELL-CLEAR")) {
                fbrl_cell_clear(&s->cell);
                block = -1;
            } else if (word_is(w, "CELL-BLOCK") || need > 2) {
                char *name = next_token(&p);
                if (!name) {
                    sim_seterr(err, errlen, "%s:%lu: %s: a name must follow", path, no, w);
                    goto fail;
                }
                if (word_is(w, "CELL-BLOCK")) {
                    r = fbrl_cell_block(&s->cell, name, strlen(name), &block);
                } else {
                    snprintf(o.name, sizeof o.name, "%s", name);
                    for (char *c = o.name; *c; c++)
                        *c = (char)toupper((unsigned char)*c);
                    if (need == 6) {
                        o.kind = word_is(w, "CELL-BOX") ? FBRL_CELL_BOX : FBRL_CELL_KEEPOUT;
                        for (int k = 0; k < 3; k++)
                            o.lo[k] = st[k], o.hi[k] = st[k + 3];
                    } else {
                        o.kind = FBRL_CELL_CYLINDER;
                        o.c[0] = st[0], o.c[1] = st[1], o.lo[2] = st[2], o.r = st[3];
                        o.hi[2] = st[4] > 0 ? st[2] + st[4] : st[2];
                    }
                    r = fbrl_cell_add(&s->cell, &o);
                }
            }
            if (r != FBRL_OK) {
                sim_seterr(err, errlen, "%s:%lu: %s: %s", path, no, w,
                           r == FBRL_ENAME    ? "a name used twice, empty or too long"
                           : r == FBRL_ERANGE ? "a size that is not positive"
                                              : fbrl_status_str(r));
                goto fail;
            }
        }
    }
    fclose(f);
    if (n) {
        sim_seterr(err, errlen, "%s: %d numbers left over at the end", path, n);
        return -1;
    }
    s->cell_on = 1;
    return 0;
bad_stack:
    sim_seterr(err, errlen, "%s:%lu: too many numbers", path, no);
fail:
    fclose(f);
    return -1;
}

/* The motion from the joints now to qt (joint-interpolated, or straight to pose pb of the
 * tool point tool inches past the flange): where it meets the cell, the fraction of the
 * way (1: it does not). */
double sim_cell_stop(fbrl_sim *s, double tool, const double *qt, const double *pb, double *qstop)
{
    fbrl_cell_hit h;
    fbrl_status st;
    if (!s->cell_on || fbrl_cell_set_arm(&s->cell, s->arm.model, tool) != FBRL_OK)
        return 1.0;
    st = pb ? fbrl_cell_check_line(&s->cell, s->arm.q, pb, &h)
            : fbrl_cell_check_joints(&s->cell, s->arm.q, qt, &h);
    /* a motion that starts in contact (after a collision) may back out of it */
    if (st != FBRL_OK || !h.hit || h.fraction <= 0.0)
        return 1.0;
    memcpy(qstop, h.q_end, s->arm.model->naxes * sizeof *qstop);
    return h.fraction;
}
