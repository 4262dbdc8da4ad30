/* SPDX-License-Identifier: MIT */
/* step.c - the word hook (fbrl_vm_word_hook): a debugger's view of each word before it
 * runs, as gforth's dbg steps: inside a colon definition every word, built-ins, numbers
 * and control words included, named as the source wrote them (as SEE shows compiled code);
 * and each word the interpreter runs. run.c calls it through its dispatch table while the
 * hook is set; interp.c before it runs an interpreted word. */
#include <stdio.h>
#include <string.h>
#include "fbrl/num.h"
#include "words.h"

/* A superinstruction shows as the words it was compiled from; lit: a literal operand
 * follows the op, written where the words have # (first when they have none); br: a branch
 * target follows (after the literal), 1 shown as 0BRANCH, 2 a loop's (shown by nothing).
 * One table for SEE and the word hook. */
static const struct {
    int16_t op;
    uint8_t lit, br; /* a row is 8 bytes, not 12 */
    const char *words;
} fused[] = {
    {OP_LITPLUS, 1, 0, "+"},         {OP_LITMINUS, 1, 0, "-"},    {OP_LITSTAR, 1, 0, "*"},
    {OP_LITAND, 1, 0, "AND"},        {OP_LITEQ, 1, 0, "="},       {OP_LITNE, 1, 0, "<>"},
    {OP_LITLT, 1, 0, "<"},           {OP_LITGT, 1, 0, ">"},       {OP_LITFETCH, 1, 0, "@"},
    {OP_PICK2, 0, 0, "2 PICK"},      {OP_OVERPLUS, 0, 0, "OVER +"}, {OP_IPLUS, 0, 0, "I +"},
    {OP_CELLPLUSFETCH, 0, 0, "CELL+ @"}, {OP_DUPFETCH, 0, 0, "DUP @"}, {OP_EQZBR, 0, 1, "="},
    {OP_NEZBR, 0, 1, "<>"},          {OP_LTZBR, 0, 1, "<"},       {OP_GTZBR, 0, 1, ">"},
    {OP_ZEQZBR, 0, 1, "0="},         {OP_LITEQZBR, 1, 1, "="},    {OP_LITNEZBR, 1, 1, "<>"},
    {OP_LITLTZBR, 1, 1, "<"},        {OP_LITGTZBR, 1, 1, ">"},
    {OP_DUPLITEQZBR, 1, 1, "DUP # ="}, {OP_DUPLITNEZBR, 1, 1, "DUP # <>"}, {OP_DUPLITLTZBR, 1, 1, "DUP # <"},
    {OP_DUPLITGTZBR, 1, 1, "DUP # >"}, {OP_DROPLIT, 1, 0, "DROP #"},   {OP_IFETCH, 0, 0, "I @"},
    {OP_ICFETCH, 0, 0, "I C@"},      {OP_ITWOFETCH, 0, 0, "I 2@"},  {OP_ISTORE, 0, 0, "I !"},
    {OP_ICSTORE, 0, 0, "I C!"},      {OP_ITWOSTORE, 0, 0, "I 2!"},  {OP_LITPPLOOP, 1, 2, "+LOOP"},
    {OP_DUPPPLOOP, 0, 2, "DUP +LOOP"}, {OP_OVERFETCH, 0, 0, "OVER @"}, {OP_PICK2FETCH, 0, 0, "2 PICK @"},
    {OP_STARPLUS, 0, 0, "* +"},      {OP_TWODUPEQZBR, 0, 1, "2DUP ="}, {OP_TWODUPNEZBR, 0, 1, "2DUP <>"},
    {OP_TWODUPLTZBR, 0, 1, "2DUP <"}, {OP_TWODUPGTZBR, 0, 1, "2DUP >"}, {OP_LITPLUSFETCH, 1, 0, "+ @"},
    {OP_LITPLUSCFETCH, 1, 0, "+ C@"}, {OP_LITPLUSSTORE, 1, 0, "+ !"}, {OP_LITPLUSCSTORE, 1, 0, "+ C!"},
    {OP_ISTOF, 0, 0, "I S>F"},       {OP_FOVERFOVER, 0, 0, "FOVER FOVER"}, {OP_FDUPFSTAR, 0, 0, "FDUP F*"},
    {OP_IJ, 0, 0, "I J"},
};

const char *fbrl__fused_words(int op, int *lit, int *br)
{
    for (size_t i = 0; i < sizeof fused / sizeof fused[0]; i++)
        if (fused[i].op == op) {
            *lit = fused[i].lit;
            *br = fused[i].br;
            return fused[i].words;
        }
    return NULL;
}

/* The cell at p, or 0 when p is not readable. */
static fbrl_cell cell_at(const fbrl_vm *vm, const fbrl_cell *p)
{
    fbrl_cell v = 0;
    if (fbrl__addr_ok(vm, (fbrl_cell)p, CELL))
        memcpy(&v, (const void *)p, sizeof v);
    return v;
}

/* The variable or created word whose data is at v (compiled as a literal), or NULL. */
static const fbrl_hdr *data_word(const fbrl_vm *vm, fbrl_cell v)
{
    if (v < (fbrl_cell)vm->dict_lo || v >= (fbrl_cell)vm->here)
        return NULL; /* not the dictionary's data: a number */
    for (uint32_t i = vm->nwords; i-- > HDR_ROM;) {
        const fbrl_hdr *h = HDR(vm, i);
        if (h->body == v && (h->kind == K_VAR || h->kind == K_CREATE) && h->len)
            return h;
    }
    return NULL;
}

/* A literal as the source wrote it: a variable or created word compiles as its address,
 * so it shows as its name; else the number. Returns the length written. */
static size_t literal(const fbrl_vm *vm, fbrl_cell v, char *out, size_t cap)
{
    const fbrl_hdr *x = data_word(vm, v);
    fbrl_bt b;
    if (x)
        fbrl__add_name(x, &b);
    int n = x ? snprintf(out, cap, "%s", b.word) : snprintf(out, cap, "%ld", (long)v);
    return n < 0 ? 0 : (size_t)n < cap ? (size_t)n : cap - 1;
}

/* The word w (an op, ip: after it, at its operands; or an xt) as the source wrote it. h:
 * the colon definition it enters, when it is a call of one. */
static void name_word(fbrl_vm *vm, fbrl_cell w, const fbrl_cell *ip, const fbrl_hdr *in, char *out, size_t cap,
                      const fbrl_hdr **h)
{
    int lit, br;
    const char *text;
    fbrl_bt b;
    *h = NULL;
    if (w >= FBRL_XT_BASE) {
        const fbrl_hdr *x = fbrl__xt_hdr(vm, w);
        if (!x) {
            snprintf(out, cap, "?");
            return;
        }
        fbrl__add_name(x, &b);
        snprintf(out, cap, "%s", b.word);
        *h = x->kind == K_COLON ? x : NULL;
        return;
    }
    if ((text = fbrl__fused_words((int)w, &lit, &br)) != NULL) {
        const char *at = strchr(text, '#');
        size_t k = 0;
        if (at) { /* DUP # <: the words before the literal, the literal, the rest */
            k = (size_t)(at - text) < cap ? (size_t)(at - text) : cap - 1;
            memcpy(out, text, k);
            text = at + 1;
        }
        k += lit ? literal(vm, cell_at(vm, ip), out + k, cap - k) : 0;
        snprintf(out + k, cap - k, "%s%s", lit && !at ? " " : "", text);
        return;
    }
    switch (w) {
    case OP_LIT: literal(vm, cell_at(vm, ip), out, cap); return;
    case OP_FLIT: {
        double d = 0;
        if (fbrl__addr_ok(vm, (fbrl_cell)ip, (fbrl_cell)sizeof d))
            memcpy(&d, (const void *)ip, sizeof d);
        fbrl_num_general(out, cap > 1 ? cap - 1 : cap, d, 17, NULL); /* locale-free %.17g */
        strncat(out, "E", cap - strlen(out) - 1);
        return;
    }
    case OP_CALL:
        *h = fbrl__word_at(vm, cell_at(vm, ip));
        if (*h) {
            fbrl__add_name(*h, &b);
            snprintf(out, cap, "%s", b.word);
        } else {
            snprintf(out, cap, "?");
        }
        return;
    case OP_EXIT: /* the one ; compiled ends the definition */
        snprintf(out, cap, "%s", in && (fbrl_cell)ip == H_END(in) ? ";" : "EXIT");
        return;
    case OP_BRANCH:
    case OP_EXITBR: snprintf(out, cap, "BRANCH"); return; /* EXITBR: a BRANCH that lands on ; */
    case OP_ZBRANCH: snprintf(out, cap, "0BRANCH"); return;
    case OP_PDO: snprintf(out, cap, "DO"); return;
    case OP_PQDO: snprintf(out, cap, "?DO"); return;
    case OP_PLOOP: snprintf(out, cap, "LOOP"); return;
    case OP_PPLOOP: snprintf(out, cap, "+LOOP"); return;
    case OP_POF: snprintf(out, cap, "OF"); return;
    case OP_SLIT: snprintf(out, cap, "S\""); return;
    case OP_CSLIT: snprintf(out, cap, "C\""); return;
    case OP_PABORTQ: snprintf(out, cap, "ABORT\""); return;
    case OP_DOESSET: snprintf(out, cap, "DOES>"); return;
    case OP_PTOVAL:
    case OP_PTOFVAL:
    case OP_PTO2VAL: snprintf(out, cap, "TO"); return;
    default: snprintf(out, cap, "%s", fbrl__op_name((int)w)[0] ? fbrl__op_name((int)w) : "?"); return;
    }
}

static int call_hook(fbrl_vm *vm, fbrl_vm_stop *st)
{
    vm->in_step = 1;
    int r = vm->word_fn(vm->word_ctx, vm, st);
    vm->in_step = 0;
    return r;
}

int fbrl__step_word(fbrl_vm *vm, fbrl_cell w)
{
    const fbrl_cell *ip = vm->ip;
    char word[FBRL_NAME_MAX + 48];
    const fbrl_hdr *callee, *in;
    fbrl_bt caller = {"", 0, 0};
    fbrl_vm_stop st;
    if (w == OP_HALT || w == OP_CATCHEND || w == OP_BAD || w == OP_COMPSEM)
        return 0; /* the engine's own cells, no word of the source */
    in = fbrl__word_at(vm, (fbrl_cell)ip - CELL);
    name_word(vm, w, ip, in, word, sizeof word, &callee);
    if (in) {
        fbrl__add_name(in, &caller);
        fbrl__line_at(vm, in, (fbrl_cell)ip - CELL, &caller);
    }
    st.word = word;
    st.file = callee ? fbrl__file_name(vm, HDR_FILE(callee)) : "";
    st.line = callee ? HDR_LINE(callee) : 0;
    st.caller = caller.word;
    st.call_file = fbrl__file_name(vm, caller.file);
    st.call_line = caller.line;
    st.depth = (size_t)fbrl__frames(vm);
    return call_hook(vm, &st);
}

int fbrl__step_top(fbrl_vm *vm, fbrl_cell xt)
{
    const fbrl_hdr *h = fbrl__xt_hdr(vm, xt);
    uint32_t file, line;
    fbrl_bt b;
    fbrl_vm_stop st;
    if (!vm->word_fn || vm->in_step || !h)
        return 0;
    fbrl__add_name(h, &b);
    fbrl__position(vm, &file, &line);
    st.word = b.word;
    st.file = h->kind == K_COLON ? fbrl__file_name(vm, HDR_FILE(h)) : "";
    st.line = h->kind == K_COLON ? HDR_LINE(h) : 0;
    st.caller = "";
    st.call_file = fbrl__file_name(vm, file);
    st.call_line = line;
    st.depth = (size_t)fbrl__frames(vm);
    return call_hook(vm, &st);
}

fbrl_status fbrl_vm_word_hook(fbrl_vm *vm, fbrl_vm_step_fn fn, void *ctx)
{
    if (!vm)
        return FBRL_EINVAL;
    if (!FBRL_WORD_HOOK)
        return FBRL_EUNSUPPORTED; /* built without it (FBRL_NO_WORD_HOOK) */
    vm->word_fn = fn;
    vm->word_ctx = fn ? ctx : NULL;
    return FBRL_OK;
}
