/* SPDX-License-Identifier: MIT */
/* mon.c - the monitor's session: VM setup and one-line error reports. */
#include "mon.h"
#include "mon_debug.h"
#include "mon_recover.h"
#include "mon_teach.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A failed write leaves the stream's error flag set: mon_save_svg checks it at the end. */
static void write_file(void *ctx, const char *s, size_t n) { (void)fwrite(s, 1, n, (FILE *)ctx); }

/* CELL-SVG's file (and the dry run's picture): written whole through a temporary and
 * renamed, so a reader never sees half a picture. */
fbrl_status mon_save_svg(void *ctx, const char *path, fbrl_cell_words *cw)
{
    char tmp[1100];
    FILE *f;
    int bad;
    (void)ctx;
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return FBRL_ENAME;
    if ((f = fopen(tmp, "w")) == NULL)
        return FBRL_EIO;
    fbrl_cell_svg(cw, write_file, f);
    bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        remove(tmp);
        return FBRL_EIO;
    }
    return rename(tmp, path) == 0 ? FBRL_OK : (remove(tmp), FBRL_EIO);
}

int mon_open(mon *m, size_t dict_bytes, fbrl_link *link)
{
    fbrl_vm_config cfg;
    size_t size;
    fbrl_status st;

    memset(&cfg, 0, sizeof cfg);
    mon_host_init(&m->host, stdout, STDIN_FILENO, &cfg.host);
    size = fbrl_vm_size_for(&cfg, dict_bytes);
    /* calloc's alignment (max_align_t) is at least 16 bytes on the hosts we build for;
     * aligned_alloc would need C11. */
    m->vm_mem = calloc(1, size);
    if (m->vm_mem == NULL) {
        fprintf(stderr, "fbrlmon: cannot allocate %zu bytes for the VM\n", size);
        return -1;
    }
    cfg.mem = m->vm_mem;
    cfg.mem_size = size;
    /* calloc hands a large block over as fresh zero pages the OS backs only when
     * touched: the default 8 MB dictionary costs what the program really uses. */
    cfg.mem_zeroed = 1;
    st = fbrl_vm_create(&m->vm, &cfg);
    if (st == FBRL_OK)
        st = fbrl_glossary_install(m->vm, &m->glossary);
    if (st == FBRL_OK) {
        /* calloc: pages are only touched when a file really uses them. */
        m->file_mem = calloc(1, MON_FILE_STORAGE);
        st = m->file_mem == NULL
                 ? FBRL_ENOSPC
                 : fbrl_glossary_set_file_storage(&m->glossary, m->file_mem, MON_FILE_STORAGE);
    }
    if (st == FBRL_OK)
        st = fbrl_robot_install(m->vm, &m->robot, link, &m->glossary);
    if (st == FBRL_OK)
        st = fbrl_method_install(m->vm, &m->methods);
    if (st == FBRL_OK) {
        m->ws_mem = calloc(1, MON_WORKSPACE_STORAGE);
        st = m->ws_mem == NULL ? FBRL_ENOSPC
                               : fbrl_workspace_install(m->vm, &m->ws, &m->glossary, &m->robot, m->ws_mem,
                                                        MON_WORKSPACE_STORAGE);
    }
    if (st == FBRL_OK) {
        m->cell = calloc(1, sizeof *m->cell);
        st = m->cell == NULL ? FBRL_ENOSPC : fbrl_cell_install(m->vm, m->cell, &m->robot, &m->glossary);
        if (st == FBRL_OK)
            fbrl_cell_set_save(m->cell, mon_save_svg, NULL);
    }
    if (st == FBRL_OK) {
        m->link = link;
        st = mon_teach_install(m);
    }
    if (st == FBRL_OK)
        st = mon_debug_install(m);
    if (st == FBRL_OK)
        st = mon_step_install(m);
    if (st == FBRL_OK)
        st = mon_trace_install(m);
    if (st == FBRL_OK)
        st = mon_recover_install(m);
    if (st == FBRL_OK) /* after the corrective actions: the run asks and notes through them */
        st = fbrl_run_install(&m->run, m->vm, &m->methods, &m->recover, &m->robot);
    if (st == FBRL_OK && m->host.out_is_tty) /* long waits show their progress at a terminal */
        fbrl_robot_set_console(&m->robot, mon_host_progress, &m->host, 0);
    if (st != FBRL_OK) {
        fprintf(stderr, "fbrlmon: cannot create the VM: %s\n", fbrl_status_str(st));
        free(m->file_mem);
        free(m->ws_mem);
        free(m->cell);
        free(m->vm_mem);
        m->file_mem = NULL;
        m->ws_mem = NULL;
        m->vm_mem = NULL;
        m->vm = NULL;
        return -1;
    }
    return 0;
}

void mon_close(mon *m)
{
    fbrl_status st = fbrl_glossary_finish(&m->glossary);
    fflush(m->host.out);
    if (st != FBRL_OK) {
        fprintf(stderr, "error: closing the data files: %s\n", fbrl_status_str(st));
        m->errors++;
    }
    free(m->file_mem);
    m->file_mem = NULL;
    free(m->ws_mem);
    free(m->cell);
    m->ws_mem = NULL;
    mon_host_free(&m->host);
    free(m->vm_mem);
    m->vm_mem = NULL;
    m->vm = NULL;
    mon_trace_close(m);
    free(m->typed_src);
    m->typed_src = NULL;
    m->typed_len = m->typed_cap = m->typed_open = 0;
}

/* Write s to stderr with control characters shown as '?', so a report is
 * always exactly one line whatever bytes the input held. */
#define MON_BT_FRAMES FBRL_VM_BACKTRACE_MAX
#define MON_BT_OUTER  FBRL_VM_BACKTRACE_OUTER
#define MON_BT_STACK  FBRL_VM_BACKTRACE_STACK

static void put_clean(const char *s)
{
    for (; *s; s++)
        fputc((unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s, stderr);
}

/* " (FILE:LINE)" of a backtrace frame; words typed at the prompt say so. */
static void put_frame_place(const fbrl_vm_frame *f)
{
    if (!f->file[0]) {
        fputs(" (defined at the prompt)", stderr);
        return;
    }
    fputs(" (", stderr);
    put_clean(f->file);
    if (f->line > 0)
        fprintf(stderr, ":%lu", f->line);
    fputc(')', stderr);
}

/* After the error line, the chain of calls that led to it (innermost first; the error
 * line names the innermost), where the failing text was, and the data stack then: each
 * indented, so the error itself stays the one line an editor parses. */
static void report_backtrace(mon *m, const fbrl_vm_error *e, const fbrl_vm_frame *bt, size_t n,
                             size_t omitted, const char *where, unsigned long line)
{
    for (size_t i = 1; i < n; i++) {
        if (omitted && i == n - MON_BT_OUTER)
            fprintf(stderr, "  ... %zu more calls ...\n", omitted);
        fputs("  called by ", stderr);
        put_clean(bt[i].word);
        put_frame_place(&bt[i]);
        fputc('\n', stderr);
    }
    if (e->file[0] && e->line > 0 && (n == 0 || strcmp(bt[0].file, e->file) != 0 || bt[0].line != e->line)) {
        fputs("  called from ", stderr);
        put_clean(e->file);
        fprintf(stderr, ":%lu\n", e->line);
    } else if (!e->file[0] && where != NULL && line > 0) {
        fputs("  called from ", stderr);
        put_clean(where);
        fprintf(stderr, ":%lu\n", line + (e->line > 1 ? e->line - 1 : 0));
    }
    fbrl_cell cells[MON_BT_STACK];
    size_t depth = fbrl_vm_error_stack(m->vm, cells, MON_BT_STACK);
    if (depth > 0) {
        size_t shown = depth < MON_BT_STACK ? depth : MON_BT_STACK;
        fprintf(stderr, "  data stack <%zu>:%s", depth, depth > shown ? " ..." : "");
        for (size_t i = 0; i < shown; i++)
            fprintf(stderr, " %ld", (long)cells[i]);
        fputc('\n', stderr);
    }
}

/* "FILE:LINE: error: MESSAGE [in WORD]", the form editors and compilers use
 * (docs/fbrlmon.md). Errors inside an included file carry that file's name and line;
 * otherwise `where` and the line we counted; a typed line has no place: "error: ...".
 * An error inside a colon definition of a file names that word and its place, and the
 * indented lines after it show the calls that led there (report_backtrace). */
static void report(mon *m, fbrl_status st, const char *where, unsigned long line)
{
    const fbrl_vm_error *e = fbrl_vm_last_error(m->vm);
    fbrl_vm_frame bt[MON_BT_FRAMES];
    size_t omitted = 0;
    size_t nbt = e != NULL ? fbrl_vm_backtrace(m->vm, bt, MON_BT_FRAMES, &omitted) : 0;
    if (nbt > MON_BT_FRAMES)
        nbt = MON_BT_FRAMES;
    const char *msg = e != NULL && e->message[0] ? e->message : fbrl_status_str(st);

    mon_host_newline(&m->host);
    if (e != NULL && e->file[0] && e->line > 0 && strlen(e->file) < sizeof m->resume_file) {
        strcpy(m->resume_file, e->file); /* where RESUME goes on */
        m->resume_line = e->line;
    }
    if (nbt > 0 && bt[0].file[0]) {
        put_clean(bt[0].file);
        if (bt[0].line > 0)
            fprintf(stderr, ":%lu", bt[0].line);
        fputs(": ", stderr);
    } else if (e != NULL && e->file[0]) {
        put_clean(e->file);
        if (e->line > 0)
            fprintf(stderr, ":%lu", e->line);
        fputs(": ", stderr);
    } else if (where != NULL && line > 0) {
        put_clean(where);
        fprintf(stderr, ":%lu: ", line + (e != NULL && e->line > 1 ? e->line - 1 : 0));
    } else if (where != NULL) {
        put_clean(where);
        fputs(": ", stderr);
    }
    fputs("error: ", stderr);
    put_clean(msg);
    /* Codes outside the system's ranges are the program's own: show the number. */
    if (e != NULL && (e->throw_code > 0 || e->throw_code < -4095))
        fprintf(stderr, " %d", e->throw_code);
    /* The word that failed; -39 (end of file) happens between words. */
    if (e != NULL && e->word[0] && e->throw_code != -39) {
        fputs(e->throw_code == -13 ? " " : " in ", stderr);
        put_clean(e->word);
    }
    fputc('\n', stderr);
    if (nbt > 0)
        report_backtrace(m, e, bt, nbt, omitted, where, line);
    fflush(stderr);
}

int mon_eval(mon *m, const char *text, size_t len, const char *where, unsigned long line, int counts)
{
    size_t words = fbrl_vm_word_count(m->vm);
    int compiling = fbrl_vm_compiling(m->vm), counting = m->counting;
    m->counting = counts;
    fbrl_status st = fbrl_vm_eval(m->vm, text, len);
    m->counting = counting;
    mon_step_end(m);
    /* The prompt's definitions (typed or piped), for LOCATE and SAVE-DEFINITIONS: the
     * lines of a definition count once it ended without an error. */
    if (where == NULL || strcmp(where, "stdin") == 0)
        mon_debug_typed(m, text, len, st == FBRL_OK, compiling, fbrl_vm_compiling(m->vm),
                        fbrl_vm_word_count(m->vm) > words);
    if (st == FBRL_OK)
        return 0;
    report(m, st, where, line);
    if (counts)
        m->errors++;
    return -1;
}

int mon_include(mon *m, const char *path)
{
    int counting = m->counting;
    m->counting = 1;
    fbrl_status st = fbrl_vm_include(m->vm, path);
    m->counting = counting;
    mon_step_end(m);
    if (st == FBRL_OK)
        return 0; /* (the engine itself refuses a file that ends inside a definition) */
    report(m, st, path, 0);
    m->errors++;
    return -1;
}

int mon_check_closed(mon *m, const char *what, const char *where, unsigned long line)
{
    if (!fbrl_vm_compiling(m->vm))
        return 0;
    mon_host_newline(&m->host);
    put_clean(where);
    if (line > 0)
        fprintf(stderr, ":%lu", line);
    fprintf(stderr, ": error: unterminated definition at end of %s\n", what);
    fflush(stderr);
    m->errors++;
    fbrl_vm_reset(m->vm); /* as after any other error: the definition is dropped */
    return -1;
}
