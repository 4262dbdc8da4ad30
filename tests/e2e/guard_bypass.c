/* SPDX-License-Identifier: MIT */
/* guard_bypass.c - the five ways a motion once went past the work cell's guard (issue 28),
 * each against a real fbrlsim that knows the same cell (--cell: a motion into it stops with
 * 190-COLLISION; --log-format stamped: every command with its result), fbrlmon at a real
 * terminal. Each move that would hit must be refused before a byte of it is sent: its
 * POINT or JOG line is not in fbrlsim's log, and no line there ended in 190.
 *  1. TEACH: a keyboard jog and a pitch move into a beam; then a robot word's jog from
 *     where TEACH left the arm;
 *  2. after RAPL HALT stopped a straight move low on its way (and ARM-HERE read the truth),
 *     a move that is clear from the halted move's target but not from where the arm stands;
 *  3. the same after arm power off and on at the front panel (fbrlsim's control FIFO);
 *  4. two tasks: while the main task's move waits for the arm another task claimed, that
 *     task moves, then the main task's move and its next move;
 *  5. a controller left in METRIC: a target out of the guard's reach in inches lands
 *     inside the post in millimetres; and (the rule behind it) a target out of reach on an
 *     inch controller is refused too, saying why.
 * And TEACH's advice after a 190 (a cell the host does not describe, the guard off, a host
 * cell that lacks what the arm met) says what to do in that situation.
 *
 *   guard_bypass FBRLMON FBRLSIM CELLDIR TMPDIR [CASE]    exit 0 when every case passed */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <sys/stat.h>

#include "mon_session.h"

#define TIMEOUT_MS 60000 /* generous: the machine may be loaded, or ASan slow */

static const char *g_mon, *g_sim, *g_cells, *g_tmp;
static int g_fails;

typedef struct sim {
    pid_t pid;
    char port[256], log[1024], ctl[1024], out[1024];
} sim;

/* fbrlsim with the cell, a stamped command log and a control FIFO, in dir. */
static int sim_start(sim *x, const char *dir, const char *cell, const char *scale)
{
    char cellpath[1024], ctlout[1024];
    snprintf(cellpath, sizeof cellpath, "%s/%s", g_cells, cell);
    snprintf(x->log, sizeof x->log, "%s/sim.log", dir);
    snprintf(x->ctl, sizeof x->ctl, "%s/ctl", dir);
    snprintf(ctlout, sizeof ctlout, "%s/ctl.out", dir);
    remove(x->log);
    remove(x->ctl);
    const char *args[] = {"--cell",    cellpath, "--log",         x->log, "--log-format", "stamped",
                          "--control", x->ctl,   "--control-out", ctlout, "--time-scale", scale,
                          NULL};
    x->pid = start_sim_pty_args(g_sim, args, x->port, sizeof x->port, TIMEOUT_MS);
    return x->pid < 0 ? -1 : 0;
}

static void sim_stop(sim *x)
{
    kill(x->pid, SIGTERM);
    waitpid(x->pid, NULL, 0);
}

/* A control line to fbrlsim's FIFO (POWER 0 ...). */
static void control(const sim *x, const char *line)
{
    FILE *f = fopen(x->ctl, "w");
    if (f == NULL) {
        fprintf(stderr, "FAIL: cannot open fbrlsim's control FIFO %s\n", x->ctl);
        g_failed = 1;
        return;
    }
    fprintf(f, "%s\n", line);
    fclose(f);
}

/* fbrlmon on a terminal against x, the cell included (NULL: none described). */
static int mon_start(session *s, const sim *x, const char *dir, const char *cell)
{
    char inc[1200];
    char *argv[6];
    snprintf(inc, sizeof inc, "INCLUDE %s/%s", g_cells, cell ? cell : "");
    argv[0] = (char *)g_mon;
    argv[1] = (char *)"--port";
    argv[2] = (char *)x->port;
    argv[3] = cell ? (char *)"-e" : NULL;
    argv[4] = inc;
    argv[5] = NULL;
    if (start_mon_argv(s, TIMEOUT_MS, dir, argv) != 0)
        return -1;
    return expect(s, "ok> ", "first prompt") ? 0 : -1;
}

/* A line at the prompt, then the next prompt. */
static void line(session *s, const char *text, const char *what)
{
    type(s, text);
    type(s, "\r");
    expect(s, "ok> ", what);
}

static void fail(const char *name, const char *fmt, const char *a)
{
    fprintf(stderr, "FAIL: %s: ", name);
    fprintf(stderr, fmt, a);
    fprintf(stderr, "\n");
    g_failed = 1;
}

/* The cell's promise in fbrlsim's log: nothing of the refused motion (its line `sent`) and
 * no motion that ended in 190-COLLISION. */
static void check_log(const char *name, const sim *x, const char *sent)
{
    if (file_count(x->log, " 190 ") != 0)
        fail(name, "a motion hit the cell (190 in fbrlsim's log %s)", x->log);
    if (sent && file_count(x->log, sent) != 0)
        fail(name, "the refused motion reached fbrlsim: %s", sent);
}

static void end_case(const char *name, session *s, sim *x)
{
    type(s, "BYE\r");
    finish(s);
    sim_stop(x);
    if (g_failed) {
        transcript(s);
        g_fails++;
        g_failed = 0;
        printf("guard_bypass %s: FAILED (fbrlsim's log: %s)\n", name, x->log);
    } else {
        printf("guard_bypass %s: passed\n", name);
    }
}

static int case_dir(const char *name, char *dir, size_t cap)
{
    snprintf(dir, cap, "%s/%s", g_tmp, name);
    mkdir(dir, 0777);
    return 0;
}

/* 1. TEACH */
static void teach(void)
{
    static session s;
    sim x;
    char dir[1024];
    case_dir("teach", dir, sizeof dir);
    if (sim_start(&x, dir, "beam.fbrl", "5") != 0 || mon_start(&s, &x, dir, "beam.fbrl") != 0) {
        g_fails++;
        return;
    }
    line(&s, "HOME READY CREATE-LOC P", "home");
    type(&s, "TEACH P\r");
    expect(&s, "Enter  store the position", "TEACH starts");
    expect(&s, "X+12.000 Y+0.000 Z+20.000 in", "TEACH reads the arm at READY");
    type(&s, "4"); /* 1 in, 10 degrees */
    expect(&s, "step 1 in 10 deg", "step 1 in");
    type(&s, "\033[6~");
    expect(&s, "Z+19.000", "PgDn jogs Z -1");
    type(&s, "\033[6~");
    expect(&s, "Z+18.000", "PgDn jogs Z -1 again");
    type(&s, "\033[6~"); /* into the beam below */
    expect(&s, "! JOG: would hit BEAM", "the third jog down is refused, naming the beam");
    expect(&s, "Z+18.000", "the arm stayed at Z 18");
    for (int k = 0; k < 9 && !g_failed; k++) { /* pitch down, 10 degrees a key, until it would hit */
        size_t before = s.mark;
        type(&s, "[");
        expect(&s, "\033[K", "status line after [");
        if (strstr(s.buf + before, "! PITCH: would hit BEAM") != NULL)
            break;
        if (k == 8)
            fail("teach", "%s", "pitching the tool down never came to the beam");
    }
    type(&s, "\r");
    expect(&s, "stored", "Enter stores");
    expect(&s, "ok> ", "prompt after TEACH");
    /* the robot words follow where TEACH left the arm: 1 in down is into the beam from there */
    line(&s, "0E0 0E0 -1E0 JOG", "a jog after TEACH");
    if (strstr(s.buf, "error: JOG: would hit BEAM") == NULL)
        fail("teach", "%s", "the jog after TEACH was not refused");
    check_log("teach", &x, NULL);
    if (file_count(x.log, "JOG 0,0,-1") != 2)
        fail("teach", "%s", "fbrlsim's log does not hold exactly the two jogs down that were clear");
    end_case("teach (keyboard jog, pitch, the jog after)", &s, &x);
}

/* The positions of cases 2 and 3 (tests/e2e/cell/cell.fbrl: the post at x 13..15, y -1..1,
 * up to z 6): A right of the post, low; T straight above it; B left of the post. B is clear
 * from T (over the post) and not from low on the way up (through it). */
static const char *const halt_locs =
    "CREATE-LOC A 12E0 -6E0 4E0 0E0 -90E0 0E0 A DEFINE-LOC "
    "CREATE-LOC T 12E0 -6E0 14E0 0E0 -90E0 0E0 T DEFINE-LOC "
    "CREATE-LOC B 12E0 6E0 7E0 0E0 -90E0 0E0 B DEFINE-LOC CREATE-LOC AT 20 SPEED";

/* 2. and 3.: a straight move up stopped low on its way (how: stop), then B */
static void stopped(const char *name, int power)
{
    static session s;
    sim x;
    char dir[1024];
    case_dir(power ? "power" : "halt", dir, sizeof dir);
    if (sim_start(&x, dir, "cell.fbrl", "1") != 0 || mon_start(&s, &x, dir, "cell.fbrl") != 0) {
        g_fails++;
        return;
    }
    line(&s, "HOME READY", "home");
    line(&s, halt_locs, "locations");
    line(&s, "A MOV FINISH", "to A");
    line(&s, "T MOV-STRT", "the straight move up starts");
    if (power) {
        control(&x, "POWER 0"); /* the front panel's switch */
        usleep(300 * 1000);
        control(&x, "POWER 1");
    } else {
        line(&s, "RAPL HALT", "HALT typed as a RAPL line");
    }
    line(&s, "AT ARM-HERE AT DISPLAY-LOC", "ARM-HERE shows where it stopped");
    line(&s, "B MOV", "the move to B");
    if (strstr(s.buf, "error: MOV: would hit POST") == NULL)
        fail(name, "%s", "the move to B was not refused naming the post");
    check_log(name, &x, "POINT FBRLT1,12,6,7,");
    end_case(name, &s, &x);
}

/* 4. two tasks: the second task holds the arm (CLAIM-ARM) while the main task's move to A
 * waits for it; meanwhile the second task moves to B2. The main task's next move, to C, is
 * clear from B2 and not from A, where the arm is. */
static void tasks(void)
{
    static session s;
    sim x;
    char dir[1024];
    case_dir("tasks", dir, sizeof dir);
    if (sim_start(&x, dir, "cell.fbrl", "2") != 0 || mon_start(&s, &x, dir, "cell.fbrl") != 0) {
        g_fails++;
        return;
    }
    line(&s, "HOME READY FINISH", "home");
    line(&s,
         "CREATE-LOC A 12E0 -6E0 4E0 0E0 -90E0 0E0 A DEFINE-LOC "
         "CREATE-LOC B2 12E0 6E0 12E0 0E0 -90E0 0E0 B2 DEFINE-LOC "
         "CREATE-LOC C 12E0 6E0 7E0 0E0 -90E0 0E0 C DEFINE-LOC",
         "locations");
    line(&s, "TASK T2 : OTHER ( -- ) CLAIM-ARM 300 MS B2 MOV RELEASE-ARM ;", "the second task");
    line(&s, "' OTHER T2 START 20 MS A MOV C MOV", "both run");
    line(&s, "T2 AWAIT", "the second task ended");
    if (strstr(s.buf, "error: MOV: would hit POST") == NULL)
        fail("tasks", "%s", "the main task's move to C was not refused naming the post");
    check_log("tasks", &x, "POINT FBRLT1,12,6,7,");
    check_log("tasks", &x, "POINT FBRLT2,12,6,7,");
    end_case("tasks (a second task's move while the main task's waits)", &s, &x);
}

/* 5. units: the controller left in millimetres by an earlier session; 355.6 76.2 are out
 * of the arm's reach in inches, and 14 in and 3 in, inside the post, in millimetres */
static const char *const far_loc = "CREATE-LOC FAR 355.6E0 0E0 76.2E0 0E0 -90E0 0E0 FAR DEFINE-LOC";

static void metric(void)
{
    static session s;
    sim x;
    char dir[1024];
    case_dir("metric", dir, sizeof dir);
    if (sim_start(&x, dir, "cell.fbrl", "5") != 0 || mon_start(&s, &x, dir, "cell.fbrl") != 0) {
        g_fails++;
        return;
    }
    line(&s, "HOME READY RAPL METRIC", "the controller switched to millimetres");
    type(&s, "BYE\r");
    finish(&s);
    if (mon_start(&s, &x, dir, "cell.fbrl") != 0) { /* another session, the units unknown */
        g_fails++;
        sim_stop(&x);
        return;
    }
    line(&s, far_loc, "the location");
    line(&s, "FAR MOV", "the move");
    if (strstr(s.buf, "error: MOV: ") == NULL)
        fail("metric", "%s", "the move on the controller in millimetres was not refused");
    check_log("metric", &x, "POINT FBRLT1,355.6,");
    check_log("metric", &x, "POINT FBRLT2,355.6,");
    end_case("metric (a controller left in millimetres)", &s, &x);
}

/* and on an inch controller: a target the guard cannot check is refused, not passed */
static void reach(void)
{
    static session s;
    sim x;
    char dir[1024];
    case_dir("reach", dir, sizeof dir);
    if (sim_start(&x, dir, "cell.fbrl", "5") != 0 || mon_start(&s, &x, dir, "cell.fbrl") != 0) {
        g_fails++;
        return;
    }
    line(&s, "HOME READY", "home");
    line(&s, far_loc, "the location");
    line(&s, "FAR MOV", "out of reach in inches");
    if (strstr(s.buf, "error: MOV: the guard cannot check it: X 355.6000 Y 0.0000 Z 76.2000 in is beyond the "
                      "arm's reach; nothing was sent") == NULL)
        fail("reach", "%s", "a target out of reach was not refused by the guard, saying why");
    check_log("reach", &x, "POINT FBRLT1,355.6,");
    check_log("reach", &x, "POINT FBRLT2,355.6,");
    end_case("reach (a target out of the guard's reach, in inches)", &s, &x);
}

/* TEACH's advice after fbrlsim's 190 matches the situation: no cell described on the host,
 * the guard off, or a host cell that lacks what the arm met (the beam). Jogs down 1 in at a
 * time until fbrlsim stops one at the beam, then 0.5 in up out of the contact (so that the
 * next descent crosses the beam again rather than starting on it). */
static void advice_after(session *s, const char *want, const char *what)
{
    type(s, "TEACH P\r");
    expect(s, "Enter  store the position", "TEACH starts");
    type(s, "4");
    expect(s, "step 1 in 10 deg", "step 1 in");
    for (int k = 0; k < 4 && !g_failed && !strstr(s->buf + s->mark, "190-COLLISION"); k++) {
        type(s, "\033[6~");
        expect(s, "\033[K", "status line after PgDn");
        settle(s, 300);
    }
    expect(s, want, what);
    type(s, "3");
    expect(s, "step 0.5 in", "step 0.5 in");
    type(s, "\033[5~"); /* out of the contact */
    expect(s, "\033[K", "status line after PgUp");
    settle(s, 300);
    type(s, "\033");
    expect(s, "cancelled", "TEACH cancelled");
    expect(s, "ok> ", "the prompt after TEACH");
}

static void advice(void)
{
    static session s;
    sim x;
    char dir[1024], inc[1200];
    case_dir("advice", dir, sizeof dir);
    if (sim_start(&x, dir, "beam.fbrl", "5") != 0 || mon_start(&s, &x, dir, NULL) != 0) {
        g_fails++;
        return;
    }
    line(&s, "HOME READY CREATE-LOC P", "home");
    advice_after(&s, "190-COLLISION (the arm met the work cell and stopped there (fbrlsim --cell)): describe the cell "
                     "on the host too",
                 "no cell on the host: describe it");
    snprintf(inc, sizeof inc, "INCLUDE %s/beam.fbrl CELL-GUARD-OFF", g_cells);
    line(&s, inc, "the cell, the guard off");
    advice_after(&s, ": the guard is off (CELL-GUARD-OFF); CELL-GUARD-ON checks", "the guard off: switch it on");
    line(&s, "CELL-CLEAR 0E0 CELL-TABLE CELL-GUARD-ON", "a host cell without the beam");
    advice_after(&s, ": the guard let it pass, so the host's cell lacks what the arm met",
                 "the guard on: the host's cell lacks it");
    if (file_count(x.log, " 190 ") != 3)
        fail("advice", "%s", "fbrlsim did not stop three jogs at the beam");
    end_case("advice (TEACH after a 190: what to do, as things stand)", &s, &x);
}

int main(int argc, char **argv)
{
    const char *only = argc > 5 ? argv[5] : "";
    if (argc < 5) {
        fprintf(stderr, "usage: guard_bypass FBRLMON FBRLSIM CELLDIR TMPDIR [teach|halt|power|tasks|metric|reach|advice]\n");
        return 2;
    }
    g_mon = argv[1], g_sim = argv[2], g_cells = argv[3], g_tmp = argv[4];
    mkdir(g_tmp, 0777);
    signal(SIGPIPE, SIG_IGN);
    if (!*only || !strcmp(only, "teach"))
        teach();
    if (!*only || !strcmp(only, "halt"))
        stopped("halt (RAPL HALT low on the way)", 0);
    if (!*only || !strcmp(only, "power"))
        stopped("power (arm power off and on at the front panel)", 1);
    if (!*only || !strcmp(only, "tasks"))
        tasks();
    if (!*only || !strcmp(only, "metric"))
        metric();
    if (!*only || !strcmp(only, "reach"))
        reach();
    if (!*only || !strcmp(only, "advice"))
        advice();
    return g_fails ? 1 : 0;
}
