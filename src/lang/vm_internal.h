/* SPDX-License-Identifier: MIT */
/* vm_internal.h - the FBRL engine's private structures (not installed).
 *
 * Memory layout of one VM, all inside the caller's block:
 *
 *   [struct fbrl_vm][data stack][return stack][float stack]
 *   [data region: system variables, buffers, dictionary --> HERE ... <-- word headers][guard]
 *
 * The data region is the only memory Forth code can address: every @ ! C@ MOVE ...
 * is checked against [data_lo, hdr_lo). Word headers (names, kinds, C pointers)
 * grow down from the guard and are never addressable, so a program cannot corrupt
 * them. Threaded code lives in the data region; the inner interpreter validates
 * every non-sequential change of the instruction pointer, and the guard cells at
 * the very end stop a sequential run-off. */
#ifndef FBRL_LANG_VM_INTERNAL_H
#define FBRL_LANG_VM_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "atomic.h"

#define CELL      ((fbrl_cell)sizeof(fbrl_cell))
#define CELL_BITS ((int)(sizeof(fbrl_cell) * 8))

/* Sizes a small target may set lower on the compiler's command line (the Cortex-M3
 * firmware does: ports/cortex-m3/CMakeLists.txt, docs/firmware.md). */
#ifndef FBRL_NAME_MAX
#define FBRL_NAME_MAX FBRL_VMX_NAME_MAX /* longest word name (as F-PC) */
#endif
#ifndef FBRL_LINE_MAX
#define FBRL_LINE_MAX 1024 /* longest source line */
#endif
#ifndef FBRL_SRC_MAX
#define FBRL_SRC_MAX 10 /* nested input sources (files, texts, EVALUATE) */
#endif
#define FBRL_CF_MAX 64 /* control-flow stack entries */
#ifndef FBRL_PATH_MAX
#define FBRL_PATH_MAX 256
#endif
#ifndef FBRL_REQ_POOL
#define FBRL_REQ_POOL 4096 /* bytes for REQUIRE's list of included files */
#endif
#define FBRL_GUARD_CELLS 8
#define FBRL_XT_BASE     4096 /* execution tokens are FBRL_XT_BASE + header index */
#ifndef FBRL_WL_MAX
#define FBRL_WL_MAX      32   /* word lists (wordlist.c); a wid is its index + 1 */
#endif
#ifndef FBRL_ORDER_MAX
#define FBRL_ORDER_MAX   16   /* word lists in the search order */
#endif
#ifndef FBRL_LOCALS_MAX
#define FBRL_LOCALS_MAX  512  /* cells of the locals stack (locals.c) */
#endif
#define FBRL_NLOCALS     32   /* locals of one definition */
#ifndef FBRL_FILES_MAX
#define FBRL_FILES_MAX   16   /* files open at once through the standard FILE words */
#endif

/* Sizes of the buffers at the start of the data region. */
#define FBRL_WORDBUF  260
#define FBRL_PADSIZE  256
#define FBRL_HOLDSIZE 260
#define FBRL_SBUF     256 /* each interpretation-state S" buffer */
#ifndef FBRL_NSBUF
#define FBRL_NSBUF 8 /* S" buffers in rotation (the standard asks for 2) */
#endif

enum {
#define OP(id, name, flags, stack, help) OP_##id,
#include "ops.def"
#undef OP
    OP__END
};

/* word kinds */
enum {
    K_PRIM,
    K_COLON,
    K_VAR,
    K_CREATE,
    K_CONST,
    K_2CONST,
    K_FCONST,
    K_VALUE,
    K_2VALUE,
    K_FVALUE,
    K_DEFER,
    K_CFUNC,
    K_MARKER
};
/* header flags */
#define FI 1u /* immediate */
#define FC 2u /* compile-only */
#define FH 4u /* hidden (being defined, or :NONAME) */
#define FS 8u /* state-smart immediate word (POSTPONE runs it compiling) */

/* FBRL_SMALL_HEADERS: a header of 32 bytes (on a 32-bit target), as its chain links are
 * 16 bits (at most FBRL_WORDS_MAX words), it keeps no hash (dict.c computes it from the
 * name), points at its name and keeps no source position. */
#ifdef FBRL_SMALL_HEADERS
typedef uint16_t fbrl_hlink;
#define FBRL_WORDS_MAX UINT16_MAX
#else
typedef uint32_t fbrl_hlink;
#define FBRL_WORDS_MAX UINT32_MAX
#endif
typedef struct fbrl_hdr {
    fbrl_hlink next; /* next header in the hash chain, as index+1 (0 = end) */
#ifndef FBRL_SMALL_HEADERS
    uint32_t hash; /* its name's hash (dict.c; compared before the name, so beside next) */
#endif
    fbrl_hlink head; /* the dictionary index (dict.c): the first header of the bucket whose
                        number is this header's place among the RAM headers, index+1 */
    uint8_t kind, flags, len;
    uint8_t wl; /* its word list (wordlist.c): 0 = FORTH-WORDLIST */
#ifdef FBRL_SMALL_HEADERS
    const char *name; /* len bytes, not NUL-terminated (dict.c new_header_at) */
#else
    char name[FBRL_NAME_MAX + 1];
#endif
    fbrl_cell body; /* data field / colon body (a data-region address) */
    /* the fields by kind never meet in one word, so they share the room (read through
     * H_END ... H_OP): end (K_COLON: end of the code, for SEE; K_MARKER: the saved word
     * count), does (K_CREATE with DOES>: its code; K_MARKER: the saved REQUIRE pool use);
     * fn, arg, xfn (K_CFUNC; xfn, from vmx.h, is called instead of fn); op (K_PRIM) */
    union {
        struct {
            fbrl_cell end, does;
        } code;
        struct {
            fbrl_vm_prim fn;
            void *arg;
            fbrl_vmx_fn xfn;
        } c;
        uint16_t op;
    } u;
#ifndef FBRL_SMALL_HEADERS
    uint32_t file, line; /* where it was defined: req_pool offset + 1 (0: not a file), line */
#endif
    const void *word; /* its word pointer */
#ifndef FBRL_NO_HELP
    const char *stack, *help; /* HELP text (NUL-terminated) */
#endif
} fbrl_hdr;

#define H_END(h)  ((h)->u.code.end)
#define H_DOES(h) ((h)->u.code.does)
#define H_FN(h)   ((h)->u.c.fn)
#define H_ARG(h)  ((h)->u.c.arg)
#define H_XFN(h)  ((h)->u.c.xfn)
#define H_OP(h)   ((h)->u.op)

/* Where a word was defined; FBRL_SMALL_HEADERS keeps no place (the small targets read no
 * source files): file 0, line 0. */
#ifdef FBRL_SMALL_HEADERS
#define HDR_FILE(h) ((void)(h), 0u)
#define HDR_LINE(h) ((void)(h), 0u)
#else
#define HDR_FILE(h) ((h)->file)
#define HDR_LINE(h) ((h)->line)
#endif

enum { SRC_TEXT, SRC_FILE, SRC_STRING };

typedef struct fbrl_src {
    int kind;
    char *buf; /* current line (data region) */
    size_t len;
    char *linebuf;               /* SRC_TEXT/SRC_FILE: this level's line buffer */
    const char *text, *text_end; /* SRC_TEXT: text not yet read */
    void *fh;                    /* SRC_FILE: host handle */
    unsigned long line;
    fbrl_cell id;             /* SOURCE-ID */
    fbrl_cell saved_in;       /* the parent's >IN */
    char path[FBRL_PATH_MAX]; /* SRC_FILE: the file's path */
    uint32_t file;            /* SRC_FILE: the path's req_pool offset + 1 (debug.c) */
} fbrl_src;

/* Where compiled code came from (debug.c): one entry each time compilation moves to a
 * new source line, in the order of the code addresses. A port short of RAM may shrink it;
 * when it is full, later lines fall back to the line their word was defined on. */
#ifndef FBRL_LINE_TABLE
#define FBRL_LINE_TABLE 1024
#endif
#define FBRL_BT_MAX   FBRL_VM_BACKTRACE_MAX
#define FBRL_BT_OUTER FBRL_VM_BACKTRACE_OUTER
#define FBRL_BT_STACK FBRL_VM_BACKTRACE_STACK
typedef struct fbrl_line {
    fbrl_cell addr;
    uint32_t file, line;
} fbrl_line;
typedef struct fbrl_bt {
    char word[FBRL_NAME_MAX + 1];
    uint32_t file, line;
} fbrl_bt;

enum { CF_COLON = 1, CF_ORIG, CF_DEST, CF_DO, CF_CASE, CF_OF, CF_ENDOF };

typedef struct fbrl_cf {
    int tag;
    fbrl_cell a;
} fbrl_cf;

/* THROW codes the engine uses internally to unwind without being catchable. */
#define THROW_BYE  (-100000)
#define THROW_QUIT (FBRL_THROW_QUIT)
/* task.c: a waiting word in a background task gives up the processor (the word runs
 * again when the task resumes); STOP of the running task ends it. Neither is catchable. */
#define THROW_YIELD (-100001)
#define THROW_STOP  (-100002)
/* A fbrl_status returned by a C word becomes THROW code FBRL_THROW_STATUS(st). */
#define FBRL_THROW_STATUS(st) FBRL_VM_THROW_OF_STATUS(st)

/* Cooperative tasks (task.c, docs/tasks.md). Slot 0 is the main task: whatever
 * fbrl_vm_eval() runs, on the caller's C stack, whose waits run the other tasks in
 * place. Every other task runs in slices: fbrl__run from its saved ip with its own stacks
 * (in data space), until a waiting word yields (THROW_YIELD) or the word ends. The record
 * lives here, outside data space, so a program cannot corrupt its pointers. */
#ifndef FBRL_TASKS_MAX
#define FBRL_TASKS_MAX    16
#endif
#define FBRL_TASK_NEVER   UINT64_MAX /* a wait with no deadline: only another task's signal ends it */
#ifndef FBRL_CLAIMS_MAX
#define FBRL_CLAIMS_MAX   16
#endif
enum { TK_FREE, TK_IDLE, TK_READY, TK_WAIT, TK_RUN, TK_DONE, TK_FAILED, TK_STOPPED };
typedef struct fbrl_task {
    uint32_t word; /* header index + 1 of its TASK word (0: a free slot; slot 0: main) */
    int state;
    fbrl_cell *ds0, *ds_end, *sp, *rs0, *rs_end, *rp;
    double *fs0, *fs_end, *fp;
    fbrl_cell handler;
    const fbrl_cell *ip; /* where it resumes, and the word it runs again (w) first */
    fbrl_cell w;
    uint64_t wake_us;      /* TK_WAIT: run again at or after this host time */
    unsigned char *mem_lo; /* its stacks' memory in data space (dropped if forgotten) */
    int resuming;          /* its slice ended in a wait: the word runs again, its record kept */
    int on_signal;         /* TK_WAIT: another task's signal (an end, a release) makes it due */
    int stop_req;          /* STOP while it waits in place: it ends when it gets back */
    fbrl_vmx_wait wait;
    fbrl_vmx_timer timer;
    /* timed steps: the task's clock origin, EVERY's next due time, lateness */
    uint64_t origin_us, every_due_us;
    unsigned long steps, missed;
    uint64_t late_max_us, late_sum_us;
    int code; /* TK_FAILED: its throw code */
    char msg[96];
} fbrl_task;
typedef struct fbrl_claim {
    fbrl_cell key;                 /* what is claimed (0: a free entry) */
    int owner;                     /* task slot, -1 none */
    int depth;                     /* nested claims by the owner */
    int queue[FBRL_TASKS_MAX], nq; /* waiting tasks, in order */
} fbrl_claim;

struct fbrl_vm {
    fbrl_vm_host host;
    unsigned char *mem_end;
    /* stacks: sp/rp point at the next free slot */
    fbrl_cell *ds0, *ds_end, *sp;
    fbrl_cell *rs0, *rs_end, *rp;
    double *fs0, *fs_end, *fp;
    /* data region */
    unsigned char *data_lo; /* first addressable byte */
    unsigned char *dict_lo; /* first dictionary byte (MARKER cannot go below) */
    unsigned char *here;
    fbrl_hdr *hdr_top;      /* header i is hdr_top[-1 - i] */
    unsigned char *data_hi; /* end of the addressable region = lowest header */
    uint32_t nwords;
    uint32_t nbuckets; /* the dictionary index's buckets (dict.c): 0, or a power of two */
    fbrl_cell *base, *state, *toin; /* system variables in the data region */
    char *wordbuf, *pad, *hold, *sbuf;
    char *hld; /* pictured output: next free position (moves down) */
    int sbuf_next;
    /* compilation */
    fbrl_cf cf[FBRL_CF_MAX];
    int ncf;
    int defining;            /* a definition is open */
    uint32_t def_word;       /* its header index */
    unsigned char *def_here; /* HERE before it started */
    uint32_t def_nwords;
    /* input sources */
    fbrl_src src[FBRL_SRC_MAX];
    int nsrc;
    int nest;          /* nested run() calls */
    fbrl_cell handler; /* return-stack depth of the innermost CATCH frame, 0 = none */
    /* errors */
    int pending_throw;
    const char *pending_msg;
    int pending_code;    /* the code pending_msg belongs to */
    char throw_msg[256]; /* ABORT" text, or a C word's message (a controller error with its meaning) */
    int err_captured;
    char cur_word[64];
    fbrl_vm_error err;
    int bye;
    size_t interrupt; /* attention bits FBRL_ATTN_* (atomic access only) */
    int running;      /* inside fbrl_vm_eval/include */
    int precision;
    char req_pool[FBRL_REQ_POOL];
    size_t req_used;
    fbrl_cell guard_addr;    /* address of the guard cells (HALT, CATCHEND, BAD...) */
    unsigned char *peep;     /* last instruction the compiler may fuse with (dict.c) */
    unsigned char *peep_end; /* HERE right after it; NULL: no fusion */
    unsigned char *peep_prev; /* the instruction right before peep, NULL: none to fuse with */
    /* words.c: the open definition's forward BRANCHes (ELSE, AHEAD, ENDOF; the last few),
     * and those resolved to exit_here: ; makes them EXITBR when its EXIT lands there */
    fbrl_cell br_orig[8], exit_orig[8];
    unsigned nbr_orig, nexit_orig;
    unsigned char *exit_here;
    int run_code;            /* run.c: the code of an error exit */
    const fbrl_cell *ip;     /* run.c: the instruction pointer while a C word or step hook runs */
    fbrl_vm_step_fn step_fn; /* fbrl_vm_step_hook (debug.c) */
    void *step_ctx;
    fbrl_vm_step_fn word_fn; /* fbrl_vm_word_hook (debug.c): before each word */
    void *word_ctx;
    int in_step; /* inside step_fn or word_fn: what it evaluates runs without stops */
    fbrl_bt where; /* fbrl_vm_where's answer */
    fbrl_line lines[FBRL_LINE_TABLE];
    uint32_t nlines;
    fbrl_bt bt[FBRL_BT_MAX]; /* the last error's chain of words, innermost first */
    uint32_t nbt, bt_omitted;
    int bt_captured;
    fbrl_cell bt_stack[FBRL_BT_STACK]; /* its data stack: the top cells, deepest first */
    size_t bt_depth;
    const struct fbrl_hdr *cword; /* the C word last called (names it in vmx.c's errors) */
    /* word lists and the search order (wordlist.c): find() takes the newest word of the
     * name in the earliest word list of order[0..norder) */
    uint8_t order[FBRL_ORDER_MAX];
    int norder;
    uint8_t current;      /* the compilation word list */
    uint8_t nwl;          /* word lists made */
    uint8_t wl_forth2012; /* the standard words FBRL's word sets shadow (FORTH-2012) */
    const char *wl_name[FBRL_WL_MAX];
    /* locals (locals.c): the frames of running definitions (not addressable), and the
     * names of the definition being compiled */
    fbrl_cell locals[FBRL_LOCALS_MAX];
    fbrl_cell lp;       /* cells in use; a CATCH frame keeps it */
    int nlocals;        /* locals of the open definition (0: none) */
    int lpend;          /* (LOCAL) declarations not yet ended */
    fbrl_cell lexit_xt; /* (LOCALS-EXIT): compiled before EXIT and ; when nlocals */
    char lname[FBRL_NLOCALS][FBRL_NAME_MAX + 1];
    uint8_t llen[FBRL_NLOCALS];
    /* ALLOCATE's heap (heap.c): [heap_lo, heap_hi) inside the data region */
    unsigned char *heap_lo, *heap_hi;
    fbrl_cell subst; /* strings.c: REPLACES's first entry (a heap block), 0 = none */
    /* file.c: the standard FILE words' open files (host handles, not addressable);
     * a fileid is the slot's number + 1 */
    void *file_h[FBRL_FILES_MAX];
    char file_path[FBRL_FILES_MAX][FBRL_PATH_MAX];
    /* The text interpreter (interp.c) nested from below: EVALUATE, INCLUDED, INCLUDE and
     * REQUIRE run in run.c and words.c, which interp.c itself calls. fbrl_vm_create sets
     * these, so the files depend one way only: interp.c -> run.c -> words.c -> dict.c. */
    int (*nest_evaluate)(fbrl_vm *vm, char *text, size_t len);
    int (*nest_included)(fbrl_vm *vm, const char *name, size_t n, int require);
    /* tasks (task.c); words.c waits through task_pause (set by fbrl_vm_create) */
    fbrl_task tasks[FBRL_TASKS_MAX];
    fbrl_claim claims[FBRL_CLAIMS_MAX];
    int cur_task;               /* the task whose stacks are in sp/rp/fp */
    int ntasks;                 /* background tasks started and not yet ended */
    int slice_nest;             /* nest of the running slice's fbrl__run (-1: main) */
    int resuming; /* the word about to run is a waiting word run again (cleared after a C word) */
    const fbrl_cell *resume_ip; /* set before fbrl__run resumes a task */
    const fbrl_cell *resume_at; /* set by fbrl__run when a slice yields: ip and the word */
    fbrl_cell resume_w;
    /* wait until wake_us, letting the other tasks run; on_signal: or until another task ends
     * or releases a claim (the caller looks at its condition again) */
    int (*task_pause)(fbrl_vm *vm, uint64_t wake_us, int on_signal);
    unsigned long task_signals; /* counts those signals (task.c) */
};

/* Header i. FBRL_ROM_PRIMS (a small target short of RAM: the Cortex-M3 firmware): the
 * primitives' headers stay in flash, as a const table of 4 bytes a primitive (its name's
 * place in one block of names, its flags and length; indices 0 .. OP__END-1, an internal
 * op's nameless and hidden); RAM holds only the other words' headers, which follow them.
 * A full header for a primitive is made when asked for (dict.c fbrl__rom_hdr), in a ring
 * of FBRL_ROM_VIEWS, so a pointer to one stays good until that many more are made: every
 * user takes one, reads it and lets it go. Nothing writes a primitive's header. The
 * primitives are in no hash chain: fbrl__find looks them up by name after the RAM words,
 * which are all newer. */
#ifdef FBRL_ROM_PRIMS
#ifndef FBRL_SMALL_HEADERS
#error "FBRL_ROM_PRIMS needs FBRL_SMALL_HEADERS (a header points at its name)"
#endif
#define FBRL_ROM_VIEWS 4
fbrl_hdr *fbrl__rom_hdr(uint32_t op);
#define HDR_ROM ((uint32_t)OP__END)
#define HDR(vm, i)                                                  \
    ((uint32_t)(i) < HDR_ROM ? fbrl__rom_hdr((uint32_t)(i))         \
                             : (vm)->hdr_top - 1 - ((ptrdiff_t)(i) - (ptrdiff_t)HDR_ROM))
#else
#define HDR_ROM 0u
#define HDR(vm, i) ((vm)->hdr_top - 1 - (ptrdiff_t)(i))
#endif
/* The lowest header in RAM (the end of the addressable data region). */
#define HDR_LOW(vm) ((vm)->hdr_top - ((vm)->nwords - HDR_ROM))
/* The index of header h (its xt is FBRL_XT_BASE + the index). */
uint32_t fbrl__hdr_index(const fbrl_vm *vm, const fbrl_hdr *h);

/* True if [a, a+n) lies inside the VM's addressable data region. */
static inline int fbrl__addr_ok(const fbrl_vm *vm, fbrl_cell a, fbrl_cell n)
{
    fbrl_ucell size = (fbrl_ucell)(vm->data_hi - vm->data_lo);
    fbrl_ucell off = (fbrl_ucell)a - (fbrl_ucell)vm->data_lo;
    return (fbrl_ucell)n <= size && off <= size - (fbrl_ucell)n;
}

/* run.c: execute one xt (the inner interpreter) */
int fbrl__run(fbrl_vm *vm, fbrl_cell xt);

/* vm->interrupt: the inner interpreter's one check at calls and loops (nonzero: look). */
#define FBRL_ATTN_INTERRUPT 1u /* fbrl_vm_interrupt() was called */
#define FBRL_ATTN_STEP      2u /* a step hook wants each colon definition's start */

/* 1 (and cleared) if fbrl_vm_interrupt() was called */
static inline int fbrl__take_interrupt(fbrl_vm *vm)
{
    size_t v = fbrl_load_rlx(&vm->interrupt);
    if (!(v & FBRL_ATTN_INTERRUPT))
        return 0;
    fbrl_store_rlx(&vm->interrupt, v & ~(size_t)FBRL_ATTN_INTERRUPT);
    return 1;
}

/* errors.c */
int fbrl__throw_msg(fbrl_vm *vm, int code, const char *msg);
const char *fbrl__throw_text(int code);

/* dict.c */
fbrl_hdr *fbrl__xt_hdr(const fbrl_vm *vm, fbrl_cell xt);
int fbrl__find(const fbrl_vm *vm, const char *name, size_t len);

/* io.c */
void fbrl__write(fbrl_vm *vm, const char *s, size_t n);
void fbrl__puts(fbrl_vm *vm, const char *s);

/* debug.c: where code came from */
void fbrl__note_line(fbrl_vm *vm);                      /* before compiling from the current line */
void fbrl__note_header(fbrl_vm *vm, fbrl_hdr *h);       /* a new word: its file and line */
void fbrl__lines_forget(fbrl_vm *vm);                   /* code above HERE is gone */
void fbrl__backtrace(fbrl_vm *vm, const fbrl_cell *ip); /* at a throw: keep the chain of words */
void fbrl__position(const fbrl_vm *vm, uint32_t *file, uint32_t *line); /* compiling/interpreting */
const fbrl_hdr *fbrl__word_at(const fbrl_vm *vm, fbrl_cell addr);       /* colon def holding addr */
void fbrl__line_at(const fbrl_vm *vm, const fbrl_hdr *h, fbrl_cell addr, fbrl_bt *f);
void fbrl__add_name(const fbrl_hdr *h, fbrl_bt *f);
int fbrl__frames(const fbrl_vm *vm); /* colon definitions running (return addresses kept) */
int fbrl__step(fbrl_vm *vm, fbrl_cell body); /* a colon definition starts: the step hook (vm->ip: the call) */
/* FBRL_NO_WORD_HOOK (a small target without a debugger, the firmware): fbrl_vm_word_hook
 * is refused and the inner interpreter has no step test at all. */
#ifdef FBRL_NO_WORD_HOOK
#define FBRL_WORD_HOOK 0
#else
#define FBRL_WORD_HOOK 1
#endif
int fbrl__step_word(fbrl_vm *vm, fbrl_cell w); /* a word of a definition: the word hook (vm->ip: after w) */
int fbrl__step_top(fbrl_vm *vm, fbrl_cell xt); /* the interpreter runs xt: the word hook */
/* The words a superinstruction was compiled from ("+" of a literal and +), whether a
 * literal and a branch target follow the op; NULL for an op that is no superinstruction
 * (SEE and the word hook show them so). */
const char *fbrl__fused_words(int op, int *lit, int *br);
const char *fbrl__file_name(const fbrl_vm *vm, uint32_t file);

/* number.c: the text interpreter's number syntax: 1 single, 2 double (v[0] low, v[1] high),
 * 3 float (*f); 0 not a number. */
int fbrl__parse_number(fbrl_vm *vm, const char *s, size_t n, fbrl_cell v[2], double *f);

/* The waiting word's record (vmx.h): kept when the word runs again after a yield. */
static inline fbrl_vmx_wait *fbrl__wait_begin(fbrl_vm *vm)
{
    fbrl_task *t = &vm->tasks[vm->cur_task];
    if (vm->resuming) {
        vm->resuming = 0;
        t->wait.resumed = 1;
        return &t->wait;
    }
    memset(&t->wait, 0, sizeof t->wait);
    t->wait.since_us = vm->host.now_us ? vm->host.now_us(vm->host.user) : 0;
    return &t->wait;
}

/* task.c */
int fbrl__task_words(fbrl_vm *vm);

/* prelude.c */
extern const char fbrl__prelude[];

#endif
