/* SPDX-License-Identifier: MIT */
/* mon.h - the monitor's session: one FBRL engine, its host services, and the
 * rules for reporting errors (one line each) shared by every input source. */
#ifndef FBRLMON_MON_H
#define FBRLMON_MON_H

#include <stddef.h>
#include "fbrl/cell_words.h"
#include "fbrl/glossary.h"
#include "fbrl/link.h"
#include "fbrl/method.h"
#include "fbrl/recover.h"
#include "fbrl/robot.h"
#include "fbrl/run.h"
#include "fbrl/vm.h"
#include "fbrl/workspace.h"
#include "mon_host.h"
#include "mon_step.h"
#include "mon_trace.h"

/* Exit status (documented in docs/fbrlmon.md). */
#define MON_EXIT_OK      0 /* everything evaluated without error */
#define MON_EXIT_ERROR   1 /* an error aborted a file, -e text or a line of piped input */
#define MON_EXIT_USAGE   2 /* bad command line */
#define MON_EXIT_CONNECT 3 /* could not start: no memory for the VM, port would not open */
#define MON_EXIT_RUN     4 /* a method run from a file, -e text or piped input did not complete */

/* Storage for the typed data files the file words keep open (split among them). */
#define MON_FILE_STORAGE (8u * 1024u * 1024u)

/* File buffer of the workspace words (SAVE-WORKSPACE ...): FBRL_WORKSPACE_OBJECT_BYTES
 * each, so about 20,000 named objects. */
#define MON_WORKSPACE_STORAGE (4u * 1024u * 1024u)

struct mon_conn;

/* Keep at a fixed address while the VM runs (the words point into it). */
typedef struct mon {
    fbrl_vm *vm;
    void *vm_mem;
    void *file_mem;
    mon_host host;
    fbrl_glossary glossary;  /* locations, matrices, calibration, metric, data files */
    fbrl_robot robot;        /* robot words; talk through the link, if any */
    fbrl_method_set methods; /* METHOD ... RUN-METHOD (the console runs them) */
    fbrl_workspace ws;       /* SAVE-WORKSPACE, LOAD-WORKSPACE (mon_ws.c: --workspace) */
    void *ws_mem;
    fbrl_cell_words *cell; /* the work cell and the motion guard (CELL-BOX ...) */
    fbrl_link *link;       /* the controller (NULL offline); TEACH talks through it too */
    unsigned long errors;  /* errors in files, -e text and piped input */
    struct mon_conn *conn; /* the connection RECONNECT opens again (NULL: none) */
    int typed;             /* evaluating a line typed at the prompt */
    /* each line a person types at the prompt, before it runs: fbrlmon records it in the
     * audit trail (the console records its own Forth line the same way) */
    void (*typed_hook)(void *ctx, const char *line, size_t len);
    void *typed_ctx;
    char resume_file[256]; /* RESUME: the file and line of the last error in a file */
    unsigned long resume_line;
    char *typed_src; /* lines typed at the prompt that defined words (mon_debug.c) */
    size_t typed_len, typed_cap;
    size_t typed_open; /* of typed_len, the last bytes: a definition not yet ended */
    char edit_ws[256];    /* EDIT: where the session's work waits while the file loads */
    mon_step step;        /* the debugger (mon_step.c) */
    mon_trace trace;      /* TRACE-ON, TRACE-WORDS (mon_trace.c, mon_step.c) */
    fbrl_recover recover; /* ON-FAILURE, ATTEMPT (mon_recover.c) */
    fbrl_run run;         /* RUN-METHOD: the method run the console and the run log observe */
    int counting;         /* evaluating a file, -e text or piped input (errors count) */
    unsigned long runs_incomplete; /* of those: method runs whose outcome was not completed */
    struct fbrl_runlog *runlog; /* the run log RECONNECT notes in while a run is logged */
} mon;

/* Create the VM (dict_bytes of dictionary) with output to stdout, keys from stdin,
 * and the thesis's glossary and robot words; link is the connected controller or
 * NULL (offline: the robot words say so when used). *m must be all zero, as static
 * storage is: clearing its 134 KB again would make every page of it resident. */
int mon_open(mon *m, size_t dict_bytes, fbrl_link *link);
/* The picture of the cell written to path whole (CELL-SVG, the dry run's picture). */
fbrl_status mon_save_svg(void *ctx, const char *path, fbrl_cell_words *cw);
/* Close the data files (committing them; a failure counts as an error) and free. */
void mon_close(mon *m);

/* Evaluate one line (or text) from `where` (a name for messages, e.g. "stdin"),
 * whose first line is `line`. On error print one line to stderr and return -1;
 * counts toward the exit status only if `counts`. */
int mon_eval(mon *m, const char *text, size_t len, const char *where, unsigned long line, int counts);
/* INCLUDED the file at path; errors as for mon_eval (always counted). */
int mon_include(mon *m, const char *path);
/* At the end of -e text or piped input a definition must not be left open:
 * report it as an error (counted; `what` is "text" or "input")
 * and return the VM to interpreting. */
int mon_check_closed(mon *m, const char *what, const char *where, unsigned long line);

/* Interactive session on the terminal (mon_edit.c). Returns when the user ends
 * it (BYE or end of input). */
void mon_interactive(mon *m);

#endif
