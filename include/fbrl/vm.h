/* SPDX-License-Identifier: MIT */
/* vm.h - the embeddable FBRL language engine (a Forth system).
 *
 * A VM lives entirely in memory the caller provides (dictionary, stacks, buffers);
 * the engine never allocates, prints or touches the OS: output, input, files and
 * time come through the callbacks in fbrl_vm_config. Several VMs may live in one
 * process. Every error is returned, never an exit. */
#ifndef FBRL_VM_H
#define FBRL_VM_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef intptr_t fbrl_cell; /* 64-bit on 64-bit hosts */
typedef struct fbrl_vm fbrl_vm;

/* Host services. Any callback may be NULL; the words that need a missing one
 * throw a clear error (e.g. INCLUDED without file_open). */
/* The standard FILE word set's access to a file system (optional: a host without one,
 * e.g. the firmware, passes NULL and the VM has no standard file words). Paths are
 * NUL-terminated; a handle is the host's own. Each returns FBRL_OK or a status
 * (FBRL_ENOENT no such file, FBRL_EIO ...), which the words give as an ior. */
typedef struct fbrl_vm_files {
    /* fam: FBRL_FAM_* bits; create: make or empty the file first */
    fbrl_status (*open)(void *user, const char *path, unsigned fam, int create, void **handle);
    fbrl_status (*close)(void *user, void *handle);
    /* up to n bytes (*got < n only at the end of the file) */
    fbrl_status (*read)(void *user, void *handle, void *buf, size_t n, size_t *got);
    fbrl_status (*write)(void *user, void *handle, const void *buf, size_t n);
    fbrl_status (*seek)(void *user, void *handle, uint64_t pos);
    fbrl_status (*tell)(void *user, void *handle, uint64_t *pos);
    fbrl_status (*size)(void *user, void *handle, uint64_t *size);
    fbrl_status (*resize)(void *user, void *handle, uint64_t size);
    fbrl_status (*flush)(void *user, void *handle);
    fbrl_status (*remove)(void *user, const char *path);
    fbrl_status (*rename)(void *user, const char *from, const char *to);
    /* FBRL_OK if the file exists (*mode: FBRL_FAM_* bits it may be opened with) */
    fbrl_status (*status)(void *user, const char *path, unsigned *mode);
} fbrl_vm_files;
#define FBRL_FAM_READ  1u
#define FBRL_FAM_WRITE 2u
#define FBRL_FAM_BIN   4u

typedef struct fbrl_vm_host {
    void *user;
    /* Output: n bytes for the console (EMIT, TYPE, ., error messages). */
    void (*write)(void *user, const char *s, size_t n);
    /* Input for KEY/ACCEPT: next byte or -1 at end of input; key_ready for KEY?. */
    int (*key)(void *user);
    int (*key_ready)(void *user);
    /* Source files for INCLUDED/REQUIRE: open by path (already resolved against the
     * including file's directory by the engine), read one line at a time
     * (without its end-of-line; *len set; FBRL_EEOF at end), close. */
    fbrl_status (*file_open)(void *user, const char *path, void **handle);
    fbrl_status (*file_read_line)(void *user, void *handle, char *buf, size_t cap, size_t *len);
    void (*file_close)(void *user, void *handle);
    /* Time: monotonic microseconds (MS, timers), sleeping, and local date/time
     * for TIME&DATE as {sec, min, hour, day, month, year}. */
    uint64_t (*now_us)(void *user);
    void (*sleep_ms)(void *user, uint32_t ms);
    void (*time_date)(void *user, int out[6]);
    /* One edited console line (optional; words that read whole lines from the console,
     * e.g. GET-CAL-POINTS, use it instead of key): show prompt, let the user type and
     * edit the line as at the host's own prompt; FBRL_OK with buf[0..*len) (no line end,
     * *len < cap), FBRL_EEOF at the end of input or when Ctrl-C ended the reading (the
     * host then has called fbrl_vm_interrupt). */
    fbrl_status (*read_line)(void *user, const char *prompt, char *buf, size_t cap, size_t *len);
    /* The standard FILE words (optional, see fbrl_vm_files). */
    const fbrl_vm_files *files;
} fbrl_vm_host;

typedef struct fbrl_vm_config {
    void *mem;                 /* all VM storage; aligned to 16 bytes */
    size_t mem_size;           /* bytes; fbrl_vm_create() says FBRL_ENOSPC if too small */
    size_t data_stack_cells;   /* 0 = default (256) */
    size_t return_stack_cells; /* 0 = default (256) */
    size_t float_stack_cells;  /* 0 = default (64) */
    fbrl_vm_host host;
    /* Non-zero: the caller promises that mem reads as all zero bytes (calloc, a
     * fresh anonymous mmap). fbrl_vm_create() then writes only the pages it uses
     * (stacks, buffers, the built-in words at both ends), so a large dictionary
     * costs address space, not memory, until a program fills it. Zero (the
     * default): fbrl_vm_create() clears the whole block itself, touching every
     * page. Either way unused dictionary space reads as zero; the engine stays
     * memory-safe whatever the block held (every code cell is checked). */
    int mem_zeroed;
} fbrl_vm_config;

/* What went wrong in the last failed fbrl_vm_eval()/fbrl_vm_include(). */
typedef struct fbrl_vm_error {
    int throw_code;     /* Forth THROW code (e.g. -13 undefined word), 0 if none */
    char message[256];  /* e.g. "undefined word"; a controller error with its meaning */
    char word[64];      /* the word being interpreted when it failed */
    char file[256];     /* source file, "" for evaluated text */
    unsigned long line; /* 1-based line in that source */
} fbrl_vm_error;

/* A C primitive: pops its arguments and pushes its results through the API below.
 * Return FBRL_OK, or fbrl_vm_throw()'s result to raise a Forth exception. Any other
 * fbrl_status st raises THROW code FBRL_VM_THROW_OF_STATUS(st) (catchable in Forth;
 * its message is fbrl_status_str(st)); uncaught, fbrl_vm_eval() returns st itself. */
#define FBRL_VM_THROW_OF_STATUS(st) (-300 + (int)(st))
typedef fbrl_status (*fbrl_vm_prim)(fbrl_vm *vm, void *arg);

FBRL_API fbrl_status fbrl_vm_create(fbrl_vm **out, const fbrl_vm_config *cfg);
/* Smallest mem_size that fits the VM with these stack sizes and dict_bytes of dictionary. */
FBRL_API size_t fbrl_vm_size_for(const fbrl_vm_config *cfg, size_t dict_bytes);

/* Interpret text (any number of lines) as if typed. On error: stacks are reset,
 * the interpreter is back in interpretation state, the dictionary is unharmed,
 * and fbrl_vm_last_error() says what happened. Returns FBRL_OK (also after BYE,
 * which stops the text), FBRL_ETHROW for a Forth error, the status a C word failed
 * with (see FBRL_VM_THROW_OF_STATUS), FBRL_EINVAL, or FBRL_ESTATE when called from
 * inside a running word. A definition may span several calls (fbrl_vm_compiling). */
FBRL_API fbrl_status fbrl_vm_eval(fbrl_vm *vm, const char *text, size_t len);
/* INCLUDED: interpret a file through the host's file callbacks. */
FBRL_API fbrl_status fbrl_vm_include(fbrl_vm *vm, const char *path);
FBRL_API const fbrl_vm_error *fbrl_vm_last_error(const fbrl_vm *vm);

/* A backtrace keeps at most FBRL_VM_BACKTRACE_MAX frames: of a deeper chain, the
 * innermost ones and the outermost FBRL_VM_BACKTRACE_OUTER (the gap is before those). */
#define FBRL_VM_BACKTRACE_MAX   16
#define FBRL_VM_BACKTRACE_OUTER 4
#define FBRL_VM_BACKTRACE_STACK 8 /* data stack cells kept at an error */

/* Where the word name was defined: *file is its file ("" when it was typed or evaluated
 * text) and *line the line its definition starts on; a built-in word (a primitive, a C
 * word, the engine's own Forth) has *file "" and *line 0. FBRL_ENOENT if there is none. */
FBRL_API fbrl_status fbrl_vm_locate(const fbrl_vm *vm, const char *name, const char **file,
                                    unsigned long *line);
/* A colon definition about to run, as a step hook sees it; or a word about to run, as a
 * word hook sees it (fbrl_vm_word_hook). */
typedef struct fbrl_vm_stop {
    const char *word;        /* the definition ("" for :NONAME code); the word hook's word as
                                the source wrote it ("7", "DUP", "0BRANCH", "GO") */
    const char *file;        /* where it is defined ("" typed or evaluated, or built in) */
    unsigned long line;      /* its first line */
    const char *caller;      /* the definition calling it ("" when typed or run from C) */
    const char *call_file;   /* where the call is (the word hook: where the word is) */
    unsigned long call_line; /* 0: not known (typed, or C) */
    size_t depth;            /* colon definitions running, the one starting (or holding the
                                word) included: deeper calls have more */
} fbrl_vm_stop;
/* Called before each colon definition runs while set: return 0 to let it run, or a THROW
 * code to throw there (e.g. -1 to abort the evaluation). It may evaluate text with
 * fbrl_vmx_evaluate_catch (what that runs is not stepped) and must leave the stacks as
 * it found them. */
typedef int (*fbrl_vm_step_fn)(void *ctx, fbrl_vm *vm, const fbrl_vm_stop *stop);
/* Set (fn) or clear (NULL) the step hook: the base of a debugger. A program runs slower
 * while one is set. FBRL_EINVAL for a NULL vm. */
FBRL_API fbrl_status fbrl_vm_step_hook(fbrl_vm *vm, fbrl_vm_step_fn fn, void *ctx);
/* Set (fn) or clear (NULL) the word hook: while set, fn is called before each word a colon
 * definition runs (built-in words, numbers and control words included, as gforth's dbg
 * steps) and before each word the interpreter runs: a debugger's single steps and line
 * breakpoints. stop->word is the word; file and line where it is defined (""/0 built in);
 * caller, call_file and call_line the definition it is in and the word's line ("" and the
 * text's file and line for an interpreted word). fn returns as a step hook's. A program
 * runs several times slower while one is set. FBRL_EINVAL for a NULL vm. */
FBRL_API fbrl_status fbrl_vm_word_hook(fbrl_vm *vm, fbrl_vm_step_fn fn, void *ctx);

/* Where the running program is, for a C word (e.g. a robot word telling which line sent
 * a command): the colon definition that called it and the file and line of that call; or,
 * called from interpreted text, *word "" and the text's file and line. Outside an
 * evaluation all are "" and 0. */
FBRL_API fbrl_status fbrl_vm_where(fbrl_vm *vm, const char **word, const char **file, unsigned long *line);

/* How many words the dictionary holds (it grows with each definition). */
FBRL_API size_t fbrl_vm_word_count(const fbrl_vm *vm);

/* One word of the last error's chain of calls. */
typedef struct fbrl_vm_frame {
    const char *word;   /* the colon definition (valid until the next evaluation) */
    const char *file;   /* the file it is in; "" when it was typed or evaluated text */
    unsigned long line; /* the line of the failing or calling code (that of the definition
                           when finer lines are not known); 0: unknown */
} fbrl_vm_frame;
/* The chain of colon definitions the last error happened in, innermost first: the
 * word that failed, then its callers. Fills up to cap frames and returns how many
 * there are; a chain deeper than the engine keeps loses its middle, and *omitted
 * (if not NULL) says how many frames that dropped. 0 when the error happened outside
 * any colon definition (e.g. an undefined word typed). */
FBRL_API size_t fbrl_vm_backtrace(const fbrl_vm *vm, fbrl_vm_frame *out, size_t cap, size_t *omitted);
/* The data stack when the last error happened: returns its depth and copies up to cap
 * of its top cells (deepest first; at most FBRL_VM_BACKTRACE_STACK are kept). */
FBRL_API size_t fbrl_vm_error_stack(const fbrl_vm *vm, fbrl_cell *out, size_t cap);
/* Ask the running evaluation to stop: it throws -28 ("user interrupt") at its next
 * call, loop iteration, backward branch, C word's return, MS or output padding. Safe from a signal handler or another
 * thread (e.g. the monitor's Ctrl-C). A request is dropped when it is delivered and
 * at the start of each fbrl_vm_eval()/fbrl_vm_include(). */
FBRL_API void fbrl_vm_interrupt(fbrl_vm *vm);
/* True while an interrupt is requested and not yet delivered: a C word that waits
 * (motion, input, sleep) polls this and returns early; the engine then throws -28
 * as soon as the word returns. */
FBRL_API int fbrl_vm_interrupt_pending(const fbrl_vm *vm);
/* True once BYE ran. */
FBRL_API int fbrl_vm_bye(const fbrl_vm *vm);
/* True while a colon definition (or other compilation) spans lines. */
FBRL_API int fbrl_vm_compiling(const fbrl_vm *vm);
/* Back to a clean prompt, as after an error: an unfinished definition is dropped,
 * the stacks are emptied, interpretation state. (Not from inside a running word.) */
FBRL_API void fbrl_vm_reset(fbrl_vm *vm);

/* Cooperative tasks (docs/tasks.md) from a host's own event loop: run every task that
 * is due until each waits, without blocking; *wake_us (host clock, now_us) is when to
 * call again (UINT64_MAX: no task waits on the clock; *live = 0: no task left). Output
 * (a task's error, its name first) goes to the write callback. FBRL_ESTATE from inside
 * fbrl_vm_eval() (its waits run the tasks themselves). live may be NULL. */
FBRL_API fbrl_status fbrl_vm_run_tasks(fbrl_vm *vm, uint64_t *wake_us, int *live);

/* Extending the language from C (robot words, data words). The stack effect and
 * the one-line description are what HELP prints. */
/* A word table's stack effect and description. Under FBRL_NO_HELP (a small target's build
 * option) neither the texts nor the two pointers are in the image: a row type ends with
 * FBRL_DOC_FIELDS (no semicolon after it), each row ends with FBRL_DOC(stack, help) (which
 * leaves a trailing comma, as C allows), and FBRL_DOC_STACK(row), FBRL_DOC_HELP(row) read
 * them (NULL under the option). A text given to a call (fbrl_vmx_create's for the words a
 * defining word makes) is FBRL_DOC_TEXT(text): NULL under the option. In Forth source kept
 * in C, a definition's "( stack ) \\ help" is FBRL_DOC_SRC("( stack ) \\ help"): "" under the
 * option. */
#ifdef FBRL_NO_HELP
#define FBRL_DOC_FIELDS
#define FBRL_DOC(stack_effect, help)
#define FBRL_DOC_STACK(row)   NULL
#define FBRL_DOC_HELP(row)    NULL
#define FBRL_DOC_TEXT(text)   NULL
#define FBRL_DOC_SRC(comment) ""
#else
#define FBRL_DOC_FIELDS              const char *stack, *help;
#define FBRL_DOC(stack_effect, help) stack_effect, help
#define FBRL_DOC_STACK(row)          ((row).stack)
#define FBRL_DOC_HELP(row)           ((row).help)
#define FBRL_DOC_TEXT(text)          (text)
#define FBRL_DOC_SRC(comment)        comment
#endif
FBRL_API fbrl_status fbrl_vm_define(fbrl_vm *vm, const char *name, fbrl_vm_prim fn, void *arg,
                                    const char *stack_effect, const char *help);
FBRL_API fbrl_status fbrl_vm_push(fbrl_vm *vm, fbrl_cell v);
FBRL_API fbrl_status fbrl_vm_pop(fbrl_vm *vm, fbrl_cell *v);
FBRL_API fbrl_status fbrl_vm_fpush(fbrl_vm *vm, double v);
FBRL_API fbrl_status fbrl_vm_fpop(fbrl_vm *vm, double *v);
FBRL_API size_t fbrl_vm_depth(const fbrl_vm *vm);
FBRL_API size_t fbrl_vm_fdepth(const fbrl_vm *vm);
/* Raise a Forth exception from a primitive (code < 0 standard, else user); msg may be NULL. */
FBRL_API fbrl_status fbrl_vm_throw(fbrl_vm *vm, int code, const char *msg);
/* Parse the next blank-delimited name from the input (for parsing words such as
 * `CREATE-LOC P1`); *len = 0 at end of line. */
FBRL_API fbrl_status fbrl_vm_parse_name(fbrl_vm *vm, const char **name, size_t *len);
/* Translate a VM address (as pushed on the data stack) to a C pointer with n bytes
 * in the VM's data space, or NULL if it does not lie wholly inside. */
FBRL_API void *fbrl_vm_addr(fbrl_vm *vm, fbrl_cell addr, size_t n);

/* Introspection for the monitor: help text and word iteration (for TAB completion). */
FBRL_API fbrl_status fbrl_vm_help(const fbrl_vm *vm, const char *name, const char **stack_effect,
                                  const char **help);
/* Calls fn for every visible word name, newest first; stops early if fn returns non-zero. */
FBRL_API void fbrl_vm_words(const fbrl_vm *vm, int (*fn)(void *ctx, const char *name, size_t len), void *ctx);

#ifdef __cplusplus
}
#endif
#endif
