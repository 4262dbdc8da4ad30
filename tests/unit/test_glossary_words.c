/* SPDX-License-Identifier: MIT */
/* test_glossary_words.c - docs/glossary.md is the glossary of every thesis word; this test
 * keeps it true. It parses the document's tables and, in a VM with the data glossary and the
 * robot words installed offline (no controller), checks that
 *   - every word listed with a stack effect exists, has HELP text, and its HELP stack
 *     effect is the table's (whitespace normalised);
 *   - every word listed as absent (not applicable, internal to the thesis's implementation,
 *     not bound) is indeed not defined;
 *   - every implemented word cites at least one test, and each cited test really uses the
 *     word: `tests/forth/F.fs:N` = line N of F.fs uses it outside a comment;
 *     `tests/unit/F.c:fn()` = test function fn in F.c uses it in a string.
 * and the other way round: every word the glossary and the robot words define (all but the
 * engine's own) has a row, so a new word missing from the document fails too.
 * It also runs tests/forth/glossary_audit.fs (the words no other test covered) and checks
 * TYPE-STRING's console output. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/cell_words.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/method.h"
#include "fbrl/run.h"
#include "fbrl/vm.h"
#include "support/vm_host.h"

#define GLOSSARY  FBRL_TEST_SRCDIR "/docs/glossary.md"
#define FORTH_DIR FBRL_TEST_SRCDIR "/tests/forth/"

/* ---- an offline VM: console into a text, source files through stdio (support/vm_host.h) ---- */
typedef struct fixture {
    unsigned char *mem;
    fbrl_vm *vm;
    fbrl_glossary g;
    fbrl_robot r;
    fbrl_cell_words cell;
    fbrl_method_set methods;
    fbrl_run run;
    vmh_text out;
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(4 << 20); /* glibc: 16-byte aligned */
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = 4 << 20;
    cfg.host.user = &f->out;
    cfg.host.write = vmh_write;
    vmh_use_files(&cfg.host);
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(fbrl_robot_install(f->vm, &f->r, NULL, &f->g), FBRL_OK);
    assert_int_equal(fbrl_cell_install(f->vm, &f->cell, &f->r, &f->g), FBRL_OK);
    assert_int_equal(fbrl_method_install(f->vm, &f->methods), FBRL_OK);
    assert_int_equal(fbrl_run_install(&f->run, f->vm, &f->methods, NULL, &f->r), FBRL_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    assert_int_equal(fbrl_glossary_finish(&f->g), FBRL_OK);
    free(f->mem);
    free(f);
    return 0;
}

/* ---- reading the document ---- */
#define MAX_CELLS 8
#define LINE_MAX_ 4096

typedef struct row {
    char cell[MAX_CELLS][LINE_MAX_];
    int n;
} row;

/* Split a table line at the '|' that are not escaped as "\|"; cells trimmed, "\|" -> "|". */
static void split_row(const char *line, row *r)
{
    r->n = 0;
    const char *p = strchr(line, '|');
    if (!p)
        return;
    p++;
    while (*p && *p != '\n' && r->n < MAX_CELLS) {
        char *o = r->cell[r->n];
        size_t k = 0;
        while (*p && *p != '\n' && *p != '|') {
            if (p[0] == '\\' && p[1] == '|')
                p++;
            if (k < LINE_MAX_ - 1)
                o[k++] = *p;
            p++;
        }
        if (*p != '|')
            break; /* text after the last '|' is not a cell */
        p++;
        while (k && isspace((unsigned char)o[k - 1]))
            k--;
        o[k] = 0;
        size_t lead = 0;
        while (isspace((unsigned char)o[lead]))
            lead++;
        memmove(o, o + lead, k - lead + 1);
        r->n++;
    }
}

/* The n-th `backticked` piece of s into out; 0 if there is none. */
static int backticked(const char *s, int n, char *out, size_t cap)
{
    for (;;) {
        const char *a = strchr(s, '`');
        if (!a)
            return 0;
        const char *b = strchr(a + 1, '`');
        if (!b)
            return 0;
        if (n-- == 0) {
            size_t len = (size_t)(b - a - 1);
            if (len >= cap)
                len = cap - 1;
            memcpy(out, a + 1, len);
            out[len] = 0;
            return 1;
        }
        s = b + 1;
    }
}

static void normalise(const char *s, char *out, size_t cap)
{
    size_t k = 0;
    int space = 0;
    for (; *s && k < cap - 1; s++) {
        if (isspace((unsigned char)*s)) {
            space = k > 0;
            continue;
        }
        if (space && k < cap - 1)
            out[k++] = ' ';
        space = 0;
        out[k++] = *s;
    }
    out[k] = 0;
}

/* Does text hold word as a token (case-insensitive), tokens split at the characters in delims? */
static int has_token(const char *text, size_t len, const char *word, const char *delims)
{
    size_t wl = strlen(word);
    for (size_t i = 0; i + wl <= len; i++) {
        if (i > 0 && !strchr(delims, text[i - 1]))
            continue;
        if (i + wl < len && !strchr(delims, text[i + wl]))
            continue;
        size_t j = 0;
        while (j < wl && toupper((unsigned char)text[i + j]) == toupper((unsigned char)word[j]))
            j++;
        if (j == wl)
            return 1;
    }
    return 0;
}

/* A Forth line uses word outside its \ comment. */
static int forth_line_uses(const char *line, const char *word)
{
    size_t len = strlen(line);
    for (size_t i = 0; i < len; i++)
        if (line[i] == '\\' && (i == 0 || isspace((unsigned char)line[i - 1])) &&
            (i + 1 == len || isspace((unsigned char)line[i + 1]))) {
            len = i;
            break;
        }
    return has_token(line, len, word, " \t\r\n\""); /* a word may be in an S" string */
}

/* A C line uses word inside one of its string literals. */
static int c_line_uses(const char *line, const char *word)
{
    const char *p = line;
    for (;;) {
        const char *a = strchr(p, '"');
        if (!a)
            return 0;
        const char *b = a + 1;
        while (*b && *b != '"')
            b += (b[0] == '\\' && b[1]) ? 2 : 1;
        if (!*b)
            return 0;
        if (has_token(a + 1, (size_t)(b - a - 1), word, " \t\\\""))
            return 1;
        p = b + 1;
    }
}

/* Check one citation of word; on failure say why in why[]. */
static int citation_ok(const char *cite, const char *word, char *why, size_t cap)
{
    char path[512], spec[256];
    const char *colon = strrchr(cite, ':');
    if (!colon || (size_t)(colon - cite) >= 256 || strlen(colon + 1) >= sizeof spec) {
        snprintf(why, cap, "citation '%s' is not file:line or file:function()", cite);
        return 0;
    }
    snprintf(path, sizeof path, "%s/%.*s", FBRL_TEST_SRCDIR, (int)(colon - cite), cite);
    strcpy(spec, colon + 1);
    FILE *fp = fopen(path, "r");
    if (!fp) {
        snprintf(why, cap, "cited file %s does not exist", path);
        return 0;
    }
    static char line[LINE_MAX_];
    int found = 0;
    size_t speclen = strlen(spec);
    if (speclen > 2 && strcmp(spec + speclen - 2, "()") == 0) {
        /* a test function: from its definition line to the closing brace in column 0 */
        spec[speclen - 2] = 0;
        int inside = 0;
        while (!found && fgets(line, sizeof line, fp)) {
            if (!inside) {
                const char *p = strstr(line, spec);
                if (line[0] != ' ' && strncmp(line, "static ", 7) == 0 && p && p[strlen(spec)] == '(' &&
                    !isalnum((unsigned char)p[-1]) && p[-1] != '_')
                    inside = 1;
            } else if (line[0] == '}') {
                break;
            } else {
                found = c_line_uses(line, word);
            }
        }
        if (!found)
            snprintf(why, cap, "%s: function %s() does not use %s in a string", path, spec, word);
    } else {
        char *end;
        long want = strtol(spec, &end, 10);
        if (*end || want < 1) {
            snprintf(why, cap, "citation '%s': bad line number", cite);
            fclose(fp);
            return 0;
        }
        long n = 0;
        while (fgets(line, sizeof line, fp))
            if (++n == want) {
                found = forth_line_uses(line, word);
                break;
            }
        if (!found)
            snprintf(why, cap, "%s:%ld does not use %s (outside a comment)", path, want, word);
    }
    fclose(fp);
    return found;
}

typedef struct tally {
    int implemented, absent, citations;
} tally;

/* Every word name check_text() saw in a word column (for the reverse check). */
static char documented[1024][64];
static int ndocumented;

/* The next line of text (up to '\n') into line; 0 at the end. */
static int next_line(const char **p, char *line, size_t cap)
{
    if (!**p)
        return 0;
    const char *e = strchr(*p, '\n');
    size_t len = e ? (size_t)(e - *p) : strlen(*p);
    if (len >= cap)
        len = cap - 1;
    memcpy(line, *p, len);
    line[len] = 0;
    *p = e ? e + 1 : *p + strlen(*p);
    return 1;
}

/* Check a glossary document's text; returns the number of problems (each printed). */
static int check_text(fixture *f, const char *doc, tally *t)
{
    static char line[LINE_MAX_];
    static row hdr, r;
    static char seen[512][64];
    int nseen = 0, c_word = -1, c_stack = -1, c_test = -1, c_absent = -1, failures = 0;
    long ln = 0;
    char why[1024];
    const char *p = doc;
    while (next_line(&p, line, sizeof line)) {
        ln++;
        if (line[0] != '|') {
            c_word = c_absent = -1; /* a table ends at the first line that is not a row */
            continue;
        }
        if (strncmp(p, "|---", 4) == 0) {
            /* a table's header: find the columns this test reads, skip the separator */
            split_row(line, &hdr);
            c_word = c_stack = c_test = c_absent = -1;
            for (int k = 0; k < hdr.n; k++) {
                if (strcmp(hdr.cell[k], "word") == 0)
                    c_word = k;
                if (strcmp(hdr.cell[k], "stack effect") == 0)
                    c_stack = k;
                if (strcmp(hdr.cell[k], "test") == 0)
                    c_test = k;
                if (strcmp(hdr.cell[k], "absent word") == 0)
                    c_absent = k;
            }
            if (c_stack < 0 || c_test < 0)
                c_word = -1; /* not a glossary table */
            next_line(&p, line, sizeof line);
            ln++;
            continue;
        }
        split_row(line, &r);
        char name[64], want[256], got[256];
        if (c_word >= 0 && r.n > c_word && r.n > c_stack && r.n > c_test) {
            if (!backticked(r.cell[c_word], 0, name, sizeof name)) {
                print_error("glossary.md:%ld: no `word` in the first cell\n", ln);
                failures++;
                continue;
            }
            char extra[64];
            if (backticked(r.cell[c_word], 1, extra, sizeof extra)) {
                print_error("glossary.md:%ld: one word per row (%s, %s)\n", ln, name, extra);
                failures++;
            }
            for (int k = 0; k < nseen; k++)
                if (strcmp(seen[k], name) == 0) {
                    print_error("glossary.md:%ld: %s is listed twice\n", ln, name);
                    failures++;
                }
            if (nseen < 512)
                strcpy(seen[nseen++], name);
            if (ndocumented < 1024)
                strcpy(documented[ndocumented++], name);
            const char *stack = NULL, *help = NULL;
            if (fbrl_vm_help(f->vm, name, &stack, &help) != FBRL_OK) {
                print_error("glossary.md:%ld: %s is listed as implemented but is not defined\n", ln, name);
                failures++;
            } else {
                char raw[256] = "";
                backticked(r.cell[c_stack], 0, raw, sizeof raw);
                normalise(raw, want, sizeof want);
                normalise(stack ? stack : "", got, sizeof got);
                if (!help || !*help || !*got) {
                    print_error("glossary.md:%ld: %s has no HELP text\n", ln, name);
                    failures++;
                }
                if (strcmp(want, got) != 0) {
                    print_error("glossary.md:%ld: %s: the table says '%s', HELP says '%s'\n", ln, name, want,
                                got);
                    failures++;
                }
            }
            int cites = 0;
            char cite[512];
            while (backticked(r.cell[c_test], cites, cite, sizeof cite)) {
                if (!citation_ok(cite, name, why, sizeof why)) {
                    print_error("glossary.md:%ld: %s: %s\n", ln, name, why);
                    failures++;
                }
                cites++;
            }
            if (!cites) {
                print_error("glossary.md:%ld: %s cites no test\n", ln, name);
                failures++;
            }
            t->citations += cites;
            t->implemented++;
        } else if (c_absent >= 0 && r.n > c_absent) {
            for (int k = 0; backticked(r.cell[c_absent], k, name, sizeof name); k++) {
                const char *stack = NULL, *help = NULL;
                if (fbrl_vm_help(f->vm, name, &stack, &help) == FBRL_OK) {
                    print_error("glossary.md:%ld: %s is listed as absent but is defined\n", ln, name);
                    failures++;
                }
                t->absent++;
            }
        }
    }
    return failures;
}

static void check_document(fixture *f, tally *t)
{
    FILE *fp = fopen(GLOSSARY, "rb");
    assert_non_null(fp);
    static char doc[1 << 20];
    size_t len = fread(doc, 1, sizeof doc - 1, fp);
    fclose(fp);
    assert_true(len > 0 && len < sizeof doc - 1);
    doc[len] = 0;
    assert_int_equal(check_text(f, doc, t), 0);
}

static void glossary_matches_the_words(void **state)
{
    fixture *f = *state;
    tally t = {0, 0, 0};
    check_document(f, &t);
    print_message("docs/glossary.md: %d implemented words (%d test citations checked), %d absent names\n",
                  t.implemented, t.citations, t.absent);
    /* the thesis's appendices list 183 words: 167 are implemented, the additions come on top */
    assert_true(t.implemented >= 167);
    assert_true(t.absent >= 16);
}

/* ---- the other way: every word of the word sets has a row ---- */
typedef struct names {
    char (*name)[64];
    int n, cap;
} names;

static int collect(void *ctx, const char *name, size_t len)
{
    names *s = ctx;
    if (s->n < s->cap && len < 64) {
        memcpy(s->name[s->n], name, len);
        s->name[s->n++][len] = 0;
    }
    return 0;
}

static int has(const names *s, const char *name)
{
    for (int k = 0; k < s->n; k++)
        if (strcmp(s->name[k], name) == 0)
            return 1;
    return 0;
}

/* The words of f's VM that a bare VM (the engine and its data words) lacks, except internal
 * "(names)", and that the last document checked did not list; each is printed. */
static int undocumented(fixture *f, int print)
{
    static char all_buf[2048][64], bare_buf[2048][64];
    names all = {all_buf, 0, 2048}, bare = {bare_buf, 0, 2048};
    size_t size = 1 << 20;
    unsigned char *mem = malloc(size);
    assert_non_null(mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = size;
    fbrl_vm *vm;
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_OK);
    fbrl_vm_words(vm, collect, &bare);
    free(mem);
    fbrl_vm_words(f->vm, collect, &all);
    assert_true(all.n < all.cap && bare.n < bare.cap);
    int missing = 0;
    for (int k = 0; k < all.n; k++) {
        const char *w = all.name[k];
        if (w[0] == '(' || has(&bare, w))
            continue;
        int listed = 0;
        for (int d = 0; d < ndocumented && !listed; d++)
            listed = strcmp(documented[d], w) == 0;
        if (!listed) {
            if (print)
                print_error("docs/glossary.md has no row for %s\n", w);
            missing++;
        }
    }
    return missing;
}

static void every_word_is_in_the_glossary(void **state)
{
    fixture *f = *state;
    tally t = {0, 0, 0};
    ndocumented = 0;
    check_document(f, &t);
    assert_int_equal(undocumented(f, 1), 0);
    /* and the check can fail: a document of two rows leaves almost every word out */
    static const char two[] = "| word | stack effect | test |\n|---|---|---|\n"
                              "| `DEQ-L` | `( q-addr -- c )` | `tests/forth/glossary_audit.fs:9` |\n"
                              "| `JOG` | `( F: dX dY dZ -- )` | `tests/forth/robot_motion.fs:51` |\n";
    ndocumented = 0;
    assert_int_equal(check_text(f, two, &t), 0);
    int n = undocumented(f, 0);
    print_message("a two-row glossary leaves %d words undocumented\n", n);
    assert_true(n >= 100);
}

/* The checks themselves can fail: a wrong effect, a missing or an extra word, a bad citation. */
static void checks_catch_drift(void **state)
{
    fixture *f = *state;
    tally t = {0, 0, 0};
    static const char good[] =
        "## I-1\n\n"
        "| word | stack effect | thesis | test |\n"
        "|---|---|---|---|\n"
        "| `DEQ-L` | `(  q-addr   -- c )` | as DEQ | `tests/forth/glossary_audit.fs:9` |\n"
        "| `TYPE-STRING` | `( str -- )` | | `tests/unit/test_glossary_words.c:type_string_prints()` |\n"
        "\n| absent word | why |\n|---|---|\n| `INSTALL-INTERRUPT` `COM` | DOS |\n";
    assert_int_equal(check_text(f, good, &t), 0);
    assert_int_equal(t.implemented, 2);
    assert_int_equal(t.absent, 2);
    static const char *const bad[] = {
        /* HELP says ( q-addr -- c ) */
        "| word | stack effect | test |\n|---|---|---|\n| `DEQ-L` | `( q -- c )` | "
        "`tests/forth/glossary_audit.fs:9` |\n",
        /* not defined */
        "| word | stack effect | test |\n|---|---|---|\n| `RAPL-ANALOG` | `( -- )` | "
        "`tests/forth/glossary_audit.fs:9` |\n",
        /* defined */
        "| absent word | why |\n|---|---|\n| `COM` `DEQ-L` | |\n",
        /* no citation */
        "| word | stack effect | test |\n|---|---|---|\n| `DEQ-L` | `( q-addr -- c )` | none |\n",
        /* the line does not use the word; only its comment does (line 12); no such file; no such function */
        "| word | stack effect | test |\n|---|---|---|\n| `DEQ-L` | `( q-addr -- c )` | "
        "`tests/forth/glossary_audit.fs:8` |\n",
        "| word | stack effect | test |\n|---|---|---|\n| `DEQ` | `( q-addr -- c )` | "
        "`tests/forth/glossary_audit.fs:12` |\n",
        "| word | stack effect | test |\n|---|---|---|\n| `DEQ-L` | `( q-addr -- c )` | "
        "`tests/forth/no-such.fs:1` |\n",
        "| word | stack effect | test |\n|---|---|---|\n| `TYPE-STRING` | `( str -- )` | "
        "`tests/unit/test_glossary_words.c:no_such()` |\n",
        /* listed twice */
        ("| word | stack effect | test |\n|---|---|---|\n| `DEQ-L` | `( q-addr -- c )` | "
         "`tests/forth/glossary_audit.fs:9` |\n"
         "| `DEQ-L` | `( q-addr -- c )` | `tests/forth/glossary_audit.fs:9` |\n"),
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        print_message("expected problem %zu:\n", k);
        assert_true(check_text(f, bad[k], &t) >= 1);
    }
    row r;
    split_row("| `A` | `( a \\| b )` | x |", &r);
    assert_int_equal(r.n, 3);
    assert_string_equal(r.cell[1], "`( a | b )`");
}

/* ---- the words no other test covered ---- */
static void type_string_prints(void **state)
{
    fixture *f = *state;
    const char *src = "10 STRING TS  TS STRING-LIT \"ROBOT\"  TS TYPE-STRING  TS NULL-STRING TS TYPE-STRING";
    f->out.n = 0;
    assert_int_equal(fbrl_vm_eval(f->vm, src, strlen(src)), FBRL_OK);
    assert_string_equal(f->out.s, "ROBOT");
}

static void run_forth(fixture *f, const char *file);

static void forth_glossary_audit(void **state) { run_forth(*state, "glossary_audit.fs"); }

/* The work-cell words (tests/forth/cell_words.fs), and the one clear message each bad
 * description gets. */
static void forth_robot_cell(void **state)
{
    fixture *f = *state;
    run_forth(f, "cell_words.fs");
    static const struct {
        const char *text, *says;
    } bad[] = {
        {"CELL-CLEAR 0E0 0E0 0E0 1E0 1E0 1E0 CELL-BOX B 0E0 0E0 0E0 1E0 1E0 1E0 CELL-BOX b",
         "CELL-BOX: B is already an obstacle of the cell"},
        {"0E0 0E0 0E0 -1E0 1E0 1E0 CELL-BOX NEG", "CELL-BOX: NEG: every size must be positive"},
        {"0E0 0E0 0E0 0E0 1E0 CELL-CYLINDER THIN", "CELL-CYLINDER: THIN: every size must be positive"},
        {"CREATE-LOC IN-IT 5E0 5E0 1E0 0E0 -90E0 0E0 IN-IT DEFINE-LOC 4E0 4E0 0E0 6E0 6E0 2E0 CELL-BOX HULL",
         "CELL-BOX: location IN-IT (X 5.0000 Y 5.0000 Z 1.0000) lies inside HULL"},
        {"-1E0 1E0 CELL-TOOL", "CELL-TOOL: the tool's length and radius must not be negative"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_not_equal(fbrl_vm_eval(f->vm, bad[k].text, strlen(bad[k].text)), FBRL_OK);
        const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
        if (strstr(e->message, bad[k].says) == NULL)
            print_error("%s\n  says '%s'\n  want '%s'\n", bad[k].text, e->message, bad[k].says);
        assert_non_null(strstr(e->message, bad[k].says));
    }
}

static void run_forth(fixture *f, const char *file)
{
    char path[512];
    snprintf(path, sizeof path, "%s%s", FORTH_DIR, file);
    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "tester.fs"), FBRL_OK);
    fbrl_status st = fbrl_vm_include(f->vm, path);
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
        print_error("%s: error %d (%s) at '%s' %s:%lu\n%s\n", file, e->throw_code, e->message, e->word,
                    e->file, e->line, f->out.s);
    }
    assert_int_equal(st, FBRL_OK);
    const char *q = "#ERRORS @ #TESTS @";
    assert_int_equal(fbrl_vm_eval(f->vm, q, strlen(q)), FBRL_OK);
    fbrl_cell tests = 0, errors = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &tests), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &errors), FBRL_OK);
    if (errors)
        print_error("%s: %ld failures:\n%s\n", file, (long)errors, f->out.s);
    assert_int_equal(errors, 0);
    assert_true(tests >= 5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(glossary_matches_the_words, setup, teardown),
        cmocka_unit_test_setup_teardown(checks_catch_drift, setup, teardown),
        cmocka_unit_test_setup_teardown(every_word_is_in_the_glossary, setup, teardown),
        cmocka_unit_test_setup_teardown(type_string_prints, setup, teardown),
        cmocka_unit_test_setup_teardown(forth_glossary_audit, setup, teardown),
        cmocka_unit_test_setup_teardown(forth_robot_cell, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
