/* SPDX-License-Identifier: MIT */
/* interp.c - the text interpreter: find or convert each name and execute or compile
 * it; EVALUATE and INCLUDED nest it, fbrl_vm_eval and fbrl_vm_include enter it.
 * Errors are captured here with the word, file and line they happened at. */
#include <string.h>
#include "atomic.h"
#include "words.h"

/* ---- the text interpreter ---- */
static void capture_error(fbrl_vm *vm)
{
    if (vm->err_captured)
        return;
    vm->err_captured = 1;
    memcpy(vm->err.word, vm->cur_word, sizeof vm->err.word);
    vm->err.file[0] = 0;
    vm->err.line = 0;
    for (int i = vm->nsrc - 1; i >= 0; i--) {
        const fbrl_src *s = &vm->src[i];
        if (s->kind == SRC_STRING)
            continue;
        if (s->kind == SRC_FILE) {
            size_t n = strlen(s->path);
            if (n >= sizeof vm->err.file)
                n = sizeof vm->err.file - 1;
            memcpy(vm->err.file, s->path, n);
            vm->err.file[n] = 0;
        }
        vm->err.line = s->line;
        break;
    }
}

static int interpret_word(fbrl_vm *vm, const char *name, size_t len)
{
    size_t n = len < sizeof vm->cur_word - 1 ? len : sizeof vm->cur_word - 1;
    memcpy(vm->cur_word, name, n);
    vm->cur_word[n] = 0;
    if (vm->nlocals && *vm->state) { /* a local of the definition comes first */
        int k = fbrl__local_index(vm, name, len);
        if (k >= 0)
            return fbrl__compile_local(vm, k, 0);
    }
    int idx = fbrl__find(vm, name, len);
    if (idx >= 0) {
        fbrl_hdr *h = HDR(vm, idx);
        fbrl_cell xt = FBRL_XT_BASE + idx;
        if (*vm->state == 0 && (h->flags & FC))
            return FBRL_THROW_COMPILE_ONLY;
        if (*vm->state != 0 && !(h->flags & FI)) {
            fbrl__note_line(vm);
            return fbrl__compile_xt(vm, xt);
        }
        if (FBRL_WORD_HOOK && *vm->state == 0 && vm->word_fn) { /* a debugger sees these too */
            int stop = fbrl__step_top(vm, xt);
            if (stop)
                return stop;
        }
        return fbrl__run(vm, xt);
    }
    fbrl_cell v[2];
    double f;
    int kind = fbrl__parse_number(vm, name, len, v, &f);
    if (kind == 0)
        return FBRL_THROW_UNDEFINED;
    if (*vm->state) {
        fbrl__note_line(vm);
        if (kind == 3)
            return fbrl__compile_flit(vm, f);
        int r = fbrl__compile_lit(vm, v[0]);
        return (r || kind == 1) ? r : fbrl__compile_lit(vm, v[1]);
    }
    if (kind == 3) {
        if (vm->fp >= vm->fs_end)
            return FBRL_THROW_FSTACK_OVERFLOW;
        *vm->fp++ = f;
        return 0;
    }
    if (vm->ds_end - vm->sp < kind)
        return FBRL_THROW_STACK_OVERFLOW;
    *vm->sp++ = v[0];
    if (kind == 2)
        *vm->sp++ = v[1];
    return 0;
}

/* Interpret the current source to its end. */
static int interpret(fbrl_vm *vm)
{
    for (;;) {
        const char *name;
        size_t len;
        int r;
        fbrl__parse_name(vm, &name, &len);
        if (len == 0) {
            r = fbrl__refill(vm);
            if (r > 0)
                continue;
        } else {
            r = interpret_word(vm, name, len);
            if (vm->bye && !r)
                r = THROW_BYE;
            if (!r)
                continue;
        }
        if (r)
            capture_error(vm);
        return r;
    }
}

int fbrl__evaluate(fbrl_vm *vm, char *text, size_t len)
{
    fbrl_src *s = NULL;
    int r = fbrl__push_source(vm, SRC_STRING, &s);
    if (r)
        return r;
    s->buf = text;
    s->len = len;
    s->id = -1;
    r = interpret(vm);
    fbrl__pop_source(vm);
    return r;
}

/* A file's id: its path's offset + 1 in REQUIRE's pool of included files (0: none). */
static uint32_t file_id(const fbrl_vm *vm, const char *path)
{
    for (size_t i = 0; i < vm->req_used; i += strlen(vm->req_pool + i) + 1)
        if (strcmp(vm->req_pool + i, path) == 0)
            return (uint32_t)i + 1;
    return 0;
}

static int is_included(const fbrl_vm *vm, const char *path) { return file_id(vm, path) != 0; }

/* INCLUDED / REQUIRED (require 1). Relative paths are taken from the including file's
 * directory, except for INCLUDE-FILE (require 2): its path is the one the host opened. */
int fbrl__included(fbrl_vm *vm, const char *name, size_t n, int require)
{
    char path[FBRL_PATH_MAX];
    size_t dl = 0;
    if (n == 0)
        return FBRL_THROW_NO_FILE;
    if (name[0] != '/' && require != 2) {
        for (int i = vm->nsrc - 1; i >= 0; i--) {
            if (vm->src[i].kind != SRC_FILE)
                continue;
            const char *slash = strrchr(vm->src[i].path, '/');
            if (slash)
                dl = (size_t)(slash - vm->src[i].path) + 1;
            if (dl)
                memcpy(path, vm->src[i].path, dl);
            break;
        }
    }
    if (dl + n >= sizeof path)
        return fbrl__throw_msg(vm, FBRL_THROW_NO_FILE, "file name too long");
    memcpy(path + dl, name, n);
    path[dl + n] = 0;
    if (memchr(path, 0, dl + n))
        return FBRL_THROW_NO_FILE;
    if (require == 1 && is_included(vm, path))
        return 0;
    if (!vm->host.file_open || !vm->host.file_read_line)
        return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no file support in this host");
    if (!is_included(vm, path)) {
        if (vm->req_used + dl + n + 1 > sizeof vm->req_pool)
            return fbrl__throw_msg(vm, FBRL_THROW_FILE_IO, "too many included files");
        memcpy(vm->req_pool + vm->req_used, path, dl + n + 1);
        vm->req_used += dl + n + 1;
    }
    fbrl_src *s = NULL;
    int r = fbrl__push_source(vm, SRC_FILE, &s);
    if (r)
        return r;
    memcpy(s->path, path, dl + n + 1);
    s->id = vm->nsrc;
    s->file = file_id(vm, path);
    fbrl_status ost = vm->host.file_open(vm->host.user, path, &s->fh);
    if (ost != FBRL_OK) {
        s->fh = NULL;
        vm->nsrc--;
        *vm->toin = s->saved_in;
        char msg[sizeof vm->throw_msg];
        size_t k = n < 80 ? n : 80;
        memcpy(msg, "cannot open ", 12);
        memcpy(msg + 12, name, k);
        msg[12 + k] = 0;
        if (ost != FBRL_ENOENT) { /* say why, e.g. a device or FIFO refused */
            const char *why = fbrl_status_str(ost);
            size_t at = 12 + k, w = strlen(why);
            if (at + 2 + w < sizeof msg) {
                memcpy(msg + at, ": ", 2);
                memcpy(msg + at + 2, why, w + 1);
            }
        }
        return fbrl__throw_msg(vm, FBRL_THROW_NO_FILE, msg);
    }
    fbrl_cell state0 = *vm->state;
    r = interpret(vm);
    if (r == 0 && *vm->state != 0 && state0 == 0) {
        r = fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "unterminated definition at end of file");
        capture_error(vm);
    }
    fbrl__pop_source(vm);
    return r;
}

/* Stacks, sources and any open definition back to a clean interpreter. */
static void reset_after_error(fbrl_vm *vm)
{
    vm->sp = vm->ds0;
    vm->rp = vm->rs0;
    vm->fp = vm->fs0;
    vm->handler = 0;
    vm->nest = 0;
    while (vm->nsrc > 0)
        fbrl__pop_source(vm);
    fbrl__drop_definition(vm);
    vm->hld = vm->hold + FBRL_HOLDSIZE;
    vm->lp = 0; /* no definition runs: no locals */
    /* a search order without FORTH-WORDLIST (0 SET-ORDER, a lone WORDLIST) could not even
     * find ONLY again: after an error it is the minimal order (docs/language.md) */
    int k = 0;
    while (k < vm->norder && vm->order[k] != 0)
        k++;
    if (k == vm->norder) {
        vm->order[0] = 0;
        vm->norder = 1;
    }
}

static void begin_top(fbrl_vm *vm)
{
    fbrl_store_rlx(&vm->interrupt, fbrl_load_rlx(&vm->interrupt) & FBRL_ATTN_STEP);
    vm->running = 1;
    vm->err_captured = 0;
    vm->pending_msg = NULL;
    vm->cur_word[0] = 0;
    memset(&vm->err, 0, sizeof vm->err);
    vm->rp = vm->rs0;
    vm->handler = 0;
    vm->nest = 0;
    vm->bt_captured = 0;
    vm->nbt = 0;
    vm->bt_depth = 0;
}

static fbrl_status finish_top(fbrl_vm *vm, int code)
{
    vm->running = 0;
    if (code == 0 || code == THROW_BYE) {
        while (vm->nsrc > 0)
            fbrl__pop_source(vm);
        return FBRL_OK;
    }
    if (code == THROW_QUIT) {
        vm->rp = vm->rs0;
        while (vm->nsrc > 0)
            fbrl__pop_source(vm);
        fbrl__drop_definition(vm);
        return FBRL_OK;
    }
    capture_error(vm);
    vm->err.throw_code = code;
    if (vm->nbt > 0) /* name the word it happened in, not the one typed */
        memcpy(vm->err.word, vm->bt[0].word, sizeof vm->bt[0].word);
    const char *msg =
        (vm->pending_msg && vm->pending_code == code) ? vm->pending_msg : fbrl__throw_text(code);
    size_t n = strlen(msg);
    if (n >= sizeof vm->err.message)
        n = sizeof vm->err.message - 1;
    memcpy(vm->err.message, msg, n);
    vm->err.message[n] = 0;
    reset_after_error(vm);
    if (code <= FBRL_THROW_STATUS(0) && code >= FBRL_THROW_STATUS(FBRL_STATUS_MIN) &&
        code != FBRL_THROW_STATUS(FBRL_ETHROW))
        return (fbrl_status)(code - FBRL_THROW_STATUS(0));
    return FBRL_ETHROW;
}

fbrl_status fbrl_vm_eval(fbrl_vm *vm, const char *text, size_t len)
{
    fbrl_src *s = NULL;
    if (!vm || (!text && len))
        return FBRL_EINVAL;
    if (vm->running)
        return FBRL_ESTATE;
    if (vm->bye)
        return FBRL_OK;
    begin_top(vm);
    int r = fbrl__push_source(vm, SRC_TEXT, &s);
    if (!r) {
        s->text = text ? text : "";
        s->text_end = s->text + len;
        s->len = 0;
        r = interpret(vm);
    }
    return finish_top(vm, r);
}

fbrl_status fbrl_vm_include(fbrl_vm *vm, const char *path)
{
    if (!vm || !path)
        return FBRL_EINVAL;
    if (vm->running)
        return FBRL_ESTATE;
    if (vm->bye)
        return FBRL_OK;
    begin_top(vm);
    int r = fbrl__included(vm, path, strlen(path), 0);
    return finish_top(vm, r);
}

void fbrl_vm_reset(fbrl_vm *vm)
{
    if (!vm || vm->running)
        return;
    reset_after_error(vm);
}
