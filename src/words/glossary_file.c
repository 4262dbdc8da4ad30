/* SPDX-License-Identifier: MIT */
/* glossary_file.c - typed data files (thesis appendix I-9) on the fileio module, and
 * SAVE-CAL / LOAD-CAL to keep calibrations in them.
 *
 * OPEN-FILE <hndl filename> makes hndl (if new) a word pushing its handle: a magic cell and
 * the number of its slot in the glossary's file table. A slot is in use while its owner is
 * that handle's address, so a stale, copied or forged handle is refused. Records live in the
 * slot's share of the caller's storage (fbrl_glossary_set_file_storage) and reach the disk
 * atomically on CLOSE-FILE or fbrl_glossary_finish(). */
#include <stdint.h>
#include <string.h>
#include "fbrl/calib.h"
#include "fbrl/fileio.h"
#include "glossary_internal.h"

#define TYPE_MAX 65535 /* largest user type (bytes), as ARRAY's cells */

static size_t share(const fbrl_glossary *g) { return (g->file_mem_size / FBRL_GLOSSARY_FILES) & ~(size_t)15; }

fbrl_status fbrl_glossary_set_file_storage(fbrl_glossary *g, void *mem, size_t size)
{
    if (!g || g->magic != GL_INSTALLED || (!mem && size))
        return FBRL_EINVAL;
    for (int i = 0; i < FBRL_GLOSSARY_FILES; i++)
        if (g->files[i].owner)
            return FBRL_ESTATE;
    g->file_mem = mem;
    g->file_mem_size = mem ? size : 0;
    return FBRL_OK;
}

fbrl_status fbrl_glossary_finish(fbrl_glossary *g)
{
    fbrl_status first = FBRL_OK;
    if (!g || g->magic != GL_INSTALLED)
        return FBRL_EINVAL;
    for (int i = 0; i < FBRL_GLOSSARY_FILES; i++) {
        fbrl_glossary_file *s = &g->files[i];
        if (!s->owner)
            continue;
        fbrl_status st = fbrl_file_close(&s->file);
        if (st != FBRL_OK) {
            fbrl_file_discard(&s->file);
            if (first == FBRL_OK)
                first = st;
        }
        s->owner = 0;
    }
    return first;
}

/* The open file of handle a, or throw naming `word`. */
static fbrl_status file_at(fbrl_vm *vm, fbrl_glossary *g, fbrl_cell a, const char *word,
                           fbrl_glossary_file **s)
{
    fbrl_cell *slot = fbrl_vmx_data(vm, a, &gl_type_hndl, sizeof(fbrl_cell));
    if (!slot)
        return gl_throw(vm, GL_TYPE_MISMATCH, "%s: unknown file handle (OPEN-FILE makes one)", word);
    if (*slot < 0 || *slot >= FBRL_GLOSSARY_FILES || g->files[*slot].owner != a)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ESTATE), "%s: file handle not open", word);
    *s = &g->files[*slot];
    return FBRL_OK;
}

static fbrl_status parse_path(fbrl_vm *vm, const char *word, char *path)
{
    const char *p;
    size_t n;
    fbrl_vm_parse_name(vm, &p, &n);
    if (n == 0)
        return gl_throw(vm, GL_NO_NAME, "%s: file name missing", word);
    if (n >= FBRL_FILE_PATH_MAX)
        return gl_throw_st(vm, FBRL_ENAME, word);
    memcpy(path, p, n);
    path[n] = 0;
    return FBRL_OK;
}

static fbrl_status file_error(fbrl_vm *vm, fbrl_status st, const char *word, const char *path)
{
    return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st), "%s %.64s: %s", word, path, fbrl_status_str(st));
}

static fbrl_status w_create_file(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    char path[FBRL_FILE_PATH_MAX];
    fbrl_status st;
    (void)arg;
    if ((st = parse_path(vm, "CREATE-FILE", path)))
        return st;
    if ((st = fbrl_file_create(path)) != FBRL_OK)
        return file_error(vm, st, "CREATE-FILE", path);
    return FBRL_OK;
}

static fbrl_status w_open_file(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    fbrl_glossary *g = arg;
    char path[FBRL_FILE_PATH_MAX];
    const char *name;
    size_t len;
    fbrl_cell xt, owner = 0;
    fbrl_cell *cells = NULL;
    fbrl_status st;
    int slot;
    fbrl_vm_parse_name(vm, &name, &len);
    if (len == 0)
        return gl_throw(vm, GL_NO_NAME, "OPEN-FILE: handle name missing (OPEN-FILE hndl filename)");
    if (len > FBRL_VMX_NAME_MAX)
        return gl_throw(vm, FBRL_THROW_NAME_TOO_LONG, "OPEN-FILE: handle name too long");
    if ((st = parse_path(vm, "OPEN-FILE", path)))
        return st;
    if (fbrl_vmx_find(vm, name, len, &xt) == FBRL_OK) { /* an existing handle word is reused */
        cells = fbrl_vmx_created(vm, xt, NULL, &owner) == FBRL_OK
                    ? fbrl_vmx_data(vm, owner, &gl_type_hndl, sizeof(fbrl_cell))
                    : NULL;
        if (!cells)
            return gl_throw(vm, GL_TYPE_MISMATCH, "OPEN-FILE: %.*s is defined and is not a file handle",
                            (int)len, name);
        if (*cells >= 0 && *cells < FBRL_GLOSSARY_FILES && g->files[*cells].owner == owner)
            return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ESTATE),
                            "OPEN-FILE: %.*s is open; CLOSE-FILE it first", (int)len, name);
    }
    if (share(g) == 0)
        return gl_throw(vm, FBRL_THROW_UNSUPPORTED,
                        "OPEN-FILE: no file storage (host: fbrl_glossary_set_file_storage)");
    for (slot = 0; slot < FBRL_GLOSSARY_FILES && g->files[slot].owner; slot++) {
    }
    if (slot == FBRL_GLOSSARY_FILES)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "OPEN-FILE: too many open files (%d)",
                        FBRL_GLOSSARY_FILES);
    fbrl_file *f = &g->files[slot].file;
    if ((st = fbrl_file_open(f, path, g->file_mem + (size_t)slot * share(g), share(g))) != FBRL_OK)
        return file_error(vm, st, "OPEN-FILE", path);
    if (!cells) { /* a new handle word: made whole, or not at all */
        void *p;
        st = fbrl_vmx_create(vm, name, len, &gl_type_hndl, sizeof(fbrl_cell), NULL, NULL,
                             FBRL_DOC_TEXT("( -- hndl )"), FBRL_DOC_TEXT("file handle (made by OPEN-FILE)"),
                             &owner, &p);
        if (st != FBRL_OK) {
            fbrl_file_discard(f);
            return st;
        }
        cells = p;
    }
    *cells = slot;
    g->files[slot].owner = owner;
    return FBRL_OK;
}

/* RESET-FILE, APPEND-FILE ( hndl -- ) */
static fbrl_status position(fbrl_vm *vm, fbrl_glossary *g, const void *row, int end)
{
    const char *word = end ? "APPEND-FILE" : "RESET-FILE";
    fbrl_cell a;
    fbrl_glossary_file *s;
    fbrl_status st;
    if ((st = gl_args(vm, row, &a, NULL)) || (st = file_at(vm, g, a, word, &s)))
        return st;
    st = end ? fbrl_file_append(&s->file) : fbrl_file_reset(&s->file);
    return st == FBRL_OK ? st : gl_throw_st(vm, st, word);
}
static fbrl_status w_reset_file(fbrl_vm *vm, void *g, const void *word) { return position(vm, g, word, 0); }
static fbrl_status w_append_file(fbrl_vm *vm, void *g, const void *word) { return position(vm, g, word, 1); }

/* CLOSE-FILE ( hndl -- code ): 0, or the fbrl_status of a failed commit (the file then
 * stays open with its changes: fix the cause and CLOSE-FILE again). */
static fbrl_status w_close_file(fbrl_vm *vm, void *g, const void *word)
{
    fbrl_cell a;
    fbrl_glossary_file *s;
    fbrl_status st;
    if ((st = gl_args(vm, word, &a, NULL)) || (st = file_at(vm, g, a, "CLOSE-FILE", &s)))
        return st;
    st = fbrl_file_close(&s->file);
    if (st == FBRL_OK)
        s->owner = 0;
    return fbrl_vm_push(vm, st);
}

static const char *type_name(fbrl_ftype_code c)
{
    switch (c) {
    case FBRL_FT_CHR: return "CHR";
    case FBRL_FT_INTEGER: return "INTEGER";
    case FBRL_FT_LONG: return "LONG-INTEGER";
    case FBRL_FT_REAL: return "REAL";
    case FBRL_FT_LOCATION: return "LOCATION";
    default: return "user type";
    }
}

/* A refused read says what the next record is, so the program can read it right. */
static fbrl_status read_error(fbrl_vm *vm, const fbrl_file *f, fbrl_status st, fbrl_ftype want,
                              const char *word)
{
    fbrl_ftype have;
    if (st == FBRL_EEOF)
        return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st), "%s: end of file", word);
    if (st != FBRL_ETYPE || fbrl_file_peek(f, &have) != FBRL_OK)
        return gl_throw_st(vm, st, word);
    return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st),
                    "%s: next record is %s (%lu bytes), not %s (%lu bytes); nothing read", word,
                    type_name(have.code), (unsigned long)have.size, type_name(want.code),
                    (unsigned long)want.size);
}

/* The host object the fileio module reads and writes for a built-in type: copied to and
 * from the VM address, which need not be aligned. */
typedef union value {
    unsigned char c;
    int16_t i;
    int32_t l;
    double r;
    fbrl_loc loc;
} value;

/* WRITE-FILE and READ-FILE ( addr type hndl -- ) */
static fbrl_status transfer(fbrl_vm *vm, fbrl_glossary *g, const void *row, int write)
{
    const char *word = write ? "WRITE-FILE" : "READ-FILE";
    fbrl_cell a[3];
    fbrl_glossary_file *s;
    value v;
    fbrl_status st;
    if ((st = gl_args(vm, row, a, NULL)) || (st = file_at(vm, g, a[2], word, &s)))
        return st;
    if (a[1] < 1 || a[1] > TYPE_MAX)
        return gl_throw(vm, GL_BAD_NUMBER, "%s: type must be a size of 1..%d bytes", word, TYPE_MAX);
    if (!fbrl_vm_addr(vm, a[0], (size_t)(a[1])))
        return gl_throw(vm, GL_BAD_ADDRESS, "%s: the variable is not in data space", word);
    fbrl_ftype t = fbrl_ftype_of_size((size_t)a[1]);
    void *obj = t.code == FBRL_FT_USER ? (void *)a[0] : (void *)&v;
    if (write) {
        if (obj == &v)
            memcpy(&v, (void *)a[0], t.size);
        st = fbrl_file_write(&s->file, t, obj);
        if (st == FBRL_ENOSPC)
            return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st),
                            "WRITE-FILE: file full (%lu bytes of records per open file)",
                            (unsigned long)share(g));
        return st == FBRL_OK ? st : gl_throw_st(vm, st, word);
    }
    st = fbrl_file_read(&s->file, t, obj);
    if (st != FBRL_OK)
        return read_error(vm, &s->file, st, t, word);
    if (obj == &v)
        memcpy((void *)a[0], &v, t.size);
    return FBRL_OK;
}
static fbrl_status w_write_file(fbrl_vm *vm, void *g, const void *word) { return transfer(vm, g, word, 1); }
static fbrl_status w_read_file(fbrl_vm *vm, void *g, const void *word) { return transfer(vm, g, word, 0); }

/* SAVE-CAL and LOAD-CAL ( cal-stru hndl -- ): a calibration structure as one user record. */
static fbrl_status cal_record(fbrl_vm *vm, fbrl_glossary *g, const void *row, int save)
{
    const char *word = save ? "SAVE-CAL" : "LOAD-CAL";
    fbrl_cell a[2];
    fbrl_calib *c;
    fbrl_glossary_file *s;
    unsigned char buf[FBRL_CALIB_BYTES];
    fbrl_ftype t = fbrl_ftype_user(FBRL_GLOSSARY_CAL_TAG, FBRL_CALIB_BYTES);
    fbrl_status st;
    if ((st = gl_args(vm, row, a, NULL)) || (st = gl_stru(vm, a[0], save, word, &c)) ||
        (st = file_at(vm, g, a[1], word, &s)))
        return st;
    if (save) {
        fbrl_calib_save(c, buf, sizeof buf);
        st = fbrl_file_write(&s->file, t, buf);
        return st == FBRL_OK ? st : gl_throw_st(vm, st, word);
    }
    if ((st = fbrl_file_read(&s->file, t, buf)) != FBRL_OK) {
        if (st == FBRL_ETYPE)
            return gl_throw(vm, FBRL_VM_THROW_OF_STATUS(st),
                            "LOAD-CAL: next record is not a calibration; nothing read");
        return read_error(vm, &s->file, st, t, word);
    }
    if ((st = fbrl_calib_load(c, buf, sizeof buf)) != FBRL_OK)
        return gl_throw_st(vm, st, word);
    return FBRL_OK;
}
static fbrl_status w_save_cal(fbrl_vm *vm, void *g, const void *word) { return cal_record(vm, g, word, 1); }
static fbrl_status w_load_cal(fbrl_vm *vm, void *g, const void *word) { return cal_record(vm, g, word, 0); }

static const gl_word file_words[] = {
    {"CREATE-FILE", w_create_file, "", 0, 0, 0,
     FBRL_DOC("( \"filename\" -- )",
              "make filename an empty data file (an existing file of that name is replaced)")},
    {"OPEN-FILE", w_open_file, "", 0, 0, 0,
     FBRL_DOC("( \"hndl filename\" -- )",
              "open a data file under handle hndl (made if not defined); reads and verifies it whole")},
    {"RESET-FILE", w_reset_file, "A", 0, 0, 0, FBRL_DOC("( hndl -- )", "position at the first record")},
    {"APPEND-FILE", w_append_file, "A", 0, 0, 0, FBRL_DOC("( hndl -- )", "position after the last record")},
    {"CLOSE-FILE", w_close_file, "A", 0, 0, 0,
     FBRL_DOC("( hndl -- code )",
              "save the file atomically and close it; code 0, or the error (file then stays open)")},
    {"WRITE-FILE", w_write_file, "AIA", 0, 0, 0,
     FBRL_DOC("( addr type hndl -- )", "write the variable at addr as one record of type (CHR INTEGER "
                                       "LONG-INTEGER REAL LOCATION or a size)")},
    {"READ-FILE", w_read_file, "AIA", 0, 0, 0,
     FBRL_DOC("( addr type hndl -- )",
              "read the next record into addr; a record of another type is refused and stays unread")},
    {"SAVE-CAL", w_save_cal, "AA", 0, 0, 0,
     FBRL_DOC("( cal-stru hndl -- )", "write the calibration structure as one record")},
    {"LOAD-CAL", w_load_cal, "AA", 0, 0, 0,
     FBRL_DOC("( cal-stru hndl -- )", "read a calibration record (written by SAVE-CAL) into cal-stru")},
};

fbrl_status gl_install_file(fbrl_vm *vm, fbrl_glossary *g)
{
    return fbrl_vmx_define_table(vm, file_words, sizeof file_words / sizeof file_words[0], g);
}
