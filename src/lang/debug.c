/* SPDX-License-Identifier: MIT */
/* debug.c - where code came from: each word's file and line, a table from compiled
 * code addresses to source lines, and the chain of words (backtrace) kept when an
 * error is thrown, so a failure names the word it happened in and the calls that led
 * there. Only plain data is read here (no calls into the dictionary or the
 * interpreters), so every other engine file may call it. */
#include <string.h>
#include "words.h"

/* The source position compilation is at: the innermost file or typed text; an
 * EVALUATEd string counts as the line that evaluated it. */
void fbrl__position(const fbrl_vm *vm, uint32_t *file, uint32_t *line)
{
    *file = 0;
    *line = 0;
    for (int i = vm->nsrc - 1; i >= 0; i--) {
        const fbrl_src *s = &vm->src[i];
        if (s->kind == SRC_STRING)
            continue;
        *file = s->kind == SRC_FILE ? s->file : 0;
        *line = (uint32_t)s->line;
        return;
    }
}

void fbrl__note_header(fbrl_vm *vm, fbrl_hdr *h)
{
#ifdef FBRL_SMALL_HEADERS
    (void)vm, (void)h;
#else
    fbrl__position(vm, &h->file, &h->line);
#endif
}

void fbrl__note_line(fbrl_vm *vm)
{
    uint32_t file, line;
    fbrl__position(vm, &file, &line);
    fbrl_cell here = (fbrl_cell)vm->here;
    if (vm->nlines > 0) {
        fbrl_line *last = &vm->lines[vm->nlines - 1];
        if (last->file == file && last->line == line && last->addr <= here)
            return;
        if (last->addr >= here) { /* nothing compiled since: the new line owns this address */
            last->addr = here;
            last->file = file;
            last->line = line;
            return;
        }
    }
    if (vm->nlines >= FBRL_LINE_TABLE)
        return;
    vm->lines[vm->nlines].addr = here;
    vm->lines[vm->nlines].file = file;
    vm->lines[vm->nlines].line = line;
    vm->nlines++;
}

void fbrl__lines_forget(fbrl_vm *vm)
{
    while (vm->nlines > 0 && vm->lines[vm->nlines - 1].addr >= (fbrl_cell)vm->here)
        vm->nlines--;
}

const char *fbrl__file_name(const fbrl_vm *vm, uint32_t file)
{
    return file > 0 && file <= vm->req_used ? vm->req_pool + file - 1 : "";
}

/* The colon definition whose code holds addr, or NULL. */
const fbrl_hdr *fbrl__word_at(const fbrl_vm *vm, fbrl_cell addr)
{
    for (uint32_t i = vm->nwords; i-- > 0;) {
        const fbrl_hdr *h = HDR(vm, i);
        fbrl_cell end = H_END(h) ? H_END(h) : (fbrl_cell)vm->here; /* still being defined */
        if (h->kind == K_COLON && h->body <= addr && addr < end)
            return h;
    }
    return NULL;
}

/* The source line of the code at addr inside h: the last line noted at or before it. */
void fbrl__line_at(const fbrl_vm *vm, const fbrl_hdr *h, fbrl_cell addr, fbrl_bt *f)
{
    f->file = HDR_FILE(h);
    f->line = HDR_LINE(h);
    uint32_t lo = 0, hi = vm->nlines;
    while (lo < hi) { /* the first entry above addr */
        uint32_t mid = lo + (hi - lo) / 2;
        if (vm->lines[mid].addr <= addr)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo > 0 && vm->lines[lo - 1].addr >= h->body) {
        f->file = vm->lines[lo - 1].file;
        f->line = vm->lines[lo - 1].line;
    }
}

void fbrl__add_name(const fbrl_hdr *h, fbrl_bt *f)
{
    memcpy(f->word, h->name, h->len);
    f->word[h->len] = 0;
    if (!h->len)
        memcpy(f->word, ":NONAME", sizeof ":NONAME");
}

static void add_frame(fbrl_vm *vm, const fbrl_hdr *h, fbrl_cell addr)
{
    fbrl_bt f;
    fbrl__add_name(h, &f);
    fbrl__line_at(vm, h, addr, &f);
    if (vm->nbt < FBRL_BT_MAX) {
        vm->bt[vm->nbt++] = f;
        return;
    }
    /* Full: keep the innermost frames and the outermost FBRL_BT_OUTER, drop the middle. */
    memmove(&vm->bt[FBRL_BT_MAX - FBRL_BT_OUTER], &vm->bt[FBRL_BT_MAX - FBRL_BT_OUTER + 1],
            (FBRL_BT_OUTER - 1) * sizeof f);
    vm->bt[FBRL_BT_MAX - 1] = f;
    vm->bt_omitted++;
}

/* True if ra is where a call returns to: just after OP_CALL body, after an xt (a word
 * with DOES>, a deferred call), or after EXECUTE / CATCH. */
static int is_return(const fbrl_vm *vm, fbrl_cell ra)
{
    if (ra % CELL != 0 || !fbrl__addr_ok(vm, ra - 2 * CELL, 2 * CELL))
        return 0;
    const fbrl_cell *c = (const fbrl_cell *)ra;
    fbrl_ucell xt = (fbrl_ucell)c[-1] - FBRL_XT_BASE;
    return c[-2] == OP_CALL || xt < vm->nwords || c[-1] == OP_EXECUTE || c[-1] == OP_CATCH;
}

int fbrl__frames(const fbrl_vm *vm)
{
    int n = 0;
    for (const fbrl_cell *r = vm->rs0; r < vm->rp; r++)
        n += is_return(vm, *r) || *r == vm->guard_addr || *r == vm->guard_addr + CELL;
    return n;
}

/* ip: just after the instruction that threw (inside the innermost word). The return
 * stack below vm->rp holds the callers' return addresses among loop parameters and >R
 * values: a cell counts when it is a return address into a colon definition. */
void fbrl__backtrace(fbrl_vm *vm, const fbrl_cell *ip)
{
    vm->bt_captured = 1;
    vm->nbt = 0;
    vm->bt_omitted = 0;
    const fbrl_hdr *h = fbrl__word_at(vm, (fbrl_cell)ip - CELL);
    if (h)
        add_frame(vm, h, (fbrl_cell)ip - CELL);
    for (const fbrl_cell *r = vm->rp; r-- > vm->rs0;) {
        fbrl_cell ra = *r;
        if (!is_return(vm, ra) || (h = fbrl__word_at(vm, ra - CELL)) == NULL)
            continue;
        add_frame(vm, h, ra - CELL);
    }
    size_t depth = vm->sp > vm->ds0 ? (size_t)(vm->sp - vm->ds0) : 0;
    size_t keep = depth < FBRL_BT_STACK ? depth : FBRL_BT_STACK;
    vm->bt_depth = depth;
    memcpy(vm->bt_stack, vm->sp - keep, keep * sizeof(fbrl_cell));
}

size_t fbrl_vm_backtrace(const fbrl_vm *vm, fbrl_vm_frame *out, size_t cap, size_t *omitted)
{
    if (omitted)
        *omitted = vm ? vm->bt_omitted : 0;
    if (!vm)
        return 0;
    for (size_t i = 0; out && i < cap && i < vm->nbt; i++) {
        out[i].word = vm->bt[i].word;
        out[i].file = fbrl__file_name(vm, vm->bt[i].file);
        out[i].line = vm->bt[i].line;
    }
    return vm->nbt;
}

size_t fbrl_vm_error_stack(const fbrl_vm *vm, fbrl_cell *out, size_t cap)
{
    if (!vm)
        return 0;
    size_t kept = vm->bt_depth < FBRL_BT_STACK ? vm->bt_depth : FBRL_BT_STACK;
    size_t n = cap < kept ? cap : kept;
    if (out && n)
        memcpy(out, vm->bt_stack + (kept - n), n * sizeof(fbrl_cell));
    return vm->bt_depth;
}

fbrl_status fbrl_vm_step_hook(fbrl_vm *vm, fbrl_vm_step_fn fn, void *ctx)
{
    if (!vm)
        return FBRL_EINVAL;
    vm->step_fn = fn;
    vm->step_ctx = ctx;
    size_t v = fbrl_load_rlx(&vm->interrupt);
    fbrl_store_rlx(&vm->interrupt, fn ? v | FBRL_ATTN_STEP : v & ~(size_t)FBRL_ATTN_STEP);
    return FBRL_OK;
}

int fbrl__step(fbrl_vm *vm, fbrl_cell body)
{
    const fbrl_hdr *h = fbrl__word_at(vm, body);
    fbrl_bt callee = {"", 0, 0}, caller = {"", 0, 0};
    fbrl_vm_stop st;
    if (h)
        fbrl__add_name(h, &callee);
    st.word = callee.word;
    st.file = h ? fbrl__file_name(vm, HDR_FILE(h)) : "";
    st.line = h ? HDR_LINE(h) : 0;
    /* vm->ip: just after the call (OP_CALL body, or EXECUTE's cell) */
    const fbrl_hdr *c = fbrl__word_at(vm, (fbrl_cell)vm->ip - CELL);
    if (c) {
        fbrl__add_name(c, &caller);
        fbrl__line_at(vm, c, (fbrl_cell)vm->ip - CELL, &caller);
    }
    st.caller = caller.word;
    st.call_file = fbrl__file_name(vm, caller.file);
    st.call_line = caller.line;
    st.depth = (size_t)fbrl__frames(vm) + 1; /* as the definition's own words will see it */
    vm->in_step = 1;
    int r = vm->step_fn(vm->step_ctx, vm, &st);
    vm->in_step = 0;
    return r;
}

fbrl_status fbrl_vm_where(fbrl_vm *vm, const char **word, const char **file, unsigned long *line)
{
    if (!vm || !word || !file || !line)
        return FBRL_EINVAL;
    fbrl_bt here; /* copied to vm->where: the name outlives the call */
    uint32_t f = 0, l = 0;
    here.word[0] = 0;
    const fbrl_hdr *h = vm->running && vm->ip ? fbrl__word_at(vm, (fbrl_cell)vm->ip - CELL) : NULL;
    if (h) {
        fbrl__add_name(h, &here);
        fbrl__line_at(vm, h, (fbrl_cell)vm->ip - CELL, &here);
        f = here.file;
        l = here.line;
    } else if (vm->running) {
        fbrl__position(vm, &f, &l);
    }
    vm->where = here;
    *word = vm->where.word;
    *file = fbrl__file_name(vm, f);
    *line = l;
    return FBRL_OK;
}
