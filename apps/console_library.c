/* SPDX-License-Identifier: MIT */
/* console_library.c - the operator console's method library (SCREEN_LIBRARY): a folder of
 * method files, each listed by the METHOD line read from its text; the file is loaded
 * only when it is chosen, and then its form is shown. */
#include "console_library.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <curses.h>

#include "fbrl/vmx.h"
#include "console_form.h"
#include "console_text.h"
#include "mon_ws.h"

#define LIB_HEAD_BYTES 65536 /* the head of a method file looked at for its METHOD line */

/* The first "METHOD name text" line of a file, read as text (the file is loaded only when
 * it is chosen): 1 found, 0 none, -1 not a regular file (a device such as /dev/zero, a
 * FIFO: opened without waiting for a writer, and never read). Only the head is read. */
static int scan_method_file(const char *path, lib_entry *e)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat sb;
    FILE *f;
    char line[512];
    long head = 0;
    int found = 0;
    if (fd < 0)
        return 0;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        close(fd);
        return -1;
    }
    f = fdopen(fd, "r");
    if (f == NULL) {
        close(fd);
        return 0;
    }
    while (!found && head < LIB_HEAD_BYTES && fgets(line, sizeof line, f) != NULL) {
        head += (long)strlen(line);
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncasecmp(p, "METHOD", 6) != 0 || (p[6] != ' ' && p[6] != '\t'))
            continue;
        p += 6;
        while (*p == ' ' || *p == '\t')
            p++;
        size_t n = strcspn(p, " \t\r\n");
        if (n == 0 || n > FBRL_METHOD_NAME_MAX)
            continue;
        memcpy(e->name, p, n);
        e->name[n] = '\0';
        p += n;
        while (*p == ' ' || *p == '\t')
            p++;
        p[strcspn(p, "\r\n")] = '\0';
        con_textf(e->text, sizeof e->text, "%s", p);
        con_textf(e->path, sizeof e->path, "%s", path);
        found = 1;
    }
    fclose(f);
    return found;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(((const lib_entry *)a)->name, ((const lib_entry *)b)->name);
}

void con_library_scan(console *c)
{
    const char *dir = c->methods;
    DIR *d = opendir(dir);
    struct dirent *de;
    char odd[64] = "";
    size_t nodd = 0;
    c->nlib = 0;
    if (d == NULL) {
        con_hint(c, "method library %s: %s", dir, strerror(errno));
        return;
    }
    while ((de = readdir(d)) != NULL && c->nlib < LIB_MAX) {
        size_t n = strlen(de->d_name);
        char path[MON_RUNLOG_PATH_MAX];
        if (n < 6 || strcmp(de->d_name + n - 5, ".fbrl") != 0)
            continue;
        con_textf(path, sizeof path, "%s/%s", dir, de->d_name);
        int got = scan_method_file(path, &c->lib[c->nlib]);
        if (got > 0)
            c->nlib++;
        else if (got < 0 && nodd++ == 0)
            con_textf(odd, sizeof odd, "%s", de->d_name);
    }
    closedir(d);
    qsort(c->lib, c->nlib, sizeof c->lib[0], by_name);
    if (nodd > 0) /* said, so a method that is missing from the list is explained */
        con_hint(c, "left out %s%s: not a regular file", odd, nodd > 1 ? " and others" : "");
    else if (c->nlib == 0)
        con_hint(c, "no method files (*.fbrl with a METHOD line) in %s", dir);
}

/* Device names: the words the cell file made with OUTPUT-DEVICE. */
static int find_device(void *ctx, const char *name, size_t len)
{
    console *c = ctx;
    fbrl_cell xt;
    fbrl_robot_device d;
    if (len <= FBRL_METHOD_NAME_MAX && fbrl_vmx_find(c->m->vm, name, len, &xt) == FBRL_OK &&
        fbrl_robot_device_of(&c->m->robot, xt, &d) == FBRL_OK && d.output && !c->devname[d.port][0]) {
        memcpy(c->devname[d.port], name, len);
        c->devname[d.port][len] = '\0';
    }
    return 0;
}

/* A taught place the method file defined again keeps its taught value: said under Messages. */
static void kept_taught(void *ctx, const char *name, const fbrl_loc *taught, const fbrl_loc *file)
{
    console *c = ctx;
    char line[MIN_COLS + 1];
    con_textf(line, sizeof line, "kept taught %s X%.2f Y%.2f Z%.2f (file: X%.2f Y%.2f Z%.2f)", name,
              taught->x, taught->y, taught->z, file->x, file->y, file->z);
    con_push_msg(c, line);
}

static void choose_method(console *c, const lib_entry *e)
{
    const fbrl_method *meth = fbrl_method_find(&c->m->methods, e->name);
    size_t kept = 0;
    if (meth == NULL || !meth->complete) {
        con_hint(c, "loading %s ...", e->path);
        fflush(c->out);
        mon_ws_protect(c->m); /* the method file's DEFINE-LOC does not overwrite a taught place */
        c->in_vm++;
        fbrl_status st = fbrl_vm_include(c->m->vm, e->path);
        c->in_vm--;
        kept = mon_ws_restore(c->m, kept_taught, c);
        if (st != FBRL_OK) {
            char msg[400];
            con_engine_error(c, msg, sizeof msg);
            fbrl_vm_reset(c->m->vm);
            con_push_error(c, NULL, msg);
            con_hint(c, "%s did not load: see the errors", e->path);
            return;
        }
        meth = fbrl_method_find(&c->m->methods, e->name);
    }
    if (meth == NULL || !meth->complete) {
        con_hint(c, "%s: no complete METHOD %s in it", e->path, e->name);
        return;
    }
    c->meth = meth;
    c->entry = e;
    memset(c->devname, 0, sizeof c->devname);
    fbrl_vm_words(c->m->vm, find_device, c);
    con_form_fill(c);
    c->screen = SCREEN_FORM;
    c->state = ST_IDLE;
    if (kept > 0)
        con_hint(c, "%zu taught place%s kept over the method file's (see Messages); F5 starts", kept,
                 kept == 1 ? "" : "s");
    else
        con_hint(c, "fill in the parameters, then F5 to start");
}

void con_library_open(console *c)
{
    c->screen = SCREEN_LIBRARY;
    con_library_scan(c);
    c->hint[0] = '\0';
}

void con_library_draw(console *c)
{
    con_put_row(1, " Method library: %s", c->methods);
    for (size_t i = 0; i < BODY_ROWS; i++) {
        int row = BODY_TOP + (int)i;
        if (i < c->nlib) {
            if (i == c->sel)
                attron(A_REVERSE);
            con_put_row(row, " %-16s %s", c->lib[i].name, c->lib[i].text);
            if (i == c->sel)
                attroff(A_REVERSE);
        } else {
            con_put_row(row, " ");
        }
    }
}

void con_library_key(console *c, int ch)
{
    if (ch == KEY_UP && c->sel > 0)
        c->sel--;
    else if (ch == KEY_DOWN && c->sel + 1 < c->nlib)
        c->sel++;
    else if ((ch == '\n' || ch == '\r' || ch == KEY_ENTER) && c->sel < c->nlib)
        choose_method(c, &c->lib[c->sel]);
}
