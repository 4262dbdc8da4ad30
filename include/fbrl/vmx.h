/* SPDX-License-Identifier: MIT */
/* vmx.h - the extension interface for word sets (as Lua's lauxlib is to its lua.h).
 *
 * A word set (the data words, the glossary, calibration, files, robot, communication,
 * I/O, the monitor's TEACH) is C code that adds words to a VM. It uses vm.h and this
 * header, and nothing of the engine's insides: src/words/ is compiled against include/
 * alone, and the suite's boundary check fails if a word set names an engine internal.
 *
 *  - define a word: a C function with two context pointers (the word set's state, e.g.
 *    the robot, and the word's own table entry) and flags (immediate, compile-only);
 *  - typed data in VM memory: a named word whose data field starts with the type's magic
 *    cell, made whole or not at all (a failed creation leaves no word behind), and checked
 *    on every use, since a program can overwrite anything in data space;
 *  - arguments: one parser for parameters from the stacks or typed after the word, with
 *    the engine's own number syntax, and one rule for integers given where a real is
 *    expected (docs/language.md, "Word sets");
 *  - execute, evaluate, parse, state, compile a literal, the host's services.
 *
 * Throw codes are named in fbrl/vm_throw.h. docs/language.md tells how to write a word set. */
#ifndef FBRL_VMX_H
#define FBRL_VMX_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/vm.h"
#include "fbrl/vm_throw.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A cell as an unsigned number. */
typedef uintptr_t fbrl_ucell;

/* The longest word name. */
#define FBRL_VMX_NAME_MAX 31

/* ---- defining words ---- */

/* Word flags. */
#define FBRL_VMX_IMMEDIATE    1u /* runs while compiling too */
#define FBRL_VMX_COMPILE_ONLY 2u /* refused while interpreting (THROW -14) */
#define FBRL_VMX_STATE_SMART  4u /* with IMMEDIATE: POSTPONE compiles a call that runs it compiling */

/* A C word. ctx is the word set's state given to fbrl_vmx_define (per VM); word is the
 * word's own entry given there (e.g. its row of the word set's table), or for a word made
 * by fbrl_vmx_create() with a run function, the C address of its data field. Return
 * FBRL_OK, fbrl_vm_throw()'s result, or a status (raised as FBRL_VM_THROW_OF_STATUS). */
typedef fbrl_status (*fbrl_vmx_fn)(fbrl_vm *vm, void *ctx, const void *word);

/* Define a C word. The stack effect and the one-line description are what HELP prints (the
 * strings must outlive the VM). FBRL_EINVAL for NULLs or unknown flags, FBRL_ENAME for a
 * bad name (1..31 characters, no blanks), FBRL_ESTATE inside a definition, FBRL_ENOMEM when
 * the dictionary is full. */
FBRL_API fbrl_status fbrl_vmx_define(fbrl_vm *vm, const char *name, fbrl_vmx_fn fn, void *ctx,
                                     const void *word, unsigned flags, const char *stack_effect,
                                     const char *help);

/* ---- a word set's table (as Lua's luaL_Reg and luaL_setfuncs) ---- */

/* One word of a word set. fn runs with ctx (fbrl_vmx_define_table's) and the row itself as
 * its word; spec lists its parameters in fbrl_vmx_args' letters ("" for none) and
 * fbrl_vmx_check() fetches them (a word set with letters of its own maps them onto those:
 * the robot's L X A J); flags as fbrl_vmx_define's, with FBRL_VMX_PARSE; code and arg are
 * the word set's own numbers, so that one function serves several rows (a controller
 * command, a selector, a size). The help text is FBRL_DOC(stack effect, help). */
typedef struct fbrl_vmx_reg {
    const char *name;
    fbrl_vmx_fn fn;
    const char *spec;
    uint8_t flags;
    int16_t code;
    intptr_t arg;
    FBRL_DOC_FIELDS
} fbrl_vmx_reg;
#define FBRL_VMX_PARSE 8u /* row flag: its parameters may be typed after it (FBRL_VMX_LINE) */

/* Define the n words of rows (which must outlive the VM), in order, each with ctx: FBRL_OK,
 * or fbrl_vmx_define's failure for the first row that fails (the rows before it stay). */
FBRL_API fbrl_status fbrl_vmx_define_table(fbrl_vm *vm, const fbrl_vmx_reg *rows, size_t n, void *ctx);

/* The execution token of the newest visible word of that name: FBRL_OK, or FBRL_ENOENT. */
FBRL_API fbrl_status fbrl_vmx_find(const fbrl_vm *vm, const char *name, size_t len, fbrl_cell *xt);
/* The name of the word xt (in the VM's headers, valid while the word is; "" for :NONAME
 * code): FBRL_OK, or FBRL_ENOENT for a cell that is no xt. */
FBRL_API fbrl_status fbrl_vmx_name(const fbrl_vm *vm, fbrl_cell xt, const char **name, size_t *len);

/* ---- typed data in VM memory ---- */

/* A type of structure: its first cell holds magic; the payload starts FBRL_VMX_PAYLOAD
 * bytes into the (16-aligned) data field. name is for messages ("queue"). */
typedef struct fbrl_vmx_type {
    const char *name;
    fbrl_cell magic;
} fbrl_vmx_type;
#define FBRL_VMX_PAYLOAD 16

/* Make a word whose data field holds a structure: name (len bytes), or with name NULL the
 * next name parsed from the input (a "( stack )" and "\ help" comment after it on its line
 * become its HELP, as for CREATE). With type, the data field is 16-aligned, starts with
 * type->magic and holds `bytes` zeroed payload bytes at FBRL_VMX_PAYLOAD; without, it is
 * `bytes` zeroed bytes, cell-aligned. With run NULL the word pushes its data field's address
 * and ctx is its tag (fbrl_vmx_tag: how a word set knows its own plain data words, e.g.
 * the glossary its locations); otherwise it runs run(vm, ctx, data field). *addr gets the data field's VM address, *payload
 * the payload's C address (either may be NULL).
 * All or nothing: on any failure (no name, name too long, dictionary full) no word and no
 * byte of data space is left behind, and the failure is thrown (e.g. -8 dictionary overflow):
 * the result is FBRL_ETHROW. */
FBRL_API fbrl_status fbrl_vmx_create(fbrl_vm *vm, const char *name, size_t len, const fbrl_vmx_type *type,
                                     size_t bytes, fbrl_vmx_fn run, void *ctx, const char *stack_effect,
                                     const char *help, fbrl_cell *addr, void **payload);

/* The payload of a structure of this type at VM address addr (a data field fbrl_vmx_create
 * made, or a copy of one), checked to lie wholly in data space with `bytes` payload bytes;
 * NULL if addr is not one (wrong magic, outside, misaligned). */
FBRL_API void *fbrl_vmx_data(fbrl_vm *vm, fbrl_cell addr, const fbrl_vmx_type *type, size_t bytes);

/* The data field of the word xt if fbrl_vmx_create made it with this run function (run
 * NULL: if xt only pushes its data field's address, as VARIABLE and fbrl_vmx_create without
 * run make it): FBRL_OK, or FBRL_ETYPE (another word, or no word). */
FBRL_API fbrl_status fbrl_vmx_created(const fbrl_vm *vm, fbrl_cell xt, fbrl_vmx_fn run, fbrl_cell *addr);

/* The tag fbrl_vmx_create gave the word xt (made without a run function; NULL for other
 * data words: VARIABLE, CREATE) and its data field: FBRL_OK, or FBRL_ETYPE if xt is not a
 * word that pushes its data field's address. */
FBRL_API fbrl_status fbrl_vmx_tag(const fbrl_vm *vm, fbrl_cell xt, const void **tag, fbrl_cell *addr);

/* A point in the dictionary's history, to take back every word (and data space) made
 * after it: a word set that makes several words as one step (a workspace loaded) undoes
 * the step when a later word fails. */
typedef struct fbrl_vmx_mark {
    fbrl_cell here;
    uint32_t nwords;
    size_t required;
} fbrl_vmx_mark;
FBRL_API fbrl_status fbrl_vmx_mark_here(const fbrl_vm *vm, fbrl_vmx_mark *m);
/* Forget every word made since m (FBRL_ESTATE inside a definition or if m lies in the future). */
FBRL_API fbrl_status fbrl_vmx_forget(fbrl_vm *vm, const fbrl_vmx_mark *m);

/* ---- arguments: from the stacks or from the input after the word ---- */

/* Parameter kinds, one letter each in a spec string (in the word's parameter order):
 *   I  integer (cell)           R  real (float stack; an integer is accepted, see below)
 *   C  character (cell)         A  address (cell); after the word: a data word's name
 *   N  address, or after the word a name that is no word (kept as text)
 *   S  string (c-addr u); after the word: a word or a "quoted text"
 *   T  string (c-addr u); after the word: the rest of the line */
typedef struct fbrl_vmx_val {
    fbrl_cell i;   /* I C A N: the value (N given as a name: 0) */
    double f;      /* R */
    const char *s; /* S T, N given as a name: the text (in the VM's data space) */
    size_t n;
} fbrl_vmx_val;
#define FBRL_VMX_MAXARGS 8

/* Where the values may come from. */
#define FBRL_VMX_STACKS 0u /* the stacks only: too few is a stack underflow (-4, or -45 for reals) */
#define FBRL_VMX_LINE \
    1u /* the stacks when they hold every parameter; otherwise all of them are
                            * parsed from the input after the word, in spec order (thesis I-6) */

/* Fetch the parameters of `spec` into v[0..strlen(spec)) (at most FBRL_VMX_MAXARGS).
 * Reals given as integers (one rule, docs/language.md): when the float stack holds fewer
 * values than the spec has R parameters, all of them are taken from the data stack instead,
 * as integers: the cells just beneath the word's other parameters, in spec order (so
 * `14 2 8 0 -90 0 P DEFINE-LOC` is `14E0 2E0 8E0 0E0 -90E0 0E0 P DEFINE-LOC`).
 * A parameter typed after the word is parsed as the interpreter parses a number (BASE,
 * 'c' characters, prefixes # $ %); a constant or value stands for its number, a data word
 * (variable, CREATE, constant, value) for an address; code never runs.
 * word names the word in error messages; what[k], if what is not NULL and what[k] is not
 * NULL, describes parameter k there ("a location name"). Throws on error. */
FBRL_API fbrl_status fbrl_vmx_args(fbrl_vm *vm, const char *word, const char *spec, const char *const *what,
                                   unsigned how, fbrl_vmx_val *v);

/* The parameters of a table word (as Lua's luaL_check*): fbrl_vmx_args with the row's name
 * and spec, from the stacks, or with FBRL_VMX_PARSE in its flags also from the input after
 * it. word is the row the word was given (its fn's third argument). Throws on error. */
FBRL_API fbrl_status fbrl_vmx_check(fbrl_vm *vm, const void *word, fbrl_vmx_val *v);

/* One parameter of the given kind parsed from the input after the word (GETREAL). */
FBRL_API fbrl_status fbrl_vmx_arg_parse(fbrl_vm *vm, const char *word, char kind, const char *what,
                                        fbrl_vmx_val *v);

/* Push n values (as the interpreter would: -3 / -44 on overflow, thrown). */
FBRL_API fbrl_status fbrl_vmx_push(fbrl_vm *vm, fbrl_cell v);
FBRL_API fbrl_status fbrl_vmx_fpush(fbrl_vm *vm, double v);

/* ---- parsing, state, compiling, running ---- */

/* Text up to delim (a blank delimiter also ends at any control character); *found = 1 if
 * the delimiter was met. At the end of the input: *len = 0. */
FBRL_API fbrl_status fbrl_vmx_parse(fbrl_vm *vm, char delim, const char **text, size_t *len, int *found);
/* Skip blanks; if a '"' follows, the text up to the next '"' (1 = found, 0 = unterminated,
 * -1 = no quote follows: nothing but the blanks is consumed). */
FBRL_API int fbrl_vmx_parse_quoted(fbrl_vm *vm, const char **text, size_t *len);
/* The rest of the line, blanks trimmed at both ends; the line is consumed. */
FBRL_API fbrl_status fbrl_vmx_parse_line(fbrl_vm *vm, const char **text, size_t *len);
/* The next line of the current input source (a file or evaluated text), consumed whole:
 * FBRL_OK, FBRL_EEOF when it has none (or it is an EVALUATEd string), or a throw. */
FBRL_API fbrl_status fbrl_vmx_refill(fbrl_vm *vm, const char **line, size_t *len);

/* True while compiling (STATE is not zero). */
FBRL_API int fbrl_vmx_compiling(const fbrl_vm *vm);
/* Compile into the current definition: a literal; a call to xt; a string literal that
 * pushes its c-addr u when run. Throw on error (dictionary full). */
FBRL_API fbrl_status fbrl_vmx_compile_lit(fbrl_vm *vm, fbrl_cell v);
FBRL_API fbrl_status fbrl_vmx_compile_xt(fbrl_vm *vm, fbrl_cell xt);
FBRL_API fbrl_status fbrl_vmx_compile_string(fbrl_vm *vm, const char *s, size_t n);

/* Run a word / interpret text (it must stay in place while it runs, e.g. in data space)
 * from inside a C word; an exception inside is re-thrown to the caller's caller. */
FBRL_API fbrl_status fbrl_vmx_execute(fbrl_vm *vm, fbrl_cell xt);
FBRL_API fbrl_status fbrl_vmx_evaluate(fbrl_vm *vm, const char *text, size_t len);

/* Interpret text as fbrl_vmx_evaluate, catching an exception inside (as CATCH would): the
 * stacks are put back to their depth before, a definition the text left open is dropped,
 * and the VM's error record stays as it was (the caller's own error, if any, is reported
 * as usual). Returns 0, or the THROW code with its one-line message (the failing word
 * named, e.g. "undefined word FOO") in msg[0..cap) (cap >= 1). BYE and QUIT are not
 * caught: they return as from fbrl_vmx_evaluate, with *code 0. */
FBRL_API fbrl_status fbrl_vmx_evaluate_catch(fbrl_vm *vm, const char *text, size_t len, int *code, char *msg,
                                             size_t cap);

/* ---- host services ---- */

/* The host callbacks the VM was made with (output, keys, files, clock). */
FBRL_API const fbrl_vm_host *fbrl_vmx_host(const fbrl_vm *vm);
/* Console output (nothing without a write callback). */
FBRL_API void fbrl_vmx_write(fbrl_vm *vm, const char *s, size_t n);
FBRL_API void fbrl_vmx_puts(fbrl_vm *vm, const char *s);
/* Take a pending Ctrl-C (fbrl_vm_interrupt) now, for a word that waits: 1 if there was one
 * (it is then cleared: the word should throw FBRL_THROW_INTERRUPT), else 0. */
FBRL_API int fbrl_vmx_take_interrupt(fbrl_vm *vm);
/* ---- waiting words and cooperative tasks (docs/tasks.md) ---- */

/* What a waiting word keeps while it waits: when it began (host microseconds) and a few
 * cells of its own progress (zero at first). A background task's waiting word gives up
 * the processor by returning fbrl_vmx_pause()'s status; the engine then calls it again
 * when the task resumes, with this record kept, until it returns anything else. */
typedef struct fbrl_vmx_wait {
    uint64_t since_us;
    fbrl_cell memo[4];
    int resumed; /* 0 on the first call of this wait, 1 when called again */
} fbrl_vmx_wait;
/* START-TIMER's mark: each task has its own. */
typedef struct fbrl_vmx_timer {
    uint64_t mark_ms;
    int set;
} fbrl_vmx_timer;

/* True while other tasks exist: a waiting word must then let them run (fbrl_vmx_pause);
 * false when the program runs alone, and the word may wait as it always did. */
FBRL_API int fbrl_vmx_tasking(const fbrl_vm *vm);
/* The running task's record for the waiting word calling it (begun on the first call). */
FBRL_API fbrl_vmx_wait *fbrl_vmx_wait_state(fbrl_vm *vm);
/* Let the other tasks run until the host clock reaches wake_us. FBRL_OK: it is that time
 * now (check your condition again). Anything else: return it at once, pushing nothing
 * (what the word popped is put back): a background task yields here, and the word is
 * called again when the task resumes; or Ctrl-C (a throw). */
FBRL_API fbrl_status fbrl_vmx_pause(fbrl_vm *vm, uint64_t wake_us);
/* True when the status fbrl_vmx_pause() just returned is a yield (the word runs again;
 * leave what it started, e.g. an output switched on, as it is), false for an error. */
FBRL_API int fbrl_vmx_yielded(const fbrl_vm *vm);
/* The running task's START-TIMER mark. */
FBRL_API fbrl_vmx_timer *fbrl_vmx_task_timer(fbrl_vm *vm);
/* Wait (as fbrl_vmx_pause) while another task holds the resource key (e.g. the arm,
 * FBRL_VMX_ARM): a motion word calls this so that it never cuts into another task's
 * claimed manoeuvre. FBRL_OK when the running task may go on. */
FBRL_API fbrl_status fbrl_vmx_claim_wait(fbrl_vm *vm, fbrl_cell key);
#define FBRL_VMX_ARM ((fbrl_cell)1) /* the arm's resource key (ARM pushes it) */

/* Throw with a printf-formatted message (at most 127 characters are kept). */
FBRL_API fbrl_status fbrl_vmx_throwf(fbrl_vm *vm, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- word lists ---- */

/* The word list FORTH-2012 puts first in the search order: the standard words whose names
 * an FBRL word set uses with another meaning (the thesis's typed files: CREATE-FILE ...). */
FBRL_API fbrl_cell fbrl_vmx_forth2012_wid(const fbrl_vm *vm);
/* Make new definitions go into word list wid (a wid from the VM); *previous: the one before. */
FBRL_API fbrl_status fbrl_vmx_set_current(fbrl_vm *vm, fbrl_cell wid, fbrl_cell *previous);

/* ---- the built-in word set ---- */

/* The data words (queues, arrays, strings, type sizes: thesis I-1 .. I-3), a word set as any
 * other: the engine installs none. fbrl_glossary_install() installs them first (the glossary
 * stands on them); a host without the glossary that wants them calls this once. */
FBRL_API fbrl_status fbrl_vmx_data_words(fbrl_vm *vm);

#ifdef __cplusplus
}
#endif
#endif
