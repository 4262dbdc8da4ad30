/* SPDX-License-Identifier: MIT */
/* sim_control_test.c - fbrlsim's control lines, --inputs file, long RUNs and
 * the state file lines the fuzz targets tripped over (issue 20: what their
 * regression inputs cannot judge alone).
 *   - control lines are strict: each accepted and refused form of the table;
 *   - an --inputs file with a bad line (junk, hex, nan, no space after the time,
 *     a line too long to read whole) stops fbrlsim at start with FILE:LINE;
 *   - a FIFO line too long for the buffer is dropped whole, never run cut;
 *   - a long RUN yields to the event loop and still runs every line exactly
 *     once (the count of V1=V1+1 is exact across the yields);
 *   - state file: a NUL byte in a line is refused with FILE:LINE, "end" closes
 *     a program, a SPEED below 1e-9 (which the SPEED command takes) loads. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "sim_cmd.h"

#define RUN_COUNT      5000
#define EXEC_STEPS_MAX 100000

static char dir[] = "/tmp/fbrl-simctl-XXXXXX";

static const char *path_in_dir(const char *name)
{
    static char p[256];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return p;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static fbrl_sim *new_sim(const char *state, const char *inputs, char *err, size_t errlen)
{
    fbrl_sim_options o;
    fbrl_sim *s = NULL;
    fbrl_sim_options_init(&o);
    o.tcp_port = 0;
    o.state_path = state;
    o.inputs_path = inputs;
    err[0] = 0;
    fbrl_sim_create(&s, &o, err, errlen);
    return s;
}

static void control_lines(void **st)
{
    static const char *const good[] = {"IN 3 1",      "IN 16 0",     " IN\t1\t1 ", "AIN 8 -10",
                                       "AIN 1 2.5",   "AIN 2 +1e-3", "POWER 0",    "POWER 1",
                                       "OBJECT 0.75", "OBJECT 2",    "TEACH"};
    static const char *const bad[] = {"IN 3 1 junk",
                                      "IN 3.5 1",
                                      "IN 0x3 1",
                                      "IN 17 1",
                                      "IN 0 1",
                                      "IN 3 2",
                                      "IN 3",
                                      "IN 3 1.0",
                                      "AIN 1 nan",
                                      "AIN 1 inf",
                                      "AIN 1 1e999",
                                      "AIN 1 5volts",
                                      "AIN 9 0",
                                      "AIN 1 10.5",
                                      "POWER 1.0",
                                      "POWER 2",
                                      "OBJECT -0.1",
                                      "OBJECT 3",
                                      "OBJECT",
                                      "TEACH 1",
                                      "in 3 1",
                                      "",
                                      "   ",
                                      "FOO",
                                      "IN 99999999999999999999 1"};
    size_t i;
    (void)st;
    for (i = 0; i < sizeof good / sizeof good[0]; i++)
        if (sim_control(NULL, good[i]) != 0)
            fail_msg("refused: '%s'", good[i]);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
        if (sim_control(NULL, bad[i]) == 0)
            fail_msg("accepted: '%s'", bad[i]);
}

static void inputs_file(void **st)
{
    static const struct {
        const char *text;
        int line; /* 0: accepted; else the line named in the message */
    } cases[] = {
        {"# ok\n0 IN 3 1\n1.5 AIN 2 -4.5\n2\tPOWER 0\n", 0},
        {"0 IN 3 1\n1 IN 3 1 junk\n", 2},
        {"-1 IN 3 1\n", 1},
        {"nan IN 3 1\n", 1},
        {"inf IN 3 1\n", 1},
        {"0x10 IN 3 1\n", 1},
        {"1.5IN 3 1\n", 1},
        {"1 IN 3.5 1\n", 1},
        {"1 AIN 1 nan\n", 1},
    };
    char err[512], want[300], longline[400];
    size_t i;
    fbrl_sim *s;
    (void)st;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_text(path_in_dir("in.txt"), cases[i].text);
        s = new_sim(NULL, path_in_dir("in.txt"), err, sizeof err);
        if (!cases[i].line) {
            if (!s)
                fail_msg("case %zu refused: %s", i, err);
            fbrl_sim_destroy(s);
            continue;
        }
        if (s)
            fail_msg("case %zu accepted", i);
        snprintf(want, sizeof want, "%s:%d: ", path_in_dir("in.txt"), cases[i].line);
        if (strncmp(err, want, strlen(want)) != 0)
            fail_msg("case %zu: '%s' does not start with '%s'", i, err, want);
    }
    /* a line too long to read whole: refused, not read as two lines (the second "2 POWER 0") */
    memset(longline, ' ', sizeof longline);
    memcpy(longline, "1 IN 3 1", 8);
    strcpy(longline + 300, "2 POWER 0\n");
    write_text(path_in_dir("in.txt"), longline);
    s = new_sim(NULL, path_in_dir("in.txt"), err, sizeof err);
    assert_null(s);
    assert_non_null(strstr(err, ":1: line too long"));
}

static void fifo_long_line_dropped(void **st)
{
    char err[512], line[400];
    int p[2];
    fbrl_sim *s = new_sim(NULL, NULL, err, sizeof err);
    (void)st;
    assert_non_null(s);
    assert_int_equal(pipe(p), 0);
    s->events.ctl = p[0]; /* the emulator reads it as its FIFO (and closes it) */
    memset(line, ' ', sizeof line);
    memcpy(line, "IN 3 1", 6);
    memcpy(line + sizeof line - 12, "IN 4 1\n", 7);
    assert_int_equal(write(p[1], line, sizeof line - 5), (ssize_t)(sizeof line - 5));
    sim_events_read_fifo(s);
    sim_events_read_fifo(s);
    assert_int_equal(s->dev.in[2], 0);
    assert_int_equal(s->dev.in[3], 0);
    assert_int_equal(write(p[1], "IN 3 1\n", 7), 7);
    sim_events_read_fifo(s);
    assert_int_equal(s->dev.in[2], 1);
    close(p[1]);
    fbrl_sim_destroy(s);
}

static void long_run_yields_and_counts(void **st)
{
    char err[512], cmd[64];
    int e = -1, steps = 0, yields = 0;
    sim_var *v;
    fbrl_sim *s;
    (void)st;
    write_text(path_in_dir("run.state"),
               "FBRLSIM-STATE 1\nVAR V1 0\nPROGRAM P\n  V1=V1+1\nEND\nPROGRAM E\nEND\n");
    s = new_sim(path_in_dir("run.state"), NULL, err, sizeof err);
    assert_non_null(s);
    snprintf(cmd, sizeof cmd, "RUN P,%d", RUN_COUNT);
    if (sim_exec(s, cmd, &e) == EXEC_BLOCK) {
        yields++;
        while (sim_exec_step(s, &e) == EXEC_BLOCK && ++steps < EXEC_STEPS_MAX)
            yields++;
    }
    assert_int_equal(e, -1);
    assert_true(yields >= 2); /* it gave the loop a turn */
    v = sim_var_find(s, "V1");
    assert_non_null(v);
    assert_true(v->v == RUN_COUNT); /* every line once: none lost or repeated at a yield */
    /* an empty program run a million million times yields too, instead of hanging */
    assert_int_equal(sim_exec(s, "RUN E,1E12", &e), EXEC_BLOCK);
    fbrl_sim_destroy(s);
}

static void state_file_lines(void **st)
{
    char err[512], want[300];
    const char *path = path_in_dir("lines.state");
    static const char nul[] = "FBRLSIM-STATE 1\nVAR X 1\0junk\n";
    FILE *f;
    fbrl_sim *s;
    (void)st;
    f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(nul, 1, sizeof nul - 1, f), sizeof nul - 1);
    fclose(f);
    assert_null(new_sim(path, NULL, err, sizeof err));
    snprintf(want, sizeof want, "%s:2: a NUL byte", path);
    if (strncmp(err, want, strlen(want)) != 0)
        fail_msg("'%s' does not start with '%s'", err, want);

    write_text(path, "FBRLSIM-STATE 1\nSPEED 4.5e-10\nPROGRAM P\n  home\nend\nVAR X 2\n");
    s = new_sim(path, NULL, err, sizeof err);
    if (!s)
        fail_msg("refused: %s", err);
    assert_int_equal(s->mem.nprogs, 1);
    assert_int_equal(s->mem.progs[0].n, 1); /* "end" closed it: VAR X is memory, not a line */
    assert_string_equal(s->mem.progs[0].lines[0], "HOME");
    assert_non_null(sim_var_find(s, "X"));
    assert_true(s->arm.speed == 4.5e-10);
    fbrl_sim_destroy(s);
}

static int setup(void **st)
{
    (void)st;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **st)
{
    const char *names[] = {"in.txt", "run.state", "lines.state"};
    size_t i;
    (void)st;
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        unlink(path_in_dir(names[i]));
    return rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(control_lines),          cmocka_unit_test(inputs_file),
        cmocka_unit_test(fifo_long_line_dropped), cmocka_unit_test(long_run_yields_and_counts),
        cmocka_unit_test(state_file_lines),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
