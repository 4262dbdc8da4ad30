/* SPDX-License-Identifier: MIT */
/* wordlist.c - word lists and the search order (SEARCH-ORDER and its EXT words), name
 * tokens (TRAVERSE-WORDLIST, NAME>STRING, NAME>INTERPRET, NAME>COMPILE), SYNONYM,
 * [DEFINED] [UNDEFINED], and the control-flow and return-stack words of TOOLS EXT
 * (CS-PICK CS-ROLL N>R NR>).
 *
 * Design (docs/language.md, "Word lists"): every header carries the number of its word
 * list; the dictionary keeps one hash over all headers, and find (dict.c) takes the
 * newest word of the name whose word list comes earliest in the search order. A wid is
 * the word list's number + 1; a name token is the word's execution token. All of FBRL's
 * words live in FORTH-WORDLIST, so a plan that never touches the search order runs as
 * before; the standard FILE words that share names with the thesis's typed files live in
 * their own word list (file.c), one word away: FORTH-2012. */
#include <string.h>
#include "words.h"

#define WL_FORTH 0u

static int wid_ok(const fbrl_vm *vm, fbrl_cell wid) { return wid >= 1 && wid <= (fbrl_cell)vm->nwl; }

static int pop_wid(fbrl_vm *vm, unsigned *wl)
{
    if (fbrl__cneed(vm, 1))
        return FBRL_THROW_STACK_UNDERFLOW;
    fbrl_cell wid = *--vm->sp;
    if (!wid_ok(vm, wid))
        return fbrl__throw_msg(vm, FBRL_THROW_BAD_NUMBER, "not a word list id");
    *wl = (unsigned)(wid - 1);
    return 0;
}

/* ---- SEARCH-ORDER ---- */

static fbrl_status w_forth_wordlist(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return fbrl__cthrow(vm, fbrl__cpush(vm, (fbrl_cell)WL_FORTH + 1));
}

static fbrl_status w_get_current(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return fbrl__cthrow(vm, fbrl__cpush(vm, (fbrl_cell)vm->current + 1));
}

static fbrl_status w_set_current(fbrl_vm *vm, void *arg)
{
    unsigned wl = 0;
    (void)arg;
    int r = pop_wid(vm, &wl);
    if (!r)
        vm->current = (uint8_t)wl;
    return fbrl__cthrow(vm, r);
}

static fbrl_status w_get_order(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (vm->ds_end - vm->sp < vm->norder + 1)
        return fbrl__cthrow(vm, FBRL_THROW_STACK_OVERFLOW);
    for (int k = vm->norder; k-- > 0;) /* the first word list searched is on top */
        *vm->sp++ = (fbrl_cell)vm->order[k] + 1;
    *vm->sp++ = vm->norder;
    return FBRL_OK;
}

static void minimal_order(fbrl_vm *vm)
{
    vm->order[0] = WL_FORTH;
    vm->norder = 1;
}

static fbrl_status w_set_order(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell n = vm->sp[-1];
    if (n == -1) {
        vm->sp--;
        minimal_order(vm);
        return FBRL_OK;
    }
    if (n < 0 || n > FBRL_ORDER_MAX)
        return fbrl__cthrow(vm, FBRL_THROW_SEARCH_OVERFLOW);
    if (fbrl__cneed(vm, n + 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    for (fbrl_cell k = 0; k < n; k++) /* check all before changing anything */
        if (!wid_ok(vm, vm->sp[-2 - k]))
            return fbrl__cthrow(vm, fbrl__throw_msg(vm, FBRL_THROW_BAD_NUMBER, "not a word list id"));
    for (fbrl_cell k = 0; k < n; k++)
        vm->order[k] = (uint8_t)(vm->sp[-2 - k] - 1);
    vm->norder = (int)n;
    vm->sp -= n + 1;
    return FBRL_OK;
}

int fbrl__new_wordlist(fbrl_vm *vm, const char *name, unsigned *wl)
{
    if (vm->nwl >= FBRL_WL_MAX)
        return fbrl__throw_msg(vm, FBRL_THROW_DICT_OVERFLOW, "too many word lists");
    vm->wl_name[vm->nwl] = name;
    *wl = vm->nwl++;
    return 0;
}

static fbrl_status w_wordlist(fbrl_vm *vm, void *arg)
{
    unsigned wl = 0;
    (void)arg;
    int r = fbrl__new_wordlist(vm, NULL, &wl);
    return fbrl__cthrow(vm, r ? r : fbrl__cpush(vm, (fbrl_cell)wl + 1));
}

static fbrl_status w_search_wordlist(fbrl_vm *vm, void *arg)
{
    unsigned wl = 0;
    (void)arg;
    if (fbrl__cneed(vm, 3))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    int r = pop_wid(vm, &wl);
    if (r)
        return fbrl__cthrow(vm, r);
    fbrl_cell a = vm->sp[-2], u = vm->sp[-1];
    if (u < 0 || (u > 0 && !fbrl__addr_ok(vm, a, u)))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    int i = fbrl__find_in(vm, wl, (const char *)a, (size_t)u);
    vm->sp -= 2;
    if (i < 0)
        return fbrl__cthrow(vm, fbrl__cpush(vm, 0));
    *vm->sp++ = FBRL_XT_BASE + i;
    *vm->sp++ = (HDR(vm, i)->flags & FI) ? 1 : -1;
    return FBRL_OK;
}

static fbrl_status w_definitions(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (vm->norder == 0)
        return fbrl__cthrow(vm, FBRL_THROW_SEARCH_UNDERFLOW);
    vm->current = vm->order[0];
    return FBRL_OK;
}

static fbrl_status w_also(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (vm->norder >= FBRL_ORDER_MAX)
        return fbrl__cthrow(vm, FBRL_THROW_SEARCH_OVERFLOW);
    if (vm->norder == 0)
        return fbrl__cthrow(vm, FBRL_THROW_SEARCH_UNDERFLOW);
    memmove(vm->order + 1, vm->order, (size_t)vm->norder);
    vm->norder++;
    return FBRL_OK;
}

static fbrl_status w_previous(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (vm->norder == 0)
        return fbrl__cthrow(vm, FBRL_THROW_SEARCH_UNDERFLOW);
    vm->norder--;
    memmove(vm->order, vm->order + 1, (size_t)vm->norder);
    return FBRL_OK;
}

static fbrl_status w_only(fbrl_vm *vm, void *arg)
{
    (void)arg;
    minimal_order(vm);
    return FBRL_OK;
}

/* FORTH, FORTH-2012 ...: replace the first word list of the search order by its own. */
static fbrl_status w_vocabulary(fbrl_vm *vm, void *arg)
{
    unsigned wl = (unsigned)(uintptr_t)arg;
    if (vm->norder == 0)
        vm->norder = 1;
    vm->order[0] = (uint8_t)wl;
    return FBRL_OK;
}

/* FORTH-2012: the standard words first (the word list in front, if not there yet). */
static fbrl_status w_forth2012(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (vm->norder > 0 && vm->order[0] == vm->wl_forth2012)
        return FBRL_OK;
    if (vm->norder >= FBRL_ORDER_MAX)
        return fbrl__cthrow(vm, FBRL_THROW_SEARCH_OVERFLOW);
    memmove(vm->order + 1, vm->order, (size_t)vm->norder);
    vm->order[0] = vm->wl_forth2012;
    vm->norder++;
    return FBRL_OK;
}

static void put_wl(fbrl_vm *vm, unsigned wl)
{
    char b[24];
    if (vm->wl_name[wl]) {
        fbrl__puts(vm, vm->wl_name[wl]);
    } else {
        size_t k = sizeof b;
        b[--k] = 0;
        unsigned v = wl + 1;
        do
            b[--k] = (char)('0' + v % 10);
        while ((v /= 10) && k > 6);
        memcpy(b + k - 6, "#WORDL", 6);
        fbrl__puts(vm, b + k - 6);
    }
    fbrl__puts(vm, " ");
}

static fbrl_status w_order(fbrl_vm *vm, void *arg)
{
    (void)arg;
    for (int k = 0; k < vm->norder; k++)
        put_wl(vm, vm->order[k]);
    fbrl__puts(vm, "  definitions: ");
    put_wl(vm, vm->current);
    fbrl__puts(vm, "\n");
    return FBRL_OK;
}

/* ---- name tokens ---- */

static int pop_nt(fbrl_vm *vm, const fbrl_hdr **h)
{
    if (fbrl__cneed(vm, 1))
        return FBRL_THROW_STACK_UNDERFLOW;
    *h = fbrl__xt_hdr(vm, *--vm->sp);
    if (!*h || !(*h)->len)
        return fbrl__throw_msg(vm, FBRL_THROW_BAD_NAME_ARG, "not a name token");
    return 0;
}

static fbrl_status w_traverse_wordlist(fbrl_vm *vm, void *arg)
{
    unsigned wl = 0;
    fbrl_cell xt;
    (void)arg;
    if (fbrl__cneed(vm, 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    int r = pop_wid(vm, &wl);
    if (r)
        return fbrl__cthrow(vm, r);
    xt = *--vm->sp;
    /* newest first; a word the xt defines meanwhile is newer than where the walk is */
    for (uint32_t i = vm->nwords; i-- > 0;) {
        const fbrl_hdr *h = HDR(vm, i);
        if (h->wl != wl || !h->len || (h->flags & FH))
            continue;
        if ((r = fbrl__cpush(vm, FBRL_XT_BASE + (fbrl_cell)i)))
            return fbrl__cthrow(vm, r);
        if ((r = fbrl__run(vm, xt)))
            return fbrl__cthrow(vm, r);
        if (fbrl__cneed(vm, 1))
            return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
        if (!*--vm->sp)
            break;
        if (i > vm->nwords) /* a MARKER ran inside */
            break;
    }
    return FBRL_OK;
}

static fbrl_status w_name_to_string(fbrl_vm *vm, void *arg)
{
    const fbrl_hdr *h;
    (void)arg;
    int r = pop_nt(vm, &h);
    if (r)
        return fbrl__cthrow(vm, r);
    /* headers are not addressable: the name is copied to a transient S" buffer */
    char *b = vm->sbuf + FBRL_SBUF * vm->sbuf_next;
    vm->sbuf_next = (vm->sbuf_next + 1) % FBRL_NSBUF;
    memcpy(b, h->name, h->len);
    *vm->sp++ = (fbrl_cell)b;
    *vm->sp++ = h->len;
    return FBRL_OK;
}

static fbrl_status w_name_to_interpret(fbrl_vm *vm, void *arg)
{
    const fbrl_hdr *h;
    (void)arg;
    int r = pop_nt(vm, &h);
    if (r)
        return fbrl__cthrow(vm, r);
    fbrl_cell nt = vm->sp[0]; /* still in the cell above */
    *vm->sp++ = (h->flags & FC) ? 0 : nt;
    return FBRL_OK;
}

static fbrl_status w_name_to_compile(fbrl_vm *vm, void *arg)
{
    const fbrl_hdr *h;
    (void)arg;
    int r = pop_nt(vm, &h);
    if (r)
        return fbrl__cthrow(vm, r);
    const char *how = (h->flags & FI) ? "EXECUTE" : "COMPILE,";
    int i = fbrl__find_in(vm, WL_FORTH, how, strlen(how));
    if (i < 0)
        return fbrl__cthrow(vm, FBRL_THROW_UNDEFINED);
    vm->sp++; /* the nt is x */
    *vm->sp++ = FBRL_XT_BASE + i;
    return FBRL_OK;
}

static fbrl_status w_synonym(fbrl_vm *vm, void *arg)
{
    const char *p, *q;
    size_t n, m;
    char name[FBRL_NAME_MAX + 1];
    (void)arg;
    fbrl__parse_name(vm, &p, &n);
    if (n == 0)
        return fbrl__cthrow(vm, FBRL_THROW_NO_NAME);
    if (n > FBRL_NAME_MAX)
        return fbrl__cthrow(vm, FBRL_THROW_NAME_TOO_LONG);
    memcpy(name, p, n);
    fbrl__parse_name(vm, &q, &m);
    int i = fbrl__find(vm, q, m);
    if (i < 0)
        return fbrl__cthrow(vm, m ? FBRL_THROW_UNDEFINED : FBRL_THROW_NO_NAME);
    return fbrl__cthrow(vm, fbrl__synonym(vm, name, n, HDR(vm, i)));
}

static fbrl_status defined(fbrl_vm *vm, int want)
{
    const char *p;
    size_t n;
    fbrl__parse_name(vm, &p, &n);
    int yes = fbrl__find(vm, p, n) >= 0;
    return fbrl__cthrow(vm, fbrl__cpush(vm, yes == want ? -1 : 0));
}
static fbrl_status w_bdefined(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return defined(vm, 1);
}
static fbrl_status w_bundefined(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return defined(vm, 0);
}

/* ---- control-flow stack and return stack ---- */

static fbrl_status w_cs_pick(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell u = *--vm->sp;
    if (u < 0 || u >= vm->ncf || vm->ncf - 1 - u < 1)
        return fbrl__cthrow(vm, FBRL_THROW_CONTROL_MISMATCH);
    if (vm->ncf >= FBRL_CF_MAX)
        return fbrl__cthrow(vm, FBRL_THROW_CF_OVERFLOW);
    vm->cf[vm->ncf] = vm->cf[vm->ncf - 1 - u];
    vm->ncf++;
    return FBRL_OK;
}

static fbrl_status w_cs_roll(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell u = *--vm->sp;
    /* cf[0] is the colon-sys of the open definition: CS-ROLL works above it */
    if (u < 0 || u >= vm->ncf - 1)
        return fbrl__cthrow(vm, FBRL_THROW_CONTROL_MISMATCH);
    fbrl_cf t = vm->cf[vm->ncf - 1 - u];
    memmove(&vm->cf[vm->ncf - 1 - u], &vm->cf[vm->ncf - u], (size_t)u * sizeof t);
    vm->cf[vm->ncf - 1] = t;
    return FBRL_OK;
}

static fbrl_status w_n_to_r(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell n = vm->sp[-1];
    if (n < 0 || fbrl__cneed(vm, n + 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    if (vm->rs_end - vm->rp < n + 1)
        return fbrl__cthrow(vm, FBRL_THROW_RSTACK_OVERFLOW);
    vm->sp--;
    vm->sp -= n;
    memcpy(vm->rp, vm->sp, (size_t)n * sizeof(fbrl_cell));
    vm->rp += n;
    *vm->rp++ = n;
    return FBRL_OK;
}

static fbrl_status w_nr_from(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (vm->rp - vm->rs0 < 1)
        return fbrl__cthrow(vm, FBRL_THROW_RSTACK_UNDERFLOW);
    fbrl_cell n = vm->rp[-1];
    if (n < 0 || vm->rp - vm->rs0 < n + 1)
        return fbrl__cthrow(vm, FBRL_THROW_RSTACK_UNDERFLOW);
    if (vm->ds_end - vm->sp < n + 1)
        return fbrl__cthrow(vm, FBRL_THROW_STACK_OVERFLOW);
    vm->rp -= n + 1;
    memcpy(vm->sp, vm->rp, (size_t)n * sizeof(fbrl_cell));
    vm->sp += n;
    *vm->sp++ = n;
    return FBRL_OK;
}

static const fbrl_cword words[] = {
    {"FORTH-WORDLIST", w_forth_wordlist, NULL, 0,
     FBRL_DOC("( -- wid )", "the word list of all built-in words")},
    {"GET-CURRENT", w_get_current, NULL, 0, FBRL_DOC("( -- wid )", "the word list new definitions go into")},
    {"SET-CURRENT", w_set_current, NULL, 0, FBRL_DOC("( wid -- )", "put new definitions into word list wid")},
    {"GET-ORDER", w_get_order, NULL, 0,
     FBRL_DOC("( -- widn .. wid1 n )", "the search order (wid1 searched first)")},
    {"SET-ORDER", w_set_order, NULL, 0,
     FBRL_DOC("( widn .. wid1 n -- )", "set the search order (wid1 first); n = -1: the minimal order")},
    {"WORDLIST", w_wordlist, NULL, 0, FBRL_DOC("( -- wid )", "make a new empty word list")},
    {"SEARCH-WORDLIST", w_search_wordlist, NULL, 0,
     FBRL_DOC("( c-addr u wid -- 0 | xt 1 | xt -1 )", "find a name in one word list (1: immediate)")},
    {"DEFINITIONS", w_definitions, NULL, 0,
     FBRL_DOC("( -- )", "new definitions go into the first word list searched")},
    {"ALSO", w_also, NULL, 0, FBRL_DOC("( -- )", "duplicate the first word list of the search order")},
    {"PREVIOUS", w_previous, NULL, 0, FBRL_DOC("( -- )", "drop the first word list of the search order")},
    {"ONLY", w_only, NULL, 0, FBRL_DOC("( -- )", "the minimal search order (FORTH-WORDLIST)")},
    {"FORTH", w_vocabulary, (void *)(uintptr_t)WL_FORTH, 0,
     FBRL_DOC("( -- )", "make FORTH-WORDLIST the first word list searched")},
    {"FORTH-2012", w_forth2012, NULL, 0,
     FBRL_DOC(
         "( -- )",
         "search the standard words first (FILE's CREATE-FILE ... instead of the thesis's typed files)")},
    {"ORDER", w_order, NULL, 0, FBRL_DOC("( -- )", "show the search order and the compilation word list")},
    {"TRAVERSE-WORDLIST", w_traverse_wordlist, NULL, 0,
     FBRL_DOC("( i*x xt wid -- j*x )",
              "run xt ( k*x nt -- l*x flag ) on each word of wid, newest first, until it gives false")},
    {"NAME>STRING", w_name_to_string, NULL, 0,
     FBRL_DOC("( nt -- c-addr u )", "the name of a word (a transient copy)")},
    {"NAME>INTERPRET", w_name_to_interpret, NULL, 0,
     FBRL_DOC("( nt -- xt | 0 )", "what a word does interpreted (0: compile-only)")},
    {"NAME>COMPILE", w_name_to_compile, NULL, 0,
     FBRL_DOC("( nt -- x xt )", "what a word does compiled: x xt EXECUTE")},
    {"SYNONYM", w_synonym, NULL, 0,
     FBRL_DOC("( \"new\" \"old\" -- )", "make new a word that behaves as old")},
    {"[DEFINED]", w_bdefined, NULL, FI,
     FBRL_DOC("( \"name\" -- flag )", "true if name is a word (search order)")},
    {"[UNDEFINED]", w_bundefined, NULL, FI, FBRL_DOC("( \"name\" -- flag )", "true if name is not a word")},
    {"CS-PICK", w_cs_pick, NULL, 0,
     FBRL_DOC("( C: destu .. orig0|dest0 -- .. destu ) ( u -- )",
              "copy the u-th control-flow entry to the top")},
    {"CS-ROLL", w_cs_roll, NULL, 0,
     FBRL_DOC("( C: x_u .. x_0 -- x_u-1 .. x_0 x_u ) ( u -- )",
              "move the u-th control-flow entry to the top")},
    {"N>R", w_n_to_r, NULL, FC,
     FBRL_DOC("( i*n +n -- ) ( R: -- j*x +n )", "move n cells and n to the return stack")},
    {"NR>", w_nr_from, NULL, FC, FBRL_DOC("( -- i*x +n ) ( R: j*x +n -- )", "move the cells N>R moved back")},
};

int fbrl__wordlist_init(fbrl_vm *vm)
{
    unsigned wl = 0;
    vm->nwl = 0;
    fbrl__new_wordlist(vm, "FORTH", &wl);
    vm->current = (uint8_t)wl;
    minimal_order(vm);
    fbrl__new_wordlist(vm, "FORTH-2012", &wl);
    vm->wl_forth2012 = (uint8_t)wl;
    return fbrl__define_words(vm, words, sizeof words / sizeof words[0]);
}
