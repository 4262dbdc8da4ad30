/* io.c - the engine's text streams: output through the host, the stack of input
 * sources (text, strings, files) and the parsing of names and delimited text. */
#include <string.h>
#include "words.h"

/* ---- output ---- */
void fbrl__write(fbrl_vm *vm, const char *s, size_t n)
{
    if (vm->host.write && n)
        vm->host.write(vm->host.user, s, n);
}

void fbrl__puts(fbrl_vm *vm, const char *s) { fbrl__write(vm, s, strlen(s)); }

/* ---- input parsing ---- */
fbrl_src *fbrl__src(fbrl_vm *vm) { return &vm->src[vm->nsrc - 1]; }

size_t fbrl__src_in(fbrl_vm *vm, const fbrl_src *s)
{
    fbrl_cell in = *vm->toin;
    if (in < 0)
        in = 0;
    if ((size_t)in > s->len)
        in = (fbrl_cell)s->len;
    return (size_t)in;
}

/* Blank-delimited name (any control character counts as blank). */
void fbrl__parse_name(fbrl_vm *vm, const char **p, size_t *n)
{
    *p = "";
    *n = 0;
    if (vm->nsrc == 0)
        return;
    fbrl_src *s = fbrl__src(vm);
    size_t i = fbrl__src_in(vm, s);
    while (i < s->len && (unsigned char)s->buf[i] <= ' ')
        i++;
    size_t st = i;
    while (i < s->len && (unsigned char)s->buf[i] > ' ')
        i++;
    *p = s->buf + st;
    *n = i - st;
    *vm->toin = (fbrl_cell)(i < s->len ? i + 1 : i);
}

/* Text up to delimiter c (a blank delimiter matches any control character too). */
void fbrl__parse(fbrl_vm *vm, char c, const char **p, size_t *n, int *found)
{
    *p = "";
    *n = 0;
    *found = 0;
    if (vm->nsrc == 0)
        return;
    fbrl_src *s = fbrl__src(vm);
    size_t i = fbrl__src_in(vm, s), st = i;
    while (i < s->len && !(s->buf[i] == c || (c == ' ' && (unsigned char)s->buf[i] < ' ')))
        i++;
    *p = s->buf + st;
    *n = i - st;
    *found = i < s->len;
    *vm->toin = (fbrl_cell)(i < s->len ? i + 1 : i);
}

/* Next line of the current source: 1 read, 0 end, <0 throw code. */
int fbrl__refill(fbrl_vm *vm)
{
    if (vm->nsrc == 0)
        return 0;
    fbrl_src *s = fbrl__src(vm);
    size_t len = 0;
    if (s->kind == SRC_STRING)
        return 0;
    if (s->kind == SRC_TEXT) {
        if (s->text >= s->text_end)
            return 0;
        const char *nl = memchr(s->text, '\n', (size_t)(s->text_end - s->text));
        const char *e = nl ? nl : s->text_end;
        len = (size_t)(e - s->text);
        if (len > 0 && s->text[len - 1] == '\r')
            len--;
        if (len > FBRL_LINE_MAX) {
            s->text = nl ? nl + 1 : s->text_end;
            s->line++;
            return fbrl__throw_msg(vm, FBRL_THROW_PARSED_OVERFLOW, "input line too long");
        }
        memcpy(s->linebuf, s->text, len);
        s->text = nl ? nl + 1 : s->text_end;
    } else {
        if (!vm->host.file_read_line)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no file support in this host");
        fbrl_status st = vm->host.file_read_line(vm->host.user, s->fh, s->linebuf, FBRL_LINE_MAX, &len);
        if (st == FBRL_EEOF)
            return 0;
        if (st == FBRL_ENOSPC) {
            s->line++;
            return fbrl__throw_msg(vm, FBRL_THROW_PARSED_OVERFLOW, "input line too long");
        }
        if (st != FBRL_OK || len > FBRL_LINE_MAX)
            return FBRL_THROW_FILE_IO;
        if (len > 0 && s->linebuf[len - 1] == '\r')
            len--;
    }
    s->buf = s->linebuf;
    s->len = len;
    s->line++;
    *vm->toin = 0;
    return 1;
}

int fbrl__push_source(fbrl_vm *vm, int kind, fbrl_src **out)
{
    if (vm->nsrc >= FBRL_SRC_MAX)
        return fbrl__throw_msg(vm, FBRL_THROW_FILE_IO, "input sources nested too deeply");
    fbrl_src *s = &vm->src[vm->nsrc];
    char *lb = s->linebuf;
    memset(s, 0, sizeof *s);
    s->linebuf = lb;
    s->kind = kind;
    s->buf = lb;
    s->saved_in = *vm->toin;
    vm->nsrc++;
    *vm->toin = 0;
    *out = s;
    return 0;
}

static void pop_source(fbrl_vm *vm)
{
    fbrl_src *s = fbrl__src(vm);
    if (s->kind == SRC_FILE && s->fh && vm->host.file_close)
        vm->host.file_close(vm->host.user, s->fh);
    *vm->toin = s->saved_in;
    vm->nsrc--;
}

void fbrl__pop_source(fbrl_vm *vm)
{
    if (vm->nsrc > 0)
        pop_source(vm);
}
