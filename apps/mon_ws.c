/* SPDX-License-Identifier: MIT */
/* mon_ws.c - fbrlmon's workspace at start and exit, and the taught places it keeps (see
 * mon_ws.h). */
#include "mon_ws.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "fbrl/vmx.h"

#define DIFF_LINES 20 /* changes the exit prompt names one by one */

static const char *g_path; /* --workspace FILE (NULL: none) */

/* The taught places: the locations the workspace file brought (saved by someone who taught
 * them) and those taught in this session; each with its value while a file loads. */
typedef struct taught {
    char name[FBRL_VMX_NAME_MAX + 1];
    int here_session; /* taught in this session (a save may write it over the file's) */
    int kept;         /* protect: has a value */
    fbrl_loc value;
} taught;
static taught *g_taught;
static size_t g_ntaught, g_cap;

static taught *find_taught(const char *name, size_t len)
{
    for (size_t i = 0; i < g_ntaught; i++)
        if (strlen(g_taught[i].name) == len && strncasecmp(g_taught[i].name, name, len) == 0)
            return &g_taught[i];
    return NULL;
}

static taught *add_taught(const char *name, size_t len)
{
    taught *t = find_taught(name, len);
    if (t != NULL || len > FBRL_VMX_NAME_MAX)
        return t;
    if (g_ntaught == g_cap) {
        size_t cap = g_cap ? g_cap * 2 : 64;
        taught *n = realloc(g_taught, cap * sizeof *n);
        if (n == NULL)
            return NULL;
        g_taught = n, g_cap = cap;
    }
    t = &g_taught[g_ntaught++];
    memset(t, 0, sizeof *t);
    memcpy(t->name, name, len);
    return t;
}

/* The location the name finds now, or NULL. */
static fbrl_loc *loc_named(mon *m, const char *name, size_t len)
{
    fbrl_cell xt, addr;
    fbrl_loc *l;
    if (fbrl_vmx_find(m->vm, name, len, &xt) != FBRL_OK || fbrl_glossary_loc_word(m->vm, xt, &addr) != FBRL_OK ||
        fbrl_glossary_loc(m->vm, addr, &l) != FBRL_OK)
        return NULL;
    return l;
}

typedef struct scan {
    mon *m;
} scan;

static int add_loaded(void *ctx, const char *name, size_t len)
{
    scan *s = ctx;
    if (loc_named(s->m, name, len) != NULL)
        add_taught(name, len);
    return 0;
}

void mon_ws_taught(mon *m, const char *name)
{
    taught *t;
    (void)m;
    if (name && (t = add_taught(name, strlen(name))) != NULL)
        t->here_session = 1;
}

void mon_ws_protect(mon *m)
{
    for (size_t i = 0; i < g_ntaught; i++) {
        fbrl_loc *l = loc_named(m, g_taught[i].name, strlen(g_taught[i].name));
        g_taught[i].kept = l != NULL;
        if (l != NULL)
            g_taught[i].value = *l;
    }
}

size_t mon_ws_restore(mon *m, void (*tell)(void *ctx, const char *name, const fbrl_loc *taught_value,
                                            const fbrl_loc *file_value),
                      void *ctx)
{
    size_t n = 0;
    for (size_t i = 0; i < g_ntaught; i++) {
        taught *t = &g_taught[i];
        fbrl_loc *l = t->kept ? loc_named(m, t->name, strlen(t->name)) : NULL;
        if (l == NULL || memcmp(l, &t->value, sizeof *l) == 0)
            continue;
        fbrl_loc file = *l;
        *l = t->value; /* the taught place wins (the newest word of the name: the file's code uses it) */
        n++;
        if (tell)
            tell(ctx, t->name, &t->value, &file);
    }
    return n;
}

static void counts_text(const fbrl_workspace_counts *n, char *buf, size_t cap)
{
    snprintf(buf, cap, "%u location%s, %u matri%s, %u calibration%s, %u device%s", n->locs,
             n->locs == 1 ? "" : "s", n->matrices, n->matrices == 1 ? "x" : "ces", n->cals,
             n->cals == 1 ? "" : "s", n->devices, n->devices == 1 ? "" : "s");
}

int mon_ws_start(mon *m, const char *path)
{
    struct stat sb;
    char why[160], what[128];
    fbrl_workspace_counts n;
    scan s;
    g_path = path;
    if (stat(path, &sb) != 0 && errno == ENOENT) {
        if (m->host.in_is_tty)
            printf("fbrlmon: %s does not exist yet: a new workspace (saved at exit or with SAVE-WORKSPACE)\n",
                   path);
        return 0;
    }
    if (fbrl_workspace_load(&m->ws, path, &n, why, sizeof why) != FBRL_OK) {
        fprintf(stderr, "fbrlmon: --workspace %s: %s; nothing loaded\n", path, why);
        return -1;
    }
    s.m = m; /* what it brought was taught (that is what a workspace keeps) */
    fbrl_vm_words(m->vm, add_loaded, &s);
    counts_text(&n, what, sizeof what);
    if (m->host.in_is_tty)
        printf("loaded %s from %s\n", what, path);
    return 0;
}

/* A line typed at the terminal (the line editor has ended: the terminal is in line mode). */
static const char *ask(mon *m, const char *question, size_t *len)
{
    fputs(question, stdout);
    fflush(stdout);
    return mon_host_read_line(&m->host, len);
}

/* The exit prompt's list: what a save would change in the file. */
typedef struct changes {
    unsigned lines, overwrites; /* overwrites: a value of the file replaced or dropped, not taught here */
} changes;

static void put_loc(const double *v)
{
    printf("X %.3f Y %.3f Z %.3f pitch %.1f roll %.1f", v[0], v[1], v[2], v[4], v[5]);
}

static void show_change(void *ctx, const fbrl_workspace_delta *d)
{
    changes *c = ctx;
    static const char *const verbs[] = {"", "add", "change", "drop"};
    taught *t = d->name[0] ? find_taught(d->name, strlen(d->name)) : NULL;
    if (d->change != FBRL_WORKSPACE_ADDED && !(t && t->here_session))
        c->overwrites++;
    if (++c->lines > DIFF_LINES)
        return;
    printf("  %-6s %s%s%s", verbs[d->change], d->name[0] ? d->name : "", d->name[0] ? " " : "", d->kind);
    if (d->tag == FBRL_WORKSPACE_TAG_LOC && d->now) {
        printf(": ");
        put_loc(d->now);
    }
    if (d->tag == FBRL_WORKSPACE_TAG_LOC && d->was) {
        printf("%s", d->now ? ", was " : ": ");
        put_loc(d->was);
    }
    if (d->change != FBRL_WORKSPACE_ADDED)
        printf(t && t->here_session ? " (taught now)" : " (as taught)");
    printf("\n");
}

void mon_ws_finish(mon *m)
{
    int changed = 0, keep;
    fbrl_workspace_counts n;
    changes c;
    char what[128], q[FBRL_FILE_PATH_MAX + 256], path[FBRL_FILE_PATH_MAX];
    const char *target = g_path ? g_path : fbrl_workspace_path(&m->ws), *line;
    size_t len;
    if (fbrl_workspace_changed(&m->ws, &changed, &n) != FBRL_OK || !changed)
        return;
    if (!target[0] && n.locs + n.matrices + n.cals + n.devices == 0)
        return; /* nothing named to keep (e.g. a setting changed in a session without a workspace) */
    counts_text(&n, what, sizeof what);
    if (!m->host.in_is_tty) {
        if (g_path)
            fprintf(stderr, "fbrlmon: the workspace changed and was not saved to %s (SAVE-WORKSPACE %s)\n",
                    g_path, g_path);
        return;
    }
    mon_host_newline(&m->host);
    if (!target[0]) {
        /* no workspace file in this session: say what would be lost, without holding up
         * the exit with a question nobody asked for */
        fprintf(stderr, "note: %s not saved (SAVE-WORKSPACE FILE keeps them; docs/workspace.md)\n", what);
        return;
    }
    /* what a save would change there, named; a value the file holds (taught, saved) that a
     * save would replace or drop makes the answer default to keeping the file */
    memset(&c, 0, sizeof c);
    printf("The workspace changed (%s). Saving it to %s would:\n", what, target);
    fbrl_status st = fbrl_workspace_diff(&m->ws, target, show_change, &c, NULL);
    if (st == FBRL_ENOENT)
        printf("  make it (it does not exist yet)\n");
    else if (st != FBRL_OK)
        printf("  replace it (its contents cannot be compared: %s)\n", fbrl_status_str(st));
    else if (c.lines == 0)
        printf("  change nothing in it (only the session's order of words differs)\n");
    if (c.lines > DIFF_LINES)
        printf("  ... and %u more\n", c.lines - DIFF_LINES);
    keep = c.overwrites > 0 || (st != FBRL_OK && st != FBRL_ENOENT);
    snprintf(q, sizeof q, "Save it to %s? %s ", target,
             keep ? "[y/N] (N keeps what was taught)" : "[Y/n]");
    line = ask(m, q, &len);
    while (line != NULL && len > 0 && (line[0] == ' ' || line[0] == '\t'))
        line++, len--;
    if (line == NULL || (len == 0 && keep) || (len > 0 && line[0] != 'y' && line[0] != 'Y')) {
        printf("not saved: %s is as it was\n", target);
        return;
    }
    snprintf(path, sizeof path, "%s", target);
    st = fbrl_workspace_save(&m->ws, path, &n);
    if (st != FBRL_OK) {
        fprintf(stderr, "error: saving the workspace to %s: %s; %s\n", path,
                st == FBRL_EFORMAT ? "that file is other data, not a workspace" : fbrl_status_str(st),
                "not saved");
        m->errors++;
        return;
    }
    counts_text(&n, what, sizeof what);
    printf("saved %s to %s\n", what, path);
}
