/* SPDX-License-Identifier: MIT */
/* test_runlog.c - the run log's records, their escaping, cutting, polls folded, the
 * samples in the summary, and a failing sink. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdint.h>
#include <string.h>

#include "fbrl/runlog.h"
#include "fbrl/run.h"

typedef struct sink {
    char buf[65536];
    size_t len;
    unsigned writes;
    int fail_after; /* writes that succeed before every later one fails; -1 never */
    uint64_t now;
} sink;

static int sink_write(void *ctx, const char *s, size_t n)
{
    sink *k = ctx;
    if (k->fail_after >= 0 && k->writes >= (unsigned)k->fail_after)
        return -1;
    k->writes++;
    assert_true(n > 0 && s[n - 1] == '\n');
    assert_null(memchr(s, '\n', n - 1)); /* one line per record */
    assert_true(k->len + n < sizeof k->buf);
    memcpy(k->buf + k->len, s, n);
    k->len += n;
    k->buf[k->len] = '\0';
    return 0;
}

static uint64_t sink_clock(void *ctx) { return ((sink *)ctx)->now; }

static const char *nth_line(const sink *k, unsigned n, char *out, size_t cap)
{
    const char *p = k->buf;
    while (n-- > 0) {
        p = strchr(p, '\n');
        assert_non_null(p);
        p++;
    }
    const char *e = strchr(p, '\n');
    assert_non_null(e);
    assert_true((size_t)(e - p) < cap);
    memcpy(out, p, (size_t)(e - p));
    out[e - p] = '\0';
    return out;
}

/* A run log of method "M" on a fresh sink that never fails, begun. */
static void begin_m(sink *k, fbrl_runlog *l)
{
    fbrl_runlog_header h = {"M", NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0};
    memset(k, 0, sizeof *k);
    memset(l, 0, sizeof *l);
    k->fail_after = -1;
    assert_int_equal(fbrl_runlog_begin(l, sink_write, k, sink_clock, k, &h), FBRL_OK);
}

static void a_run_writes_every_record(void **state)
{
    (void)state;
    static sink k;
    fbrl_runlog l;
    char line[2048];
    fbrl_runlog_param p[2] = {{"#SAMPLES", 3, "samples"}, {"REACTION-MIN", 15, "min"}};
    fbrl_runlog_header h = {"SAMPLE-PREP",
                            "methods/sample_prep.fbrl",
                            "ann",
                            "2026-11-25T04:00:00",
                            "RAPL-II 2.0",
                            "fbrlmon 0.1.0",
                            NULL,
                            p,
                            2};
    memset(&k, 0, sizeof k);
    memset(&l, 0, sizeof l);
    k.fail_after = -1;
    k.now = 5000000;
    assert_int_equal(fbrl_runlog_step_start(&l, "x", -1), FBRL_ESTATE);
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, sink_clock, &k, &h), FBRL_OK);
    assert_true(fbrl_runlog_is_open(&l));
    assert_string_equal(nth_line(&k, 0, line, sizeof line),
                        "{\"t\":0,\"type\":\"header\",\"method\":\"SAMPLE-PREP\",\"source\":\"methods/"
                        "sample_prep.fbrl\",\"operator\":\"ann\",\"started\":\"2026-11-25T04:00:00\","
                        "\"controller\":\"RAPL-II 2.0\",\"program\":\"fbrlmon 0.1.0\",\"calibration\":null,"
                        "\"parameters\":[{\"name\":\"#SAMPLES\",\"value\":3,\"unit\":\"samples\"},{\"name\":"
                        "\"REACTION-MIN\",\"value\":15,\"unit\":\"min\"}]}");
    k.now += 1500000;
    assert_int_equal(fbrl_runlog_step_start(&l, "Buffer", 2), FBRL_OK);
    assert_string_equal(nth_line(&k, 1, line, sizeof line),
                        "{\"t\":1500,\"type\":\"step_start\",\"step\":\"Buffer\",\"sample\":2}");
    assert_int_equal(fbrl_runlog_command(&l, "MOVE FBRLT1", 11, FBRL_OK, -1), FBRL_OK);
    assert_int_equal(fbrl_runlog_command(&l, "MOVE X", 6, FBRL_ECONTROLLER, 11), FBRL_OK);
    assert_int_equal(fbrl_runlog_command(&l, "OUTPUT 3", 8, FBRL_EMAYBE, -1), FBRL_OK);
    assert_string_equal(
        nth_line(&k, 3, line, sizeof line),
        "{\"t\":1500,\"type\":\"command\",\"line\":\"MOVE X\",\"status\":\"refused\",\"code\":11}");
    assert_string_equal(
        nth_line(&k, 4, line, sizeof line),
        "{\"t\":1500,\"type\":\"command\",\"line\":\"OUTPUT 3\",\"status\":\"may-have-run\"}");
    assert_int_equal(fbrl_runlog_device(&l, "WASH-VALVE", "pulse", 500, 503), FBRL_OK);
    assert_int_equal(fbrl_runlog_wait(&l, "reaction", 900000, -1 + 900012), FBRL_OK);
    assert_string_equal(nth_line(&k, 6, line, sizeof line),
                        "{\"t\":1500,\"type\":\"wait\",\"wait\":\"reaction\",\"planned_ms\":900000,"
                        "\"actual_ms\":900011}");
    assert_int_equal(fbrl_runlog_error(&l, "plan.fbrl:12", "tube \"A1\"\tmissing\n", NULL), FBRL_OK);
    assert_string_equal(nth_line(&k, 7, line, sizeof line),
                        "{\"t\":1500,\"type\":\"error\",\"where\":\"plan.fbrl:12\",\"message\":\"tube "
                        "\\\"A1\\\"\\u0009missing\\n\",\"advice\":null}");
    assert_int_equal(fbrl_runlog_step_end(&l, "Buffer", 2, NULL), FBRL_OK);
    k.now += 250000;
    assert_int_equal(fbrl_runlog_note(&l, "pause", "ann", "before Reagent"), FBRL_OK);
    assert_string_equal(nth_line(&k, 9, line, sizeof line),
                        "{\"t\":1750,\"type\":\"note\",\"event\":\"pause\",\"operator\":\"ann\","
                        "\"text\":\"before Reagent\"}");
    assert_int_equal(fbrl_runlog_sample(&l, 2, "failed", "no tube"), FBRL_OK);
    assert_string_equal(nth_line(&k, 10, line, sizeof line),
                        "{\"t\":1750,\"type\":\"sample\",\"sample\":2,\"outcome\":\"failed\","
                        "\"reason\":\"no tube\"}");
    fbrl_runlog_outcome s[2] = {{1, "succeeded", ""}, {2, "failed", "no tube"}};
    assert_int_equal(fbrl_runlog_end(&l, "partial", s, 2), FBRL_OK);
    assert_false(fbrl_runlog_is_open(&l));
    assert_string_equal(nth_line(&k, 11, line, sizeof line),
                        "{\"t\":1750,\"type\":\"summary\",\"outcome\":\"partial\",\"elapsed_ms\":1750,"
                        "\"steps\":1,\"commands\":3,\"refused\":1,\"may_have_run\":1,\"devices\":1,"
                        "\"waits\":1,\"errors\":1,\"samples\":[{\"sample\":1,\"outcome\":\"succeeded\","
                        "\"reason\":\"\"},{\"sample\":2,\"outcome\":\"failed\",\"reason\":\"no tube\"}]}");
    assert_string_equal(nth_line(&k, 12, line, sizeof line),
                        "{\"t\":1750,\"type\":\"text\",\"text\":\"SAMPLE-PREP: partial after 1.7 s\"}");
    assert_string_equal(nth_line(&k, 13, line, sizeof line),
                        "{\"t\":1750,\"type\":\"text\",\"text\":\"2 samples: 1 succeeded, 1 failed, 0 skipped\"}");
    assert_string_equal(nth_line(&k, 14, line, sizeof line),
                        "{\"t\":1750,\"type\":\"text\",\"text\":\"sample 2 failed: no tube\"}");
    assert_int_equal(k.writes, 17);
    assert_int_equal(fbrl_runlog_note(&l, "pause", NULL, NULL), FBRL_ESTATE);
}

/* A command the link typed again (docs/link.md 3.9): its second run says so, the first not. */
static void a_repeated_command_says_which_run(void **state)
{
    (void)state;
    static sink k;
    fbrl_runlog l;
    char line[512];
    begin_m(&k, &l);
    assert_int_equal(fbrl_runlog_command_run(&l, "SPEED 5", 7, FBRL_EPROTOCOL, -1, 1), FBRL_OK);
    assert_int_equal(fbrl_runlog_command_run(&l, "SPEED 5", 7, FBRL_OK, -1, 2), FBRL_OK);
    assert_int_equal(fbrl_runlog_command_run(&l, "SPEED 6", 7, FBRL_OK, -1, 0), FBRL_OK);
    assert_string_equal(nth_line(&k, 1, line, sizeof line),
                        "{\"t\":0,\"type\":\"command\",\"line\":\"SPEED 5\",\"status\":\"reply-damaged\"}");
    assert_string_equal(nth_line(&k, 2, line, sizeof line),
                        "{\"t\":0,\"type\":\"command\",\"line\":\"SPEED 5\",\"status\":\"ran\",\"run\":2}");
    assert_string_equal(nth_line(&k, 3, line, sizeof line),
                        "{\"t\":0,\"type\":\"command\",\"line\":\"SPEED 6\",\"status\":\"ran\"}");
}

/* A long text is cut inside the line limit and stays valid JSON (ends with ..."}). */
static void long_texts_are_cut(void **state)
{
    (void)state;
    static sink k;
    fbrl_runlog l;
    static char big[FBRL_RUNLOG_LINE_MAX], line[FBRL_RUNLOG_LINE_MAX + 2];
    fbrl_runlog_header h = {"M", NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0};
    memset(&k, 0, sizeof k);
    memset(&l, 0, sizeof l);
    k.fail_after = -1;
    memset(big, '"', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, NULL, NULL, &h), FBRL_OK);
    assert_int_equal(fbrl_runlog_note(&l, "abort", NULL, big), FBRL_OK);
    nth_line(&k, 1, line, sizeof line);
    assert_true(strlen(line) <= FBRL_RUNLOG_LINE_MAX);
    size_t n = strlen(line);
    assert_string_equal(line + n - 5, "...\"}");
    assert_int_equal(line[n - 6], '"'); /* whole escapes only: \" never cut in two */
    assert_int_equal(line[n - 7], '\\');
}

static void a_failing_sink_is_reported(void **state)
{
    (void)state;
    static sink k;
    fbrl_runlog l;
    fbrl_runlog_header h = {"M", NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0};
    memset(&k, 0, sizeof k);
    memset(&l, 0, sizeof l);
    k.fail_after = 0;
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, NULL, NULL, &h), FBRL_EIO);
    assert_false(fbrl_runlog_is_open(&l));
    k.fail_after = 2;
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, NULL, NULL, &h), FBRL_OK);
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, NULL, NULL, &h), FBRL_ESTATE);
    assert_int_equal(fbrl_runlog_step_start(&l, "a", -1), FBRL_OK);
    assert_int_equal(fbrl_runlog_step_end(&l, "a", -1, NULL), FBRL_EIO);
    assert_int_equal(fbrl_runlog_end(&l, "completed", NULL, 0), FBRL_EIO);
    assert_false(fbrl_runlog_is_open(&l));
    h.method = NULL;
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, NULL, NULL, &h), FBRL_EINVAL);
}

/* Polls the robot words repeat while they wait are one record each run of them, written
 * when another record comes, with their count: the commands are counted one by one. */
static void polls_are_folded(void **state)
{
    (void)state;
    static sink k;
    fbrl_runlog l;
    char line[512];
    begin_m(&k, &l);
    assert_int_equal(fbrl_runlog_command(&l, "MOVE A", 6, FBRL_OK, -1), FBRL_OK);
    for (int i = 0; i < 5; i++) {
        k.now += 50000;
        assert_int_equal(fbrl_runlog_command(&l, "W5", 2, FBRL_OK, -1), FBRL_OK);
    }
    assert_int_equal(k.writes, 2); /* the header, MOVE: the polls wait for what comes next */
    assert_int_equal(fbrl_runlog_command(&l, "TYPEI SIG(3)", 12, FBRL_OK, -1), FBRL_OK);
    assert_int_equal(fbrl_runlog_command(&l, "TYPEI SIG(3)", 12, FBRL_OK, -1), FBRL_OK);
    assert_int_equal(fbrl_runlog_command(&l, "W5", 2, FBRL_ECONTROLLER, 12), FBRL_OK); /* refused: a record */
    assert_int_equal(fbrl_runlog_wait(&l, "WAIT-INPUT X on: not seen", 100, 101), FBRL_OK);
    assert_string_equal(nth_line(&k, 2, line, sizeof line),
                        "{\"t\":50,\"type\":\"command\",\"line\":\"W5\",\"status\":\"ran\",\"count\":5,"
                        "\"last_t\":250}");
    assert_string_equal(nth_line(&k, 3, line, sizeof line),
                        "{\"t\":250,\"type\":\"command\",\"line\":\"TYPEI SIG(3)\",\"status\":\"ran\","
                        "\"count\":2,\"last_t\":250}");
    assert_string_equal(nth_line(&k, 4, line, sizeof line),
                        "{\"t\":250,\"type\":\"command\",\"line\":\"W5\",\"status\":\"refused\",\"code\":12}");
    assert_int_equal(fbrl_runlog_command(&l, "W5", 2, FBRL_OK, -1), FBRL_OK);
    assert_int_equal(fbrl_runlog_end(&l, "completed", NULL, 0), FBRL_OK);
    assert_string_equal(nth_line(&k, 6, line, sizeof line),
                        "{\"t\":250,\"type\":\"command\",\"line\":\"W5\",\"status\":\"ran\"}");
    assert_non_null(strstr(k.buf, "\"commands\":10,"));
}

/* A summary of more samples than its line holds lists those that fit, whole, and says how
 * many it left out; the line stays one valid record. */
static void a_summary_of_many_samples_stays_whole(void **state)
{
    (void)state;
    static sink k;
    static char reason[FBRL_RUNLOG_LINE_MAX / 8];
    static char line[FBRL_RUNLOG_LINE_MAX + 2];
    fbrl_runlog l;
    fbrl_runlog_outcome s[40];
    fbrl_runlog_header h = {"M", NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0};
    memset(&k, 0, sizeof k);
    memset(&l, 0, sizeof l);
    k.fail_after = -1;
    memset(reason, 'r', sizeof reason - 1);
    for (int i = 0; i < 40; i++)
        s[i].sample = i + 1, s[i].outcome = "failed", s[i].reason = reason;
    assert_int_equal(fbrl_runlog_begin(&l, sink_write, &k, NULL, NULL, &h), FBRL_OK);
    assert_int_equal(fbrl_runlog_end(&l, "failed", s, 40), FBRL_OK);
    nth_line(&k, 1, line, sizeof line);
    size_t n = strlen(line);
    assert_true(n <= FBRL_RUNLOG_LINE_MAX);
    assert_non_null(strstr(line, "\"samples_left_out\":"));
    assert_string_equal(line + n - 1, "}");
    assert_non_null(strstr(line, "rr\"}],\"samples_left_out\""));
    assert_non_null(strstr(k.buf, "\"text\":\"... and 30 more (the summary record lists every sample)\""));
}

/* A run's events as every program records them (fbrl_runlog_event): the step with its
 * sample numbered from 1, who paused, a failure with its plain advice; nothing in a log
 * that is not open; NULLs refused. (The summary at END: tests/e2e, python test_audit.py.) */
static void a_runs_events_become_its_records(void **state)
{
    static fbrl_method m;
    static fbrl_run_snap snap;
    fbrl_run *run = (fbrl_run *)(void *)&snap; /* not read but at END */
    sink k;
    fbrl_runlog l;
    char line[1024];
    (void)state;
    memset(&m, 0, sizeof m);
    strcpy(m.name, "M");
    strcpy(m.steps[0].name, "Spin");
    m.nsteps = 1;
    fbrl_run_event ev = {FBRL_RUN_EV_STEP_BEGIN, &m, 0, 1, 0, 0, FBRL_OK, NULL, "", NULL, NULL, NULL};
    begin_m(&k, &l);
    assert_int_equal(fbrl_runlog_event(&l, run, &ev, &snap), FBRL_OK);
    assert_non_null(strstr(nth_line(&k, 1, line, sizeof line), "\"type\":\"step_start\""));
    assert_non_null(strstr(line, "\"step\":\"Spin\",\"sample\":2"));
    ev.kind = FBRL_RUN_EV_PAUSE;
    ev.who = "ann";
    assert_int_equal(fbrl_runlog_event(&l, run, &ev, &snap), FBRL_OK);
    assert_non_null(strstr(nth_line(&k, 2, line, sizeof line), "\"event\":\"pause\",\"operator\":\"ann\""));
    assert_non_null(strstr(line, "before Spin, sample 2"));
    ev.kind = FBRL_RUN_EV_STEP_END;
    ev.text = "040-ARM POWER HAS BEEN SWITCHED OFF.";
    assert_int_equal(fbrl_runlog_event(&l, run, &ev, &snap), FBRL_OK);
    assert_non_null(strstr(nth_line(&k, 3, line, sizeof line), "switch the arm's power on"));
    assert_non_null(strstr(nth_line(&k, 4, line, sizeof line), "\"type\":\"step_end\""));
    unsigned writes = k.writes;
    fbrl_runlog closed;
    memset(&closed, 0, sizeof closed);
    assert_int_equal(fbrl_runlog_event(&closed, run, &ev, &snap), FBRL_OK);
    assert_int_equal(k.writes, writes);
    assert_int_equal(fbrl_runlog_event(NULL, run, &ev, &snap), FBRL_EINVAL);
    assert_int_equal(fbrl_runlog_event(&l, run, &ev, NULL), FBRL_EINVAL);
    assert_string_equal(fbrl_runlog_advice(NULL), "read the message, fix the cause, and start the method again");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_run_writes_every_record),
        cmocka_unit_test(a_repeated_command_says_which_run),
        cmocka_unit_test(long_texts_are_cut),
        cmocka_unit_test(a_failing_sink_is_reported),
        cmocka_unit_test(polls_are_folded),
        cmocka_unit_test(a_summary_of_many_samples_stays_whole),
        cmocka_unit_test(a_runs_events_become_its_records),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
