/* SPDX-License-Identifier: MIT */
/* mon_safe.c - Ctrl-C makes the cell safe, and a controller that goes away comes back:
 * fbrlmon on a real pseudo-terminal against a real fbrlsim process, whose command log
 * (--log, appended across its restarts) is the witness of what ran.
 *
 *  1. Ctrl-C in a plan file given on the command line while the arm moves, in a PULSE,
 *     in an MS that times an output, in FINISH, and at the prompt while the arm moves:
 *     each time the log shows HALT and no motion after it, W2 finds the arm standing
 *     short of its target and still standing a moment later, STATUS shows every output
 *     the session switched on off (an output another session switched on stays on), the
 *     message names file:line, and the session goes on. Two Ctrl-C in quick succession
 *     end fbrlmon (status 130) after the same safe stop.
 *  2. fbrlsim killed (SIGKILL) and started again on the same --link path in the middle
 *     of a plan: fbrlmon reports it at once, RECONNECT tells the controller's state,
 *     RESUME goes on from the failed line; every step of the plan ran exactly once. A
 *     robot word typed at the prompt after a loss reconnects by itself.
 *  3. A port the user may not open: "permission denied" and the dialout group (as the
 *     user nobody when the test runs as root, since root opens anything).
 *  4. Ctrl-C against a controller whose STATUS does not show its outputs (fbrlsim without
 *     --status-extra, as a RAPL-II controller): the valve the session switched on is
 *     switched off, every other output is named as not known and why, and fbrlsim's own
 *     output state (its control channel) and log agree.
 *
 *   mon_safe FBRLMON FBRLSIM TMPDIR      exit 0 on success; the transcript is printed on failure */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <grp.h>
#include <math.h>
#include <sys/stat.h>

#include "mon_session.h"

#define TIMEOUT_MS 60000 /* generous: the machine may be loaded, or ASan slow */
#define NOBODY     65534 /* uid and gid of the unprivileged user */
#define MAX_LOG    4096
#define LINE       160

static const char *g_mon, *g_simbin, *g_dir;
static char g_link[1024], g_log[1024];
static char g_lines[MAX_LOG][LINE];
static size_t g_nlines;

static void failf(session *s, const char *fmt, const char *a, double x)
{
    if (g_failed)
        return;
    fprintf(stderr, "FAIL: ");
    fprintf(stderr, fmt, a, x);
    fputc('\n', stderr);
    if (s != NULL)
        transcript(s);
    g_failed = 1;
}

/* fbrlsim on a pty, with the symlink g_link and the command log g_log (both kept). */
static pid_t start_sim(void)
{
    int pfd[2];
    char c;
    pid_t pid;
    if (pipe(pfd) != 0)
        return -1;
    pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        dup2(pfd[1], 1);
        close(pfd[0]);
        close(pfd[1]);
        execl(g_simbin, g_simbin, "--status-extra", "--link", g_link, "--log", g_log, (char *)NULL);
        _exit(127);
    }
    close(pfd[1]);
    /* the first line (the pty's path) comes once the link is in place */
    while (read(pfd[0], &c, 1) == 1 && c != '\n')
        ;
    close(pfd[0]);
    return pid;
}

/* The log's lines into g_lines. */
static void read_log(void)
{
    FILE *f = fopen(g_log, "r");
    g_nlines = 0;
    if (f == NULL)
        return;
    while (g_nlines < MAX_LOG && fgets(g_lines[g_nlines], LINE, f) != NULL) {
        g_lines[g_nlines][strcspn(g_lines[g_nlines], "\r\n")] = '\0';
        g_nlines++;
    }
    fclose(f);
}

static size_t log_mark(void)
{
    read_log();
    return g_nlines;
}

/* Wait until a line starting with `prefix` is in the log at index >= from. */
static int wait_log(session *s, size_t from, const char *prefix)
{
    long deadline = now_ms() + TIMEOUT_MS;
    while (!g_failed && now_ms() < deadline) {
        size_t i;
        read_log();
        for (i = from; i < g_nlines; i++)
            if (strncmp(g_lines[i], prefix, strlen(prefix)) == 0)
                return 1;
        pump(s, 20);
    }
    failf(s, "the log never showed \"%s\"", prefix, 0);
    return 0;
}

static int is_motion(const char *l)
{
    static const char *const m[] = {"MOVE", "APPRO", "DEPART", "JOG",  "JOINT", "MOTOR",
                                    "MA ",  "MI ",   "READY",  "HOME", "ALIGN", NULL};
    int k;
    for (k = 0; m[k] != NULL; k++)
        if (strncmp(l, m[k], strlen(m[k])) == 0)
            return 1;
    return 0;
}

/* Since `from`: a HALT, and no motion command after the last HALT. */
static void check_halt(session *s, size_t from, const char *what)
{
    size_t i, halt = (size_t)-1;
    settle(s, 500); /* a motion still queued somewhere would show by now */
    read_log();
    for (i = from; i < g_nlines; i++)
        if (strcmp(g_lines[i], "HALT") == 0)
            halt = i;
    if (halt == (size_t)-1) {
        failf(s, "%s: no HALT in the log", what, 0);
        return;
    }
    for (i = halt + 1; i < g_nlines; i++)
        if (is_motion(g_lines[i]))
            failf(s, "%s: a motion after HALT in the log", what, 0);
}

/* W2's WORLD x y z, read at the prompt. */
static int world(session *s, double p[3])
{
    type(s, "W2\r");
    if (!expect(s, "WORLD", "W2's WORLD line"))
        return 0;
    pump(s, 200);
    if (sscanf(s->buf + s->mark, "%lf %lf %lf", &p[0], &p[1], &p[2]) != 3) {
        failf(s, "%s: cannot read W2's WORLD line", "W2", 0);
        return 0;
    }
    expect(s, "ok> ", "prompt after W2");
    return 1;
}

/* The arm stands short of (x, y, z) and stays where it stands. */
static void check_standing(session *s, double x, double y, double z, const char *what)
{
    double a[3], b[3];
    if (!world(s, a))
        return;
    settle(s, 700);
    if (!world(s, b))
        return;
    if (fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]) > 1e-3)
        failf(s, "%s: the arm still moved after the stop (%.4f in)", what,
              fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]));
    if (sqrt((a[0] - x) * (a[0] - x) + (a[1] - y) * (a[1] - y) + (a[2] - z) * (a[2] - z)) < 0.5)
        failf(s, "%s: the arm reached its target: not stopped on the way", what, 0);
}

/* STATUS's output row equals want (16 characters of 0 and 1). */
static void check_outputs(session *s, const char *want, const char *what)
{
    type(s, "ROBOT-STATUS\r");
    if (!expect(s, "OUTPUTS 1-16: ", what))
        return;
    pump(s, 200);
    if (!g_failed && strncmp(s->buf + s->mark, want, 16) != 0) {
        fprintf(stderr, "FAIL: %s: OUTPUTS %.16s, want %s\n", what, s->buf + s->mark, want);
        transcript(s);
        g_failed = 1;
    }
    expect(s, "ok> ", "prompt after STATUS");
}

/* Ctrl-C once the log shows `prefix` (after `from`) and the line has run a moment. */
static long ctrl_c_after(session *s, size_t from, const char *prefix)
{
    wait_log(s, from, prefix);
    settle(s, 300);
    type_now(s, "\003");
    return now_ms();
}

static void write_file(const char *name, const char *text)
{
    char path[1200];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    f = fopen(path, "w");
    if (f == NULL || fputs(text, f) < 0 || fclose(f) != 0) {
        fprintf(stderr, "FAIL: cannot write %s\n", path);
        g_failed = 1;
    }
}

/* Another fbrlmon session on `link` switches output 9 on and ends: 0, or -1 (failed). */
static int other_session_output_9(const char *link)
{
    pid_t pid = fork();
    int ws;
    if (pid == 0) {
        int null = open("/dev/null", O_RDWR);
        dup2(null, 0);
        dup2(null, 1);
        execl(g_mon, g_mon, "--port", link, "-e", "9 OUTPORT BYE", (char *)NULL);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &ws, 0) != pid || !WIFEXITED(ws) || WEXITSTATUS(ws) != 0) {
        fprintf(stderr, "FAIL: the first session (9 OUTPORT) did not run\n");
        g_failed = 1;
        return -1;
    }
    return 0;
}

#define A_XYZ 12.0, 3.0, 8.0
#define B_XYZ 12.0, -3.0, 8.0

static const char cell[] = "\\ the test cell: two outputs, two places\n"
                           "5 OUTPUT-DEVICE VALVE  6 OUTPUT-DEVICE PUMP\n"
                           "CREATE-LOC A  12E0 3E0 8E0 0E0 -90E0 0E0 A DEFINE-LOC\n"
                           "CREATE-LOC B  12E0 -3E0 8E0 0E0 -90E0 0E0 B DEFINE-LOC\n";

/* fbrlmon --port PORT PLAN in the test's folder. */
static int start_plan(session *s, const char *port, const char *plan)
{
    char *argv[5];
    argv[0] = (char *)g_mon;
    argv[1] = "--port";
    argv[2] = (char *)port;
    argv[3] = (char *)plan;
    argv[4] = NULL;
    return start_mon_argv(s, TIMEOUT_MS, g_dir, argv);
}

/* 1. Ctrl-C, five ways. */
static void ctrl_c_tests(void)
{
    static session s;
    char plan1[1200], inc[1300];
    size_t from;
    int st;

    write_file("cell.fbrl", cell);
    write_file("plan1.fbrl", "\\ plan1: the valve on, then two moves\n"
                             "INCLUDE cell.fbrl\n"
                             "HOME READY 5 SPEED\n"
                             "VALVE ON\n"
                             "A MOV\n"
                             "B MOV\n"
                             ".( plan1 done) CR\n");
    write_file("plan2.fbrl", "\\ plan2: a long pulse\n"
                             ".( pulsing) CR\n"
                             "10000 VALVE PULSE\n"
                             ".( plan2 done) CR\n");
    write_file("plan3.fbrl", "\\ plan3: a pump timed by MS\n"
                             ".( pumping) CR\n"
                             "PUMP ON 10000 MS PUMP OFF\n"
                             ".( plan3 done) CR\n");
    write_file("plan4.fbrl", "\\ plan4: wait for the arm\n"
                             "5 SPEED B MOV\n"
                             "FINISH\n"
                             ".( plan4 done) CR\n");

    /* another session switched output 9 on: the safe stop leaves it alone */
    if (other_session_output_9(g_link) != 0)
        return;

    /* a plan file on the command line (it runs in the directory of cell.fbrl) */
    snprintf(plan1, sizeof plan1, "%s/plan1.fbrl", g_dir);
    if (chdir(g_dir) != 0) {
        perror("chdir");
        g_failed = 1;
        return;
    }
    from = log_mark();
    if (start_plan(&s, g_link, "plan1.fbrl") != 0)
        return;
    /* 1a: B MOV waits for A's motion (plan1.fbrl:6) */
    ctrl_c_after(&s, from, "MOVE FBRLT1");
    expect(&s, "plan1.fbrl:6: error: user interrupt in MOV", "the error names file:line");
    expect(&s, "stopped (plan1.fbrl:6 in MOV): arm halted while moving (MOVE FBRLT1)", "the stop report");
    expect(&s, "outputs switched off: 5; outputs still on: 9", "the valve switched off, output 9 left");
    expect(&s, "ok> ", "the session goes on at the prompt");
    check_halt(&s, from, "Ctrl-C in a plan's motion");
    check_standing(&s, A_XYZ, "Ctrl-C in a plan's motion");
    check_outputs(&s, "0000000010000000", "outputs after Ctrl-C in a motion");
    if (strstr(s.buf, "plan1 done") != NULL)
        failf(&s, "%s: the plan went on after Ctrl-C", "plan1", 0);

    /* 1b: a PULSE in a plan run from the prompt */
    snprintf(inc, sizeof inc, "INCLUDE plan2.fbrl\r");
    from = log_mark();
    type(&s, inc);
    expect(&s, "pulsing", "plan2 runs");
    {
        long t0 = ctrl_c_after(&s, from, "OUTPUT 5");
        expect(&s, "plan2.fbrl:3: error:", "the error names file:line");
        expect(&s, "stopped (plan2.fbrl:3", "the stop report");
        expect(&s, "ok> ", "the session goes on");
        if (now_ms() - t0 > 5000)
            failf(&s, "%s: the stop took %.0f ms", "PULSE", (double)(now_ms() - t0));
    }
    check_halt(&s, from, "Ctrl-C in a PULSE");
    check_outputs(&s, "0000000010000000", "outputs after Ctrl-C in a PULSE");

    /* 1c: an output timed by MS */
    from = log_mark();
    type(&s, "INCLUDE plan3.fbrl\r");
    expect(&s, "pumping", "plan3 runs");
    ctrl_c_after(&s, from, "OUTPUT 6");
    expect(&s, "plan3.fbrl:3: error: user interrupt in MS", "the error names file:line");
    expect(&s, "outputs switched off: 6; outputs still on: 9", "the pump switched off by the stop");
    expect(&s, "ok> ", "the session goes on");
    check_halt(&s, from, "Ctrl-C in MS");
    check_outputs(&s, "0000000010000000", "outputs after Ctrl-C in MS");

    /* 1d: FINISH */
    from = log_mark();
    type(&s, "INCLUDE plan4.fbrl\r");
    ctrl_c_after(&s, from, "MOVE");
    expect(&s, "plan4.fbrl:3: error: user interrupt in FINISH", "the error names file:line");
    expect(&s, "stopped (plan4.fbrl:3 in FINISH): arm halted while moving (MOVE FBRLT", "the stop report");
    expect(&s, "ok> ", "the session goes on");
    check_halt(&s, from, "Ctrl-C in FINISH");
    check_standing(&s, B_XYZ, "Ctrl-C in FINISH");
    check_outputs(&s, "0000000010000000", "outputs after Ctrl-C in FINISH");

    /* 1e: at the prompt, while the arm moves */
    from = log_mark();
    type(&s, "VALVE ON A MOV\r");
    expect(&s, "ok> ", "A MOV returns when the motion starts");
    wait_keys(&s);
    ctrl_c_after(&s, from, "MOVE");
    expect(&s, "stopped (at the prompt): arm halted while moving (MOVE FBRLT", "the stop report");
    expect(&s, "outputs switched off: 5; outputs still on: 9", "the valve switched off");
    expect(&s, "ok> ", "the session goes on");
    check_halt(&s, from, "Ctrl-C at the prompt");
    check_standing(&s, A_XYZ, "Ctrl-C at the prompt");
    check_outputs(&s, "0000000010000000", "outputs after Ctrl-C at the prompt");
    type(&s, "1 2 + .\r");
    expect(&s, "3 ", "the session works");
    expect(&s, "ok> ", "prompt");

    /* 1f: two Ctrl-C in quick succession: the same stop, then fbrlmon ends */
    from = log_mark();
    type(&s, "VALVE ON INCLUDE plan4.fbrl\r");
    ctrl_c_after(&s, from, "MOVE");
    settle(&s, 100);
    type_now(&s, "\003");
    expect(&s, "stopped (plan4.fbrl:3 in FINISH): arm halted", "the stop before the end");
    expect(&s, "outputs switched off: 5", "the valve switched off before the end");
    expect(&s, "fbrlmon: ended by a second Ctrl-C", "the second Ctrl-C ends fbrlmon");
    st = finish(&s);
    if (!g_failed && st != 130)
        failf(&s, "%s: exit status %.0f, want 130", "second Ctrl-C", (double)st);
    check_halt(&s, from, "two Ctrl-C");
    if (!g_failed)
        printf("mon_safe: Ctrl-C in a motion, a PULSE, MS, FINISH, at the prompt, twice: all safe\n");
}

/* 2. The controller killed and started again in the middle of a plan. */
static void reconnect_tests(pid_t *sim)
{
    static session s;
    static const double step_y[3] = {2.0, 0.0, -2.0}; /* C1 C2 C3: x 13, z 8 */
    size_t from, i, restarted, speed = (size_t)-1;
    int k;
    long t_kill;

    write_file("plan5.fbrl", "\\ plan5: one step per line\n"
                             "CREATE-LOC C1  13E0 2E0 8E0 0E0 -90E0 0E0 C1 DEFINE-LOC\n"
                             "CREATE-LOC C2  13E0 0E0 8E0 0E0 -90E0 0E0 C2 DEFINE-LOC\n"
                             "CREATE-LOC C3  13E0 -2E0 8E0 0E0 -90E0 0E0 C3 DEFINE-LOC\n"
                             "HOME READY 20 SPEED\n"
                             "C1 MOV\n"
                             "C2 MOV\n"
                             "C3 MOV\n"
                             "FINISH .( plan5 done) CR\n");
    from = log_mark();
    if (start_plan(&s, g_link, "plan5.fbrl") != 0)
        return;
    /* C2 MOV (line 7) waits for C1's motion: the controller disappears */
    wait_log(&s, from, "MOVE FBRLT");
    settle(&s, 200);
    kill(*sim, SIGKILL);
    waitpid(*sim, NULL, 0);
    t_kill = now_ms();
    if (expect(&s, "plan5.fbrl:7: error: controller disconnected (RECONNECT when it is back) in MOV",
               "the loss reported with file:line"))
        printf("mon_safe: the loss reported %ld ms after the kill\n", now_ms() - t_kill);
    if (!g_failed && now_ms() - t_kill > 2000)
        failf(&s, "%s: the loss was reported only after %.0f ms", "kill", (double)(now_ms() - t_kill));
    expect(&s, "ok> ", "the session goes on");

    restarted = log_mark();
    *sim = start_sim(); /* a restarted controller: its speed is its default again */
    type(&s, "RECONNECT\r");
    expect(&s, "the session's modes sent again: SPEED 20", "RECONNECT sends the plan's speed again");
    expect(&s, "reconnected to ", "RECONNECT");
    expect(&s, "controller NOT HOMED (HOME before moving), arm standing, outputs on:", "the state told");
    expect(&s, "ok> ", "prompt");
    type(&s, "HOME RESUME\r");
    expect(&s, "resuming plan5.fbrl at line 7", "RESUME names where it goes on");
    expect(&s, "plan5 done", "the plan goes on to its end");
    expect(&s, "ok> ", "prompt");

    /* the restarted controller got the plan's speed before its first motion (HOME) */
    read_log();
    for (i = restarted; i < g_nlines && !is_motion(g_lines[i]); i++)
        if (strcmp(g_lines[i], "SPEED 20") == 0)
            speed = i;
    if (speed == (size_t)-1 && !g_failed)
        failf(&s, "%s: no SPEED 20 before the first motion after the restart", "RESUME", 0);
    /* every step exactly once (the first run's lines and the resumed run's): the
     * scratch point's POINT, read by its numbers (the encoder writes them short) */
    for (k = 0; k < 3; k++) {
        int n = 0;
        for (i = from; i < g_nlines; i++) {
            double x, y, z;
            if (sscanf(g_lines[i], "POINT FBRLT%*1d,%lf,%lf,%lf", &x, &y, &z) == 3 && fabs(x - 13.0) < 1e-9 &&
                fabs(y - step_y[k]) < 1e-9 && fabs(z - 8.0) < 1e-9)
                n++;
        }
        if (n != 1 && !g_failed) {
            fprintf(stderr, "FAIL: step %d (POINT to 13 %g 8) ran %d times, want once\n", k + 1, step_y[k],
                    n);
            transcript(&s);
            g_failed = 1;
        }
    }
    {
        int moves = 0;
        for (i = from; i < g_nlines; i++)
            moves += strncmp(g_lines[i], "MOVE FBRLT", 10) == 0;
        if (moves != 3 && !g_failed)
            failf(&s, "%s: %.0f MOVE lines, want 3 (one per step)", "plan5", (double)moves);
    }

    /* lost while idle: the word that finds out fails, the next one typed reconnects */
    kill(*sim, SIGKILL);
    waitpid(*sim, NULL, 0);
    *sim = start_sim();
    type(&s, "W2\r");
    expect(&s, "controller disconnected", "W2 finds the loss");
    expect(&s, "ok> ", "prompt");
    type(&s, "W2\r");
    expect(&s, "(the controller was lost: reconnecting first)", "the next robot word reconnects");
    expect(&s, "reconnected to ", "reconnected");
    expect(&s, "WORLD", "and runs");
    expect(&s, "ok> ", "prompt");
    type(&s, "BYE\r");
    k = finish(&s);
    if (k != 1 && !g_failed) /* 1: the plan file failed (the loss) */
        failf(&s, "%s: fbrlmon's exit status %.0f after the reconnects, want 1", "BYE", (double)k);
    if (!g_failed)
        printf(
            "mon_safe: killed and restarted fbrlsim: reported, reconnected, resumed; each step ran once\n");
}

/* 4. Ctrl-C against a controller whose STATUS has no OUTPUTS line. */
static void plain_status_test(void)
{
    static session s;
    char link2[1100], log2[sizeof g_log], fifo[1100], ctlout[1100], saved_log[sizeof g_log], buf[256] = "";
    size_t from;
    pid_t pid;
    int k, fd;
    FILE *f;

    snprintf(link2, sizeof link2, "%s/robot2", g_dir);
    snprintf(log2, sizeof log2, "%.900s/sim2.log", g_dir);
    snprintf(fifo, sizeof fifo, "%s/ctl2", g_dir);
    snprintf(ctlout, sizeof ctlout, "%s/ctl2.out", g_dir);
    remove(log2);
    remove(ctlout);
    remove(fifo);
    if (mkfifo(fifo, 0600) != 0) {
        perror("mon_safe: mkfifo");
        g_failed = 1;
        return;
    }
    {
        int pfd[2];
        char c;
        if (pipe(pfd) != 0)
            return;
        pid = fork();
        if (pid == 0) {
            dup2(pfd[1], 1);
            close(pfd[0]);
            close(pfd[1]);
            execl(g_simbin, g_simbin, "--link", link2, "--log", log2, "--control", fifo, "--control-out",
                  ctlout, (char *)NULL);
            _exit(127);
        }
        close(pfd[1]);
        while (read(pfd[0], &c, 1) == 1 && c != '\n')
            ;
        close(pfd[0]);
    }
    memcpy(saved_log, g_log, sizeof saved_log); /* the log helpers read g_log */
    memcpy(g_log, log2, sizeof g_log);

    /* another session switched output 9 on */
    (void)other_session_output_9(link2);
    from = log_mark();
    if (!g_failed && start_plan(&s, link2, "plan1.fbrl") == 0) {
        ctrl_c_after(&s, from, "MOVE FBRLT1");
        expect(&s, "stopped (plan1.fbrl:6 in MOV): arm halted while moving (MOVE FBRLT1)", "the stop report");
        expect(&s,
               "outputs switched off: 5; not known: 1-4 6-16 (this controller's STATUS does not show its "
               "outputs, and this session did not switch them on: check them at the controller)",
               "the valve switched off, the others named as not known and why");
        expect(&s, "ok> ", "the session goes on at the prompt");
        check_halt(&s, from, "Ctrl-C, no OUTPUTS line");
        read_log();
        for (k = 0; (size_t)k < g_nlines && strcmp(g_lines[k], "OUTPUT -5") != 0; k++)
            ;
        if ((size_t)k == g_nlines)
            failf(&s, "%s: OUTPUT -5 is not in fbrlsim's log", "Ctrl-C, no OUTPUTS line", 0);
        /* fbrlsim's own outputs: the valve off, output 9 as the other session left it */
        fd = open(fifo, O_WRONLY);
        if (fd < 0 || write(fd, "GET OUTPUTS\n", 12) != 12)
            failf(&s, "%s: cannot write fbrlsim's control channel", "GET OUTPUTS", 0);
        if (fd >= 0)
            close(fd);
        for (k = 0; k < 100 && strstr(buf, "OUTPUTS ") == NULL; k++) {
            settle(&s, 50);
            f = fopen(ctlout, "r");
            if (f != NULL) {
                size_t n = fread(buf, 1, sizeof buf - 1, f);
                buf[n] = '\0';
                fclose(f);
            }
        }
        if (strstr(buf, "OUTPUTS 0000000010000000") == NULL)
            failf(&s, "%s: fbrlsim's outputs after the stop: %s", buf, 0);
        type(&s, "BYE\r");
        finish(&s);
        if (!g_failed)
            printf("mon_safe: Ctrl-C without an OUTPUTS line: the valve off, the others named unknown\n");
    }
    memcpy(g_log, saved_log, sizeof saved_log);
    kill(pid, SIGTERM);
    waitpid(pid, NULL, 0);
}

/* 3. A port without permission. */
static void permission_test(void)
{
    char errpath[1200], *slave, buf[2048] = "";
    int master = posix_openpt(O_RDWR | O_NOCTTY), ws;
    pid_t pid;
    FILE *f;
    if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0 || (slave = ptsname(master)) == NULL ||
        chmod(slave, 0) != 0) {
        perror("mon_safe: a pty without permission");
        g_failed = 1;
        return;
    }
    snprintf(errpath, sizeof errpath, "%s/perm.err", g_dir);
    pid = fork();
    if (pid == 0) {
        int fd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0666);
        int null = open("/dev/null", O_RDWR);
        dup2(null, 0);
        dup2(null, 1);
        dup2(fd, 2);
        /* root opens any file: the opener must be an ordinary user */
        if (geteuid() == 0 && (setgroups(0, NULL) != 0 || setgid(NOBODY) != 0 || setuid(NOBODY) != 0))
            _exit(126);
        execl(g_mon, g_mon, "--port", slave, "-e", "BYE", (char *)NULL);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &ws, 0) != pid) {
        g_failed = 1;
        return;
    }
    close(master);
    f = fopen(errpath, "r");
    if (f != NULL) {
        size_t n = fread(buf, 1, sizeof buf - 1, f);
        buf[n] = '\0';
        fclose(f);
    }
    if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 3 || strstr(buf, "permission denied") == NULL ||
        strstr(buf, "dialout") == NULL) {
        fprintf(stderr,
                "FAIL: a port without permission: status %d, message \"%s\"; want 3, "
                "\"permission denied\" and the dialout group\n",
                WIFEXITED(ws) ? WEXITSTATUS(ws) : -1, buf);
        g_failed = 1;
        return;
    }
    printf("mon_safe: %s", buf);
}

int main(int argc, char **argv)
{
    pid_t sim;
    if (argc != 4) {
        fprintf(stderr, "usage: mon_safe FBRLMON FBRLSIM TMPDIR\n");
        return 2;
    }
    g_mon = argv[1];
    g_simbin = argv[2];
    g_dir = argv[3];
    mkdir(g_dir, 0777);
    chmod(g_dir, 0777); /* fbrlmon as nobody writes its message there */
    signal(SIGPIPE, SIG_IGN);
    snprintf(g_link, sizeof g_link, "%s/robot", g_dir);
    snprintf(g_log, sizeof g_log, "%s/sim.log", g_dir);
    remove(g_log);
    sim = start_sim();
    if (sim < 0)
        return 1;
    ctrl_c_tests();
    if (!g_failed)
        reconnect_tests(&sim);
    if (!g_failed)
        plain_status_test();
    if (!g_failed)
        permission_test();
    kill(sim, SIGTERM);
    waitpid(sim, NULL, 0);
    if (g_failed)
        return 1;
    printf("mon_safe: all checks passed\n");
    return 0;
}
