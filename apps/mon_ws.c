/* SPDX-License-Identifier: MIT */
/* mon_ws.c - fbrlmon's workspace at start and exit (see mon_ws.h). */
#include "mon_ws.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static const char *g_path; /* --workspace FILE (NULL: none) */

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

void mon_ws_finish(mon *m)
{
    int changed = 0;
    fbrl_workspace_counts n;
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
    snprintf(q, sizeof q, "The workspace changed (%s). Save it to %s? [Y/n] ", what, target);
    line = ask(m, q, &len);
    if (line == NULL || (len > 0 && line[0] != 'y' && line[0] != 'Y')) {
        printf("not saved\n");
        return;
    }
    snprintf(path, sizeof path, "%s", target);
    fbrl_status st = fbrl_workspace_save(&m->ws, path, &n);
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
