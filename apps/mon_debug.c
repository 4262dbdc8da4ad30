/* SPDX-License-Identifier: MIT */
/* mon_debug.c - fbrlmon's words for finding and fixing a plan (docs/debugging.md):
 * LOCATE shows where a word was defined, EDIT opens that place in the user's editor and
 * loads the file again keeping the session's work, SAVE-DEFINITIONS writes the words
 * typed at the prompt to a file. The prompt's definitions are recorded here as typed. */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fbrl/status.h"
#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"
#include "mon.h"
#include "mon_debug.h"

#define LOCATE_MAX_LINES 24       /* a definition longer than this is shown cut */
#define EDIT_DEFAULT     "editor" /* Debian's choice of editor; vi when it is missing */
#define EDIT_FALLBACK    "vi"

/* ---- the prompt's definitions ---- */

/* Lines that load other sources define words too, but they are not the prompt's own
 * definitions (and saved, EDIT would run the editor again). */
static int loads_source(const char *text, size_t len)
{
    static const char *const loaders[] = {"INCLUDE", "INCLUDED",       "REQUIRE", "REQUIRED",
                                          "EDIT",    "LOAD-WORKSPACE", "RESUME",  NULL};
    size_t i = 0, n;
    while (i < len && isspace((unsigned char)text[i]))
        i++;
    for (n = 0; i + n < len && !isspace((unsigned char)text[i + n]); n++)
        ;
    for (const char *const *w = loaders; *w; w++)
        if (strlen(*w) == n && strncasecmp(text + i, *w, n) == 0)
            return 1;
    return 0;
}

static int keep_line(mon *m, const char *text, size_t len);

void mon_debug_typed(mon *m, const char *text, size_t len, int ok, int open_before, int open_after,
                     int defined)
{
    if (!ok) { /* an error abandons the open definition: its lines go (the line's too) */
        if (open_before) {
            m->typed_len -= m->typed_open;
            m->typed_open = 0;
        }
        return;
    }
    if (!(open_before || open_after || defined) || loads_source(text, len))
        return;
    if (keep_line(m, text, len) == 0)
        m->typed_open = open_after ? m->typed_open + len + 1 : 0;
}

/* Append a line (and its end) to the kept text; -1 when there is no memory for it. */
static int keep_line(mon *m, const char *text, size_t len)
{
    if (len + 1 > m->typed_cap - m->typed_len) {
        size_t cap = (m->typed_cap ? m->typed_cap * 2 : 4096) + len + 1;
        char *p = realloc(m->typed_src, cap);
        if (!p) /* keep what is there; SAVE-DEFINITIONS says what it has */
            return -1;
        m->typed_src = p;
        m->typed_cap = cap;
    }
    memcpy(m->typed_src + m->typed_len, text, len);
    m->typed_len += len;
    m->typed_src[m->typed_len++] = '\n';
    return 0;
}

/* The kept text's definitions that ended (an open one's lines follow them). */
static size_t ended(const mon *m) { return m->typed_len - m->typed_open; }

/* Does the line at p define name (": NAME", case-insensitive)? */
static int defines(const char *p, const char *e, const char *name)
{
    size_t n = strlen(name);
    for (; p < e; p++) {
        if (*p != ':' || (p + 1 < e && !isspace((unsigned char)p[1])))
            continue;
        const char *q = p + 1;
        while (q < e && isspace((unsigned char)*q))
            q++;
        if ((size_t)(e - q) >= n && strncasecmp(q, name, n) == 0 &&
            (q + n == e || isspace((unsigned char)q[n])))
            return 1;
    }
    return 0;
}

/* The typed lines from the last one defining name up to its ';' (NULL: none). */
static const char *typed_definition(const mon *m, const char *name, size_t *len)
{
    const char *found = NULL, *p = m->typed_src, *end = m->typed_src + ended(m);
    while (p && p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *e = nl ? nl : end;
        if (defines(p, e, name))
            found = p;
        p = nl ? nl + 1 : NULL;
    }
    if (!found)
        return NULL;
    const char *stop = found;
    for (int lines = 0; stop < end && lines < LOCATE_MAX_LINES; lines++) {
        const char *nl = memchr(stop, '\n', (size_t)(end - stop));
        const char *e = nl ? nl : end;
        int closed = memchr(stop, ';', (size_t)(e - stop)) != NULL;
        stop = nl ? nl + 1 : end;
        if (closed)
            break;
    }
    *len = (size_t)(stop - found);
    return found;
}

/* ---- LOCATE ---- */

static fbrl_status word_name(fbrl_vm *vm, const char *who, char *buf, size_t cap)
{
    const char *p;
    size_t n;
    fbrl_vm_parse_name(vm, &p, &n);
    if (n == 0 || n >= cap) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: name a word, e.g. %s PICK-TUBE", who, who);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    memcpy(buf, p, n);
    buf[n] = 0;
    return FBRL_OK;
}

int mon_debug_show_lines(FILE *out, const char *path, unsigned long first, int max)
{
    FILE *f = fopen(path, "r");
    char line[1024];
    unsigned long n = 0;
    int shown = 0;
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f)) {
        if (++n < first)
            continue;
        fprintf(out, "%5lu  %s", n, line);
        if (!strchr(line, '\n'))
            fputc('\n', out);
        if (++shown >= max || strchr(line, ';'))
            break;
    }
    fclose(f);
    return shown > 0 ? 0 : -1;
}

static fbrl_status w_locate(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    char name[64], msg[160];
    const char *file, *stack = "", *help = "";
    unsigned long line;
    fbrl_status st = word_name(vm, "LOCATE", name, sizeof name);
    if (st != FBRL_OK)
        return st;
    if (fbrl_vm_locate(vm, name, &file, &line) != FBRL_OK) {
        snprintf(msg, sizeof msg, "LOCATE: %s is not a word", name);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    FILE *out = m->host.out;
    mon_host_newline(&m->host);
    if (file[0]) {
        fprintf(out, "%s is defined in %s:%lu\n", name, file, line);
        if (mon_debug_show_lines(out, file, line, LOCATE_MAX_LINES) != 0)
            fprintf(out, "  (%s cannot be read now)\n", file);
    } else {
        size_t n;
        const char *text = line > 0 ? typed_definition(m, name, &n) : NULL;
        if (text) {
            fprintf(out, "%s was typed at the prompt (SAVE-DEFINITIONS writes it to a file):\n", name);
            fwrite(text, 1, n, out);
        } else {
            fbrl_vm_help(vm, name, &stack, &help);
            fprintf(out, "%s is built in (no source file): %s %s\n", name, stack, help);
        }
    }
    fflush(out);
    m->host.column = 0;
    return FBRL_OK;
}

/* ---- EDIT ---- */

static const char *editor(void)
{
    const char *e = getenv("VISUAL");
    if (!e || !*e)
        e = getenv("EDITOR");
    if (e && *e)
        return e;
    return access("/usr/bin/" EDIT_DEFAULT, X_OK) == 0 ? EDIT_DEFAULT : EDIT_FALLBACK;
}

/* Run the editor at file:line and wait for it; 0 when it exited with status 0. The
 * editor may be a command with options (EDITOR="emacs -nw"): the shell splits it. */
static int run_editor(const char *ed, const char *file, unsigned long line, char *why, size_t cap)
{
    char at[32];
    snprintf(at, sizeof at, "+%lu", line);
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(why, cap, "cannot start %s: %s", ed, strerror(errno));
        return -1;
    }
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", "exec $0 \"$1\" \"$2\"", ed, at, file, (char *)NULL);
        _exit(127);
    }
    int st;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) {
            snprintf(why, cap, "lost the editor %s: %s", ed, strerror(errno));
            return -1;
        }
    if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        snprintf(why, cap, "the editor %s failed (%s %d); the file was not loaded again", ed,
                 WIFEXITED(st) ? "exit status" : "signal", WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
        return -1;
    }
    return 0;
}

/* (EDIT) ( a -- a u ): EDIT's first half. Opens the editor at the word's file and line;
 * when it exits, keeps the session's work (locations, matrices, calibrations, devices) in
 * a workspace file and leaves the file's name at a for INCLUDED. */
static fbrl_status w_edit(fbrl_vm *vm, void *arg, const void *word)
{
    mon *m = arg;
    char name[64], msg[MON_EDIT_MSG];
    const char *file;
    unsigned long line;
    fbrl_vmx_val v[1];
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st != FBRL_OK)
        return st;
    fbrl_cell a = v[0].i;
    st = word_name(vm, "EDIT", name, sizeof name);
    if (st != FBRL_OK)
        return st;
    if (fbrl_vm_locate(vm, name, &file, &line) != FBRL_OK) {
        snprintf(msg, sizeof msg, "EDIT: %s is not a word", name);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    if (!file[0]) {
        snprintf(msg, sizeof msg,
                 "EDIT: %s has no source file (%s); SAVE-DEFINITIONS FILE writes typed words to one", name,
                 line ? "it was typed at the prompt" : "it is built in");
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    size_t n = strlen(file);
    char *p = fbrl_vm_addr(vm, a, MON_EDIT_PATH_MAX);
    if (!p || n >= MON_EDIT_PATH_MAX)
        return fbrl_vm_throw(vm, FBRL_THROW_BAD_ADDRESS, NULL);
    char path[MON_EDIT_PATH_MAX];
    memcpy(path, file, n + 1); /* the name lives in the dictionary, which the reload grows */
    mon_host_newline(&m->host);
    if (run_editor(editor(), path, line, msg, sizeof msg) != 0)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    snprintf(m->edit_ws, sizeof m->edit_ws, "%s/fbrlmon-edit-%ld.ws",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (long)getpid());
    st = fbrl_workspace_save(&m->ws, m->edit_ws, NULL);
    if (st != FBRL_OK) {
        snprintf(msg, sizeof msg, "EDIT: could not keep the session's work before loading %s: %s", path,
                 fbrl_status_str(st));
        m->edit_ws[0] = 0;
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    memcpy(p, path, n);
    fprintf(m->host.out, "loading %s again\n", path);
    fflush(m->host.out);
    m->host.column = 0;
    if (fbrl_vm_push(vm, a) != FBRL_OK || fbrl_vm_push(vm, (fbrl_cell)n) != FBRL_OK)
        return fbrl_vm_throw(vm, FBRL_THROW_STACK_OVERFLOW, NULL);
    return FBRL_OK;
}

/* (EDIT-DONE) ( -- ): EDIT's second half, after the file loaded (or failed to): the
 * work kept by (EDIT) goes back into the words of the same names. */
static fbrl_status w_edit_done(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    char why[160], msg[MON_EDIT_MSG];
    if (!m->edit_ws[0])
        return FBRL_OK;
    fbrl_status st = fbrl_workspace_load(&m->ws, m->edit_ws, NULL, why, sizeof why);
    if (st == FBRL_OK)
        remove(m->edit_ws);
    else
        snprintf(msg, sizeof msg, "EDIT: the session's work could not be put back (%s); it is kept in %s",
                 why, m->edit_ws);
    m->edit_ws[0] = 0;
    return st == FBRL_OK ? FBRL_OK : fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
}

/* ---- SAVE-DEFINITIONS ---- */

static fbrl_status w_save_definitions(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    char path[MON_EDIT_PATH_MAX], msg[MON_EDIT_MSG];
    const char *p;
    size_t n;
    struct stat sb;
    fbrl_vm_parse_name(vm, &p, &n);
    if (n == 0 || n >= sizeof path)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ,
                             "SAVE-DEFINITIONS: name the file, e.g. SAVE-DEFINITIONS mine.fbrl");
    memcpy(path, p, n);
    path[n] = 0;
    if (stat(path, &sb) == 0 && sb.st_size > 0) {
        snprintf(msg, sizeof msg, "SAVE-DEFINITIONS: %s exists; nothing written (choose a new name)", path);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    if (ended(m) == 0)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, "SAVE-DEFINITIONS: nothing was defined at the prompt");
    FILE *f = fopen(path, "w");
    int bad = !f || fprintf(f, "\\ %s - definitions typed at the fbrlmon prompt\n", path) < 0 ||
              fwrite(m->typed_src, 1, ended(m), f) != ended(m);
    if (f && fclose(f) != 0)
        bad = 1;
    if (bad) {
        snprintf(msg, sizeof msg, "SAVE-DEFINITIONS: cannot write %s: %s", path, strerror(errno));
        remove(path);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    mon_host_newline(&m->host);
    fprintf(m->host.out, "wrote the prompt's definitions to %s\n", path);
    fflush(m->host.out);
    m->host.column = 0;
    return FBRL_OK;
}

fbrl_status mon_debug_install(mon *m)
{
    static const char def[] =
        "CREATE (EDIT-FILE) " MON_EDIT_PATH_MAX_TEXT " ALLOT\n"
        ": EDIT ( \"name\" -- ) \\ edit the file that defines name at its line, then load it "
        "again keeping the session's locations and other work\n"
        "  (EDIT-FILE) (EDIT) ['] INCLUDED CATCH DUP IF NIP NIP THEN (EDIT-DONE) THROW ;\n";
    static const fbrl_vmx_reg words[] = {
        {"LOCATE", w_locate, "", 0, 0, 0,
         FBRL_DOC("( \"name\" -- )", "show where name was defined and its source lines")},
        {"(EDIT)", w_edit, "A", 0, 0, 0,
         FBRL_DOC("( a \"name\" -- a u )",
                  "EDIT's first half: run the editor, keep the session's work, the file's name at a")},
        {"(EDIT-DONE)", w_edit_done, "", 0, 0, 0,
         FBRL_DOC("( -- )", "EDIT's second half: put the session's work back after the file loaded")},
        {"SAVE-DEFINITIONS", w_save_definitions, "", 0, 0, 0,
         FBRL_DOC("( \"file\" -- )", "write the definitions typed at the prompt to a new file")},
    };
    fbrl_status st = fbrl_vmx_define_table(m->vm, words, sizeof words / sizeof words[0], m);
    if (st == FBRL_OK)
        st = fbrl_vm_eval(m->vm, def, sizeof def - 1);
    return st;
}
