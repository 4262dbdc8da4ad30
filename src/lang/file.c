/* SPDX-License-Identifier: MIT */
/* file.c - the standard FILE and FILE EXT word sets on the host's file system
 * (fbrl_vm_host.files). A host without one (the firmware) passes NULL, and the VM has
 * none of these words: the engine itself includes no OS header.
 *
 * The thesis's typed-file words (src/words/glossary_file.c) keep the names CREATE-FILE
 * OPEN-FILE READ-FILE WRITE-FILE CLOSE-FILE in FORTH-WORDLIST; the standard words of those
 * names live in the FORTH-2012 word list, first in the search order after FORTH-2012
 * (docs/language.md). The other FILE words have no FBRL namesake and are in FORTH.
 * A fileid is a slot number + 1 of vm->file_h; the host's handles are not addressable.
 * Failures are iors: -38 no such file, -37 any other file error, as THROW codes. */
#include <string.h>
#include "words.h"

#define IOR_IO    FBRL_THROW_FILE_IO /* -37 */
#define IOR_NOENT FBRL_THROW_NO_FILE /* -38 */
#define LINE_END  "\n"

static const fbrl_vm_files *fs(const fbrl_vm *vm) { return vm->host.files; }

static fbrl_cell ior_of(fbrl_status st) { return st == FBRL_OK ? 0 : st == FBRL_ENOENT ? IOR_NOENT : IOR_IO; }

/* pop n cells into v[0..n) (v[n-1] was the top); a throw code or 0 */
static int pops(fbrl_vm *vm, int n, fbrl_cell *v)
{
    if (fbrl__cneed(vm, n))
        return FBRL_THROW_STACK_UNDERFLOW;
    vm->sp -= n;
    memcpy(v, vm->sp, (size_t)n * sizeof *v);
    return 0;
}

static int pushes(fbrl_vm *vm, int n, const fbrl_cell *v)
{
    if (vm->ds_end - vm->sp < n)
        return FBRL_THROW_STACK_OVERFLOW;
    memcpy(vm->sp, v, (size_t)n * sizeof *v);
    vm->sp += n;
    return 0;
}

static int str_ok(const fbrl_vm *vm, fbrl_cell a, fbrl_cell u)
{
    return u >= 0 && (u == 0 || fbrl__addr_ok(vm, a, u));
}

/* A path as a C string; 0 or a throw code. */
static int path_of(const fbrl_vm *vm, fbrl_cell a, fbrl_cell u, char *out)
{
    if (!str_ok(vm, a, u))
        return FBRL_THROW_BAD_ADDRESS;
    if (u >= FBRL_PATH_MAX)
        return FBRL_THROW_NAME_TOO_LONG;
    memcpy(out, (const char *)a, (size_t)u);
    out[u] = 0;
    return 0;
}

static void *handle(const fbrl_vm *vm, fbrl_cell fid)
{
    return fid >= 1 && fid <= FBRL_FILES_MAX ? vm->file_h[fid - 1] : NULL;
}

/* ---- file access methods ---- */

static fbrl_status w_fam(fbrl_vm *vm, void *arg)
{
    return fbrl__cthrow(vm, fbrl__cpush(vm, (fbrl_cell)(uintptr_t)arg));
}

static fbrl_status w_bin(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    vm->sp[-1] |= (fbrl_cell)FBRL_FAM_BIN;
    return FBRL_OK;
}

/* CREATE-FILE (arg 1) and OPEN-FILE (arg 0): ( c-addr u fam -- fileid ior ) */
static fbrl_status w_open(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[3];
    char path[FBRL_PATH_MAX];
    int r = pops(vm, 3, v), k;
    if (r || (r = path_of(vm, v[0], v[1], path)))
        return fbrl__cthrow(vm, r);
    for (k = 0; k < FBRL_FILES_MAX && vm->file_h[k]; k++)
        ;
    fbrl_cell out[2] = {0, IOR_IO};
    unsigned fam = (unsigned)v[2] & (FBRL_FAM_READ | FBRL_FAM_WRITE | FBRL_FAM_BIN);
    if (k < FBRL_FILES_MAX && (fam & (FBRL_FAM_READ | FBRL_FAM_WRITE))) {
        void *h = NULL;
        fbrl_status st = fs(vm)->open(vm->host.user, path, fam, arg != NULL, &h);
        out[1] = ior_of(st);
        if (st == FBRL_OK) {
            vm->file_h[k] = h;
            memcpy(vm->file_path[k], path, (size_t)v[1] + 1);
            out[0] = k + 1;
        }
    }
    return fbrl__cthrow(vm, pushes(vm, 2, out));
}

static fbrl_status w_close(fbrl_vm *vm, void *arg)
{
    fbrl_cell fid;
    (void)arg;
    int r = pops(vm, 1, &fid);
    if (r)
        return fbrl__cthrow(vm, r);
    void *h = handle(vm, fid);
    fbrl_cell ior = IOR_IO;
    if (h) {
        ior = ior_of(fs(vm)->close(vm->host.user, h));
        vm->file_h[fid - 1] = NULL; /* gone, whatever the close said */
    }
    return fbrl__cthrow(vm, fbrl__cpush(vm, ior));
}

/* READ-FILE ( c-addr u1 fileid -- u2 ior ) */
static fbrl_status w_read(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[3];
    (void)arg;
    int r = pops(vm, 3, v);
    if (r)
        return fbrl__cthrow(vm, r);
    if (!str_ok(vm, v[0], v[1]))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    void *h = handle(vm, v[2]);
    size_t got = 0;
    fbrl_cell out[2] = {0, IOR_IO};
    if (h) {
        out[1] = v[1] ? ior_of(fs(vm)->read(vm->host.user, h, (void *)v[0], (size_t)v[1], &got)) : 0;
        out[0] = (fbrl_cell)got;
    }
    return fbrl__cthrow(vm, pushes(vm, 2, out));
}

/* READ-LINE ( c-addr u1 fileid -- u2 flag ior ): up to u1 characters of the next line,
 * without its end (LF or CR LF); the file is left after the line end. */
static fbrl_status w_read_line(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[3];
    char tmp[256];
    (void)arg;
    int r = pops(vm, 3, v);
    if (r)
        return fbrl__cthrow(vm, r);
    if (!str_ok(vm, v[0], v[1]))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    void *h = handle(vm, v[2]);
    fbrl_cell out[3] = {0, 0, IOR_IO};
    uint64_t pos0;
    if (!h || fs(vm)->tell(vm->host.user, h, &pos0) != FBRL_OK)
        return fbrl__cthrow(vm, pushes(vm, 3, out));
    char *dst = (char *)v[0];
    size_t u1 = (size_t)v[1], len = 0, total = 0;
    for (;;) {
        size_t want = u1 + 2 - total, got = 0;
        if (want > sizeof tmp)
            want = sizeof tmp;
        fbrl_status st = fs(vm)->read(vm->host.user, h, tmp, want, &got);
        if (st != FBRL_OK) {
            out[2] = ior_of(st);
            break;
        }
        const char *nl = memchr(tmp, '\n', got);
        size_t take = nl ? (size_t)(nl - tmp) : got;
        for (size_t i = 0; i < take && len < u1; i++)
            dst[len++] = tmp[i];
        if (nl) {
            if (len > 0 && dst[len - 1] == '\r' && total + take <= u1)
                len--;
            out[0] = (fbrl_cell)len;
            out[1] = -1;
            out[2] = ior_of(fs(vm)->seek(vm->host.user, h, pos0 + total + take + 1));
            break;
        }
        total += got;
        if (total >= u1 || got < want) { /* a full buffer, or the end of the file */
            if (total > u1)
                out[2] = ior_of(fs(vm)->seek(vm->host.user, h, pos0 + u1));
            else
                out[2] = 0;
            out[0] = (fbrl_cell)len;
            out[1] = total > 0 ? -1 : 0;
            break;
        }
    }
    return fbrl__cthrow(vm, pushes(vm, 3, out));
}

/* WRITE-FILE (arg 0) and WRITE-LINE (arg 1): ( c-addr u fileid -- ior ) */
static fbrl_status w_write(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[3];
    int r = pops(vm, 3, v);
    if (r)
        return fbrl__cthrow(vm, r);
    if (!str_ok(vm, v[0], v[1]))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    void *h = handle(vm, v[2]);
    fbrl_cell ior = IOR_IO;
    if (h) {
        fbrl_status st = v[1] ? fs(vm)->write(vm->host.user, h, (const void *)v[0], (size_t)v[1]) : FBRL_OK;
        if (st == FBRL_OK && arg)
            st = fs(vm)->write(vm->host.user, h, LINE_END, strlen(LINE_END));
        ior = ior_of(st);
    }
    return fbrl__cthrow(vm, fbrl__cpush(vm, ior));
}

/* FILE-POSITION (arg 0) and FILE-SIZE (arg 1): ( fileid -- ud ior ) */
static fbrl_status w_where(fbrl_vm *vm, void *arg)
{
    fbrl_cell fid;
    int r = pops(vm, 1, &fid);
    if (r)
        return fbrl__cthrow(vm, r);
    void *h = handle(vm, fid);
    uint64_t p = 0;
    fbrl_cell out[3] = {0, 0, IOR_IO};
    if (h) {
        out[2] = ior_of(arg ? fs(vm)->size(vm->host.user, h, &p) : fs(vm)->tell(vm->host.user, h, &p));
        out[0] = (fbrl_cell)p; /* a cell holds any file position on the hosts FBRL runs on */
    }
    return fbrl__cthrow(vm, pushes(vm, 3, out));
}

/* REPOSITION-FILE (arg 0) and RESIZE-FILE (arg 1): ( ud fileid -- ior ) */
static fbrl_status w_move(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[3];
    int r = pops(vm, 3, v);
    if (r)
        return fbrl__cthrow(vm, r);
    void *h = handle(vm, v[2]);
    fbrl_cell ior = IOR_IO;
    if (h && v[1] == 0 && v[0] >= 0)
        ior = ior_of(arg ? fs(vm)->resize(vm->host.user, h, (uint64_t)v[0])
                         : fs(vm)->seek(vm->host.user, h, (uint64_t)v[0]));
    else if (h)
        ior = FBRL_THROW_BAD_FILE_POSITION;
    return fbrl__cthrow(vm, fbrl__cpush(vm, ior));
}

static fbrl_status w_flush(fbrl_vm *vm, void *arg)
{
    fbrl_cell fid;
    (void)arg;
    int r = pops(vm, 1, &fid);
    if (r)
        return fbrl__cthrow(vm, r);
    void *h = handle(vm, fid);
    return fbrl__cthrow(vm, fbrl__cpush(vm, h ? ior_of(fs(vm)->flush(vm->host.user, h)) : IOR_IO));
}

static fbrl_status w_delete(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[2];
    char path[FBRL_PATH_MAX];
    (void)arg;
    int r = pops(vm, 2, v);
    if (r || (r = path_of(vm, v[0], v[1], path)))
        return fbrl__cthrow(vm, r);
    return fbrl__cthrow(vm, fbrl__cpush(vm, ior_of(fs(vm)->remove(vm->host.user, path))));
}

static fbrl_status w_rename(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[4];
    char from[FBRL_PATH_MAX], to[FBRL_PATH_MAX];
    (void)arg;
    int r = pops(vm, 4, v);
    if (r || (r = path_of(vm, v[0], v[1], from)) || (r = path_of(vm, v[2], v[3], to)))
        return fbrl__cthrow(vm, r);
    return fbrl__cthrow(vm, fbrl__cpush(vm, ior_of(fs(vm)->rename(vm->host.user, from, to))));
}

static fbrl_status w_status(fbrl_vm *vm, void *arg)
{
    fbrl_cell v[2];
    char path[FBRL_PATH_MAX];
    unsigned mode = 0;
    (void)arg;
    int r = pops(vm, 2, v);
    if (r || (r = path_of(vm, v[0], v[1], path)))
        return fbrl__cthrow(vm, r);
    fbrl_cell out[2] = {0, ior_of(fs(vm)->status(vm->host.user, path, &mode))};
    out[0] = (fbrl_cell)mode;
    return fbrl__cthrow(vm, pushes(vm, 2, out));
}

/* INCLUDE-FILE ( i*x fileid -- j*x ): interpret the file the fileid was opened on (by its
 * path, from its start: the engine reads sources through the host's line reader), then
 * close the fileid, as the standard's INCLUDE-FILE leaves it at the end. */
static fbrl_status w_include_file(fbrl_vm *vm, void *arg)
{
    fbrl_cell fid;
    char path[FBRL_PATH_MAX];
    (void)arg;
    int r = pops(vm, 1, &fid);
    if (r)
        return fbrl__cthrow(vm, r);
    void *h = handle(vm, fid);
    if (!h)
        return fbrl__cthrow(vm, fbrl__throw_msg(vm, IOR_IO, "INCLUDE-FILE: not an open fileid"));
    memcpy(path, vm->file_path[fid - 1], sizeof path);
    fs(vm)->close(vm->host.user, h);
    vm->file_h[fid - 1] = NULL;
    return fbrl__cthrow(vm, vm->nest_included(vm, path, strlen(path), 2));
}

#define FAM(x) ((void *)(uintptr_t)(x))

/* The standard words whose names the thesis's typed files use: in FORTH-2012's list. */
static const fbrl_cword shadowed[] = {
    {"CREATE-FILE", w_open, FAM(1), 0,
     FBRL_DOC("( c-addr u fam -- fileid ior )", "create (or empty) a file and open it")},
    {"OPEN-FILE", w_open, NULL, 0, FBRL_DOC("( c-addr u fam -- fileid ior )", "open an existing file")},
    {"CLOSE-FILE", w_close, NULL, 0, FBRL_DOC("( fileid -- ior )", "close a file")},
    {"READ-FILE", w_read, NULL, 0,
     FBRL_DOC("( c-addr u1 fileid -- u2 ior )", "read up to u1 bytes (u2 = 0: the end)")},
    {"WRITE-FILE", w_write, NULL, 0, FBRL_DOC("( c-addr u fileid -- ior )", "write u bytes")},
};

static const fbrl_cword words[] = {
    {"R/O", w_fam, FAM(FBRL_FAM_READ), 0, FBRL_DOC("( -- fam )", "file access method: read only")},
    {"W/O", w_fam, FAM(FBRL_FAM_WRITE), 0, FBRL_DOC("( -- fam )", "file access method: write only")},
    {"R/W", w_fam, FAM(FBRL_FAM_READ | FBRL_FAM_WRITE), 0,
     FBRL_DOC("( -- fam )", "file access method: read and write")},
    {"BIN", w_bin, NULL, 0, FBRL_DOC("( fam1 -- fam2 )", "binary (no effect: files are bytes)")},
    {"READ-LINE", w_read_line, NULL, 0,
     FBRL_DOC("( c-addr u1 fileid -- u2 flag ior )",
              "read a line of up to u1 characters (flag false: the end of the file)")},
    {"WRITE-LINE", w_write, FAM(1), 0,
     FBRL_DOC("( c-addr u fileid -- ior )", "write the text and a line end")},
    {"FILE-POSITION", w_where, NULL, 0, FBRL_DOC("( fileid -- ud ior )", "where the next read or write is")},
    {"FILE-SIZE", w_where, FAM(1), 0, FBRL_DOC("( fileid -- ud ior )", "the size of the file in bytes")},
    {"REPOSITION-FILE", w_move, NULL, 0, FBRL_DOC("( ud fileid -- ior )", "move to byte ud")},
    {"RESIZE-FILE", w_move, FAM(1), 0, FBRL_DOC("( ud fileid -- ior )", "make the file ud bytes long")},
    {"FLUSH-FILE", w_flush, NULL, 0, FBRL_DOC("( fileid -- ior )", "write buffered data to the file")},
    {"DELETE-FILE", w_delete, NULL, 0, FBRL_DOC("( c-addr u -- ior )", "remove a file")},
    {"RENAME-FILE", w_rename, NULL, 0,
     FBRL_DOC("( c-addr1 u1 c-addr2 u2 -- ior )", "rename file 1 to name 2")},
    {"FILE-STATUS", w_status, NULL, 0,
     FBRL_DOC("( c-addr u -- x ior )", "ior 0 if the file exists (x: its R/W bits)")},
    {"INCLUDE-FILE", w_include_file, NULL, 0,
     FBRL_DOC("( i*x fileid -- j*x )",
              "interpret the file fileid was opened on, from its start, and close fileid")},
};

int fbrl__file_words(fbrl_vm *vm)
{
    const fbrl_vm_files *f = fs(vm);
    if (!f || !f->open || !f->close || !f->read || !f->write || !f->seek || !f->tell || !f->size ||
        !f->resize || !f->flush || !f->remove || !f->rename || !f->status)
        return 0; /* a partial file system: no standard file words rather than half of them */
    int r = fbrl__define_words(vm, words, sizeof words / sizeof words[0]);
    if (r)
        return r;
    uint8_t cur = vm->current;
    vm->current = vm->wl_forth2012;
    r = fbrl__define_words(vm, shadowed, sizeof shadowed / sizeof shadowed[0]);
    vm->current = cur;
    return r;
}
