/* SPDX-License-Identifier: MIT */
/* test_workspace.c - the workspace module (include/fbrl/workspace.h) in real VMs with the
 * glossary and the robot words, on real files:
 *  - what one VM saves, another loads: every kind of object, by name, with the settings;
 *  - a file cut at every byte or with any one byte changed is refused and the session is
 *    exactly as before (values, words);
 *  - a name that is another kind of word here: refused, nothing made;
 *  - a dictionary that fills in the middle of a load: the words made are forgotten again;
 *  - SAVE-WORKSPACE never replaces a data file of another kind;
 *  - WORKSPACE-CHANGED? follows changes. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "fbrl/glossary.h"
#include "fbrl/matrix.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "fbrl/workspace.h"
#include "support/vm_host.h"

#define WS_BUF (64 * 1024)

typedef struct fixture {
    void *mem;
    vmh_text out;
    fbrl_vm *vm;
    fbrl_glossary g;
    fbrl_robot r;
    fbrl_workspace ws;
    unsigned char buf[WS_BUF];
} fixture;

static fixture *new_vm(size_t mem_size)
{
    fixture *f = calloc(1, sizeof *f);
    fbrl_vm_config cfg;
    assert_non_null(f);
    f->mem = malloc(mem_size);
    assert_non_null(f->mem);
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = mem_size;
    cfg.host.user = &f->out;
    cfg.host.write = vmh_write;
    vmh_use_files(&cfg.host);
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(fbrl_robot_install(f->vm, &f->r, NULL, &f->g), FBRL_OK);
    assert_int_equal(fbrl_workspace_install(f->vm, &f->ws, &f->g, &f->r, f->buf, sizeof f->buf), FBRL_OK);
    return f;
}

static void free_vm(fixture *f)
{
    free(f->mem);
    free(f);
}

static void eval(fixture *f, const char *text)
{
    fbrl_status st = fbrl_vm_eval(f->vm, text, strlen(text));
    if (st != FBRL_OK)
        fail_msg("%s: %s", text, fbrl_vm_last_error(f->vm)->message);
}

static fbrl_cell pop(fixture *f)
{
    fbrl_cell v = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &v), FBRL_OK);
    return v;
}

static int defined(fixture *f, const char *name)
{
    fbrl_cell xt;
    return fbrl_vmx_find(f->vm, name, strlen(name), &xt) == FBRL_OK;
}

static void *object(fixture *f, const char *name, fbrl_glossary_kind want)
{
    fbrl_cell xt;
    fbrl_glossary_kind k;
    void *p;
    assert_int_equal(fbrl_vmx_find(f->vm, name, strlen(name), &xt), FBRL_OK);
    assert_int_equal(fbrl_glossary_object(&f->g, xt, &k, &p), FBRL_OK);
    assert_int_equal(k, want);
    return p;
}

static const char *path(const char *name)
{
    static char p[512];
    snprintf(p, sizeof p, "%s/ws-%ld-%s", FBRL_TEST_BINDIR, (long)getpid(), name);
    return p;
}

/* A session with one of everything. */
static void populate(fixture *f)
{
    eval(f, "CREATE-LOC P 14E0 2E0 8E0 10E0 -90E0 5E0 P DEFINE-LOC "
            "P 0.5E0 1E0 0E0 RECTMAT RACK  P 0.2E0 1E0 0.5E0 RADMAT RING "
            "CREATE-CAL C1 C1 1 P SET-CAL CREATE-CAL-STRU CS "
            "1.5E0 CS 4 CAL-STRU! CS WITH-CAL MAP-ON "
            "5 OUTPUT-DEVICE VALVE 250 VALVE PULSE-WIDTH 3 INPUT-DEVICE SENSOR "
            "1E0 2E0 0E0 30E0 BASE-OFFSET");
}

static void round_trip(void **state)
{
    fixture *a = new_vm(1 << 20), *b = new_vm(1 << 20);
    fbrl_workspace_counts n;
    char why[160];
    int changed = -1;
    (void)state;
    populate(a);
    remove(path("rt.ws"));
    assert_int_equal(fbrl_workspace_save(&a->ws, path("rt.ws"), &n), FBRL_OK);
    assert_int_equal(n.locs, 1);
    assert_int_equal(n.matrices, 2);
    assert_int_equal(n.cals, 2);
    assert_int_equal(n.devices, 2);
    assert_int_equal(fbrl_workspace_changed(&a->ws, &changed, NULL), FBRL_OK);
    assert_int_equal(changed, 0);

    assert_int_equal(fbrl_workspace_load(&b->ws, path("rt.ws"), &n, why, sizeof why), FBRL_OK);
    assert_int_equal(fbrl_workspace_changed(&b->ws, &changed, NULL), FBRL_OK);
    assert_int_equal(changed, 0); /* as loaded */
    const fbrl_loc *p = object(b, "P", FBRL_GLOSSARY_LOC);
    assert_true(p->x == 14.0 && p->y == 2.0 && p->z == 8.0 && p->o == 10.0 && p->a == -90.0 && p->t == 5.0);
    const fbrl_rectmat *rm = object(b, "RACK", FBRL_GLOSSARY_RECTMAT);
    assert_true(rm->dx == 0.5 && rm->dy == 1.0 && rm->base.x == 14.0);
    const fbrl_radmat *dm = object(b, "RING", FBRL_GLOSSARY_RADMAT);
    const fbrl_radmat *da = object(a, "RING", FBRL_GLOSSARY_RADMAT);
    assert_memory_equal(dm, da, sizeof *dm); /* r0, a0 rebuilt exactly */
    const fbrl_calpts *c = object(b, "C1", FBRL_GLOSSARY_CAL);
    assert_true(c->p[0].x == 14.0 && c->p[1].x == 0.0);
    /* the matrix runs in the new VM: RACK (1, 0, 0) */
    eval(b, "CREATE-LOC Q 1 0 0 Q RACK Q GETX F>S");
    assert_int_equal(pop(b), 14); /* 14.5 truncated */
    /* settings: MAP-ON with CS, the shift 1.5 in x; BASE-OFFSET */
    eval(b, "MAPPING? CS 4 CAL-STRU@ F>S");
    assert_int_equal(pop(b), 1);
    assert_int_equal(pop(b), -1);
    double base[4];
    assert_int_equal(fbrl_robot_base_offset(&b->r, base), FBRL_OK);
    assert_true(base[0] == 1.0 && base[1] == 2.0 && base[3] == 30.0);
    fbrl_robot_device d;
    fbrl_cell xt;
    assert_int_equal(fbrl_vmx_find(b->vm, "VALVE", 5, &xt), FBRL_OK);
    assert_int_equal(fbrl_robot_device_of(&b->r, xt, &d), FBRL_OK);
    assert_true(d.port == 5 && d.output == 1 && d.pulse_ms == 250);
    assert_int_equal(fbrl_vmx_find(b->vm, "SENSOR", 6, &xt), FBRL_OK);
    assert_int_equal(fbrl_robot_device_of(&b->r, xt, &d), FBRL_OK);
    assert_true(d.port == 3 && d.output == 0);
    /* a change shows (Q, made above, is one already) */
    assert_int_equal(fbrl_workspace_changed(&b->ws, &changed, NULL), FBRL_OK);
    assert_int_equal(changed, 1);
    assert_int_equal(fbrl_workspace_save(&b->ws, path("rt.ws"), NULL), FBRL_OK);
    eval(b, "WORKSPACE-CHANGED? 3E0 P SETZ WORKSPACE-CHANGED?");
    assert_int_equal(pop(b), -1);
    assert_int_equal(pop(b), 0);
    /* loading into a session that has P updates P in place */
    eval(b, "' P");
    fbrl_cell before = pop(b);
    assert_int_equal(fbrl_workspace_load(&b->ws, path("rt.ws"), NULL, why, sizeof why), FBRL_OK);
    eval(b, "' P P GETZ F>S");
    assert_int_equal(pop(b), 8);
    assert_int_equal(pop(b), before);
    remove(path("rt.ws"));
    free_vm(a);
    free_vm(b);
}

static size_t read_all(const char *p, unsigned char *buf, size_t cap)
{
    FILE *f = fopen(p, "rb");
    assert_non_null(f);
    size_t n = fread(buf, 1, cap, f);
    fclose(f);
    return n;
}

static void write_all(const char *p, const unsigned char *buf, size_t n)
{
    FILE *f = fopen(p, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(buf, 1, n, f), n);
    fclose(f);
}

/* Every cut and every changed byte: refused, the session unchanged. */
static void damaged_files_change_nothing(void **state)
{
    fixture *a = new_vm(1 << 20), *b = new_vm(1 << 20);
    static unsigned char good[8192], bad[8192];
    char why[160];
    size_t n, k, refused = 0;
    (void)state;
    populate(a);
    remove(path("good.ws"));
    assert_int_equal(fbrl_workspace_save(&a->ws, path("good.ws"), NULL), FBRL_OK);
    n = read_all(path("good.ws"), good, sizeof good);
    assert_true(n > 100 && n < sizeof good);
    eval(b, "CREATE-LOC P 1E0 2E0 3E0 4E0 5E0 6E0 P DEFINE-LOC");
    fbrl_loc p0 = *(fbrl_loc *)object(b, "P", FBRL_GLOSSARY_LOC);
    for (k = 0; k < 2 * n; k++) {
        size_t len = n;
        memcpy(bad, good, n);
        if (k < n)
            len = k; /* cut after k bytes */
        else
            bad[k - n] ^= 0x5A; /* one byte changed */
        write_all(path("bad.ws"), bad, len);
        why[0] = 0;
        fbrl_status st = fbrl_workspace_load(&b->ws, path("bad.ws"), NULL, why, sizeof why);
        if (st == FBRL_OK)
            fail_msg("damaged file %zu (%s) was loaded", k, k < n ? "cut" : "changed");
        assert_true(why[0] != 0);
        refused++;
    }
    const fbrl_loc *p = object(b, "P", FBRL_GLOSSARY_LOC);
    assert_memory_equal(p, &p0, sizeof p0);
    assert_false(defined(b, "RACK") || defined(b, "VALVE") || defined(b, "C1"));
    eval(b, "MAPPING?");
    assert_int_equal(pop(b), 0);
    print_message("%zu damaged copies of a %zu-byte workspace refused\n", refused, n);
    remove(path("good.ws"));
    remove(path("bad.ws"));
    free_vm(a);
    free_vm(b);
}

static void name_conflict_changes_nothing(void **state)
{
    fixture *a = new_vm(1 << 20), *b = new_vm(1 << 20);
    char why[160];
    (void)state;
    populate(a);
    remove(path("c.ws"));
    assert_int_equal(fbrl_workspace_save(&a->ws, path("c.ws"), NULL), FBRL_OK);
    eval(b, "CREATE-LOC P 7E0 7E0 7E0 0E0 0E0 0E0 P DEFINE-LOC : RACK 42 ;");
    assert_int_equal(fbrl_workspace_load(&b->ws, path("c.ws"), NULL, why, sizeof why), FBRL_ETYPE);
    assert_non_null(strstr(why, "RACK is another word here, a RECTMAT in the file"));
    eval(b, "P GETX F>S RACK");
    assert_int_equal(pop(b), 42);
    assert_int_equal(pop(b), 7);
    assert_false(defined(b, "RING") || defined(b, "VALVE"));
    remove(path("c.ws"));
    free_vm(a);
    free_vm(b);
}

/* A dictionary that fills halfway through making the words: all of them forgotten. */
static void full_dictionary_takes_back(void **state)
{
    fixture *a = new_vm(1 << 20), *b = new_vm(1 << 20);
    char why[160], text[64];
    int i;
    (void)state;
    for (i = 0; i < 40; i++) {
        snprintf(text, sizeof text, "CREATE-LOC L%d", i);
        eval(a, text);
    }
    remove(path("f.ws"));
    assert_int_equal(fbrl_workspace_save(&a->ws, path("f.ws"), NULL), FBRL_OK);
    eval(b, "UNUSED 2000 - ALLOT UNUSED");
    fbrl_cell unused = pop(b);
    assert_int_equal(fbrl_workspace_load(&b->ws, path("f.ws"), NULL, why, sizeof why), FBRL_ENOMEM);
    assert_non_null(strstr(why, "dictionary is full"));
    for (i = 0; i < 40; i++) {
        snprintf(text, sizeof text, "L%d", i);
        assert_false(defined(b, text));
    }
    eval(b, "UNUSED");
    assert_int_equal(pop(b), unused);
    remove(path("f.ws"));
    free_vm(a);
    free_vm(b);
}

static void save_keeps_other_data(void **state)
{
    fixture *a = new_vm(1 << 20);
    fbrl_file f;
    unsigned char buf[256], before[256], after[256];
    (void)state;
    remove(path("d.dat"));
    assert_int_equal(fbrl_file_create(path("d.dat")), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, path("d.dat"), buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_integer(&f, 7), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    size_t n = read_all(path("d.dat"), before, sizeof before);
    populate(a);
    assert_int_equal(fbrl_workspace_save(&a->ws, path("d.dat"), NULL), FBRL_EFORMAT);
    assert_int_equal(read_all(path("d.dat"), after, sizeof after), n);
    assert_memory_equal(before, after, n);
    /* and LOAD-WORKSPACE of it says it is not a workspace */
    char why[160];
    assert_int_equal(fbrl_workspace_load(&a->ws, path("d.dat"), NULL, why, sizeof why), FBRL_EFORMAT);
    assert_non_null(strstr(why, "not a workspace"));
    remove(path("d.dat"));
    free_vm(a);
}

/* What a save would change in a file, object by object, before it overwrites anything. */
typedef struct deltas {
    char text[1024];
} deltas;

static void note_delta(void *ctx, const fbrl_workspace_delta *d)
{
    deltas *ds = ctx;
    size_t n = strlen(ds->text);
    static const char *const how[] = {"", "added", "changed", "dropped"};
    snprintf(ds->text + n, sizeof ds->text - n, "%s %s %s %g>%g;", how[d->change], d->name[0] ? d->name : "-",
             d->kind, d->was ? d->was[0] : -1.0, d->now ? d->now[0] : -1.0);
}

static void what_a_save_would_change(void **state)
{
    fixture *a = new_vm(1 << 20), *b = new_vm(1 << 20);
    deltas ds;
    unsigned count = 99;
    unsigned char before[WS_BUF], after[WS_BUF];
    (void)state;
    populate(a);
    eval(a, "CREATE-LOC GONE 1E0 2E0 3E0 0E0 -90E0 0E0 GONE DEFINE-LOC");
    remove(path("diff.ws"));
    assert_int_equal(fbrl_workspace_diff(&a->ws, path("diff.ws"), note_delta, &ds, &count), FBRL_ENOENT);
    assert_int_equal(fbrl_workspace_save(&a->ws, path("diff.ws"), NULL), FBRL_OK);
    memset(&ds, 0, sizeof ds);
    assert_int_equal(fbrl_workspace_diff(&a->ws, path("diff.ws"), note_delta, &ds, &count), FBRL_OK);
    assert_int_equal(count, 0);
    assert_string_equal(ds.text, "");
    /* another session: P taught elsewhere, a new place, GONE never made, MAP-OFF */
    populate(b);
    eval(b, "14.5E0 P SETX  CREATE-LOC NEW 5E0 5E0 5E0 0E0 -90E0 0E0 NEW DEFINE-LOC MAP-OFF");
    size_t n = read_all(path("diff.ws"), before, sizeof before);
    assert_int_equal(fbrl_workspace_diff(&b->ws, path("diff.ws"), note_delta, &ds, &count), FBRL_OK);
    assert_string_equal(ds.text, "added NEW a location -1>5;changed P a location 14>14.5;" /* newest first */
                                 "changed - the settings 1>0;dropped GONE a location 1>-1;");
    assert_int_equal(count, 4);
    /* it changed nothing */
    assert_int_equal(read_all(path("diff.ws"), after, sizeof after), n);
    assert_memory_equal(before, after, n);
    assert_int_equal(fbrl_workspace_diff(&b->ws, path("no-such.ws"), NULL, NULL, NULL), FBRL_ENOENT);
    remove(path("diff.ws"));
    free_vm(a);
    free_vm(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip),
        cmocka_unit_test(damaged_files_change_nothing),
        cmocka_unit_test(name_conflict_changes_nothing),
        cmocka_unit_test(full_dictionary_takes_back),
        cmocka_unit_test(save_keeps_other_data),
        cmocka_unit_test(what_a_save_would_change),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
