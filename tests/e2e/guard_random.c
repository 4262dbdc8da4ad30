/* SPDX-License-Identifier: MIT */
/* guard_random.c - the motion guard attacked at random in a cluttered cell: a VM with the
 * glossary, the robot words and the work cell's words over a real link to the real fbrlsim,
 * which knows the same cell (--cell: a motion into it stops with 190-COLLISION; its stamped
 * log holds every command with its result). N random actions (2,000 by default):
 * joint-interpolated and straight moves to random poses of the arm (its forward kinematics
 * computed here, from DESIGN 6), MA and MI, JOG, APPROACH and DEPART, READY, a move stopped
 * by RAPL HALT after a random time, a move stopped by arm power off at the front panel
 * (fbrlsim's control FIFO) after a random time, and a second task's move beside the main
 * task's. The truth is fbrlsim's log: no line may end in 190. Every refusal of the main
 * task must name an obstacle of the cell (or say why the guard cannot check the motion);
 * the second task's are counted by their code.
 *
 *   guard_random FBRLSIM CELL [N [SEED]]     SEED: any number (default: from the clock);
 *                                           printed first, so a failing run can be repeated
 * Exit 0 when fbrlsim's log shows no collision and every refusal said what it refused. */
#include <math.h>
#include <time.h>

#include "cell_rig.h"

/* The VM's clock runs this many times faster than the host's (and its sleeps are that much
 * shorter): the robot words' 50 ms rounds while the arm moves and the tasks' waits pass
 * quickly, as fbrlsim's --time-scale makes the arm fast. */
#define CLOCK_SPEED 10u
#define SIM_SCALE   "100"
#define MAX_OBJ     16
#define PI          3.14159265358979323846

static cell_rig C;
static fbrl_vm *vm; /* C.vm */
static char ctl_path[600];
static uint64_t seed_state;

static uint64_t fast_now_us(void *user)
{
    (void)user;
    return fbrl_clock_now_us() * CLOCK_SPEED;
}

static void fast_sleep_ms(void *user, uint32_t ms)
{
    (void)user;
    fbrl_clock_sleep_us((uint64_t)ms * 1000u / CLOCK_SPEED);
}

/* xorshift64*: the test's only randomness, all from the seed */
static uint64_t rnd(void)
{
    seed_state ^= seed_state >> 12;
    seed_state ^= seed_state << 25;
    seed_state ^= seed_state >> 27;
    return seed_state * 2685821657736338717ull;
}

static double uni(double lo, double hi) { return lo + (hi - lo) * (double)(rnd() >> 11) / 9007199254740992.0; }

/* The A255's tool point for joints q (degrees), DESIGN 6: shoulder axis 10 in above the
 * base, upper arm and forearm 10 in, wrist pitch axis to the tool point 2 in; shoulder =
 * upper arm above horizontal, elbow relative to the upper arm, wrist relative to the forearm.
 * pose: x y z yaw pitch roll. */
static void a255_fk(const double q[5], double pose[6])
{
    double a2 = q[1] * PI / 180.0, a3 = (q[1] + q[2]) * PI / 180.0, p = (q[1] + q[2] + q[3]) * PI / 180.0;
    double r = 10.0 * cos(a2) + 10.0 * cos(a3) + 2.0 * cos(p);
    double z = 10.0 + 10.0 * sin(a2) + 10.0 * sin(a3) + 2.0 * sin(p);
    pose[0] = r * cos(q[0] * PI / 180.0);
    pose[1] = r * sin(q[0] * PI / 180.0);
    pose[2] = z;
    pose[3] = q[0];
    pose[4] = q[1] + q[2] + q[3];
    pose[5] = q[4];
}

/* Random joints inside the A255's limits (the waist kept off its stops). */
static void random_joints(double q[5])
{
    q[0] = uni(-150.0, 150.0);
    q[1] = uni(0.0, 110.0);
    q[2] = uni(-130.0, 0.0);
    q[3] = uni(-110.0, 110.0);
    q[4] = uni(-180.0, 180.0);
}

static void random_pose(double pose[6])
{
    double q[5];
    random_joints(q);
    a255_fk(q, pose);
    while (pose[4] > 180.0)
        pose[4] -= 360.0;
    while (pose[4] <= -180.0)
        pose[4] += 360.0;
}

static void control(const char *line)
{
    FILE *f = fopen(ctl_path, "w");
    if (f) {
        fprintf(f, "%s\n", line);
        fclose(f);
    }
}

static void sleep_ms(unsigned ms) { fbrl_clock_sleep_us((uint64_t)ms * 1000u); }

/* ---- what happened ---- */

enum { A_MOV, A_MOV_STRT, A_MA, A_MI, A_JOG, A_APPROACH, A_DEPART, A_READY, A_HALT, A_POWER, A_TASKS, A_KINDS };
static const char *const kind_name[A_KINDS] = {"MOV",    "MOV-STRT", "MA",    "MI",   "JOG",  "APPROACH",
                                               "DEPART", "READY",    "HALT",  "POWER", "TASKS"};

static unsigned long n_kind[A_KINDS], n_ok, n_refused, n_unchecked, n_bad_refusal, n_ctrl, n_other;
static unsigned long n_t2_ok, n_t2_refused, n_t2_other, n_short;
static unsigned long n_hit[MAX_OBJ + 2];
static int ctrl_codes[1000];

/* The obstacle a refusal names: "WORD: would hit NAME at X ...". */
static int named_obstacle(const char *msg)
{
    const char *p = strstr(msg, ": would hit ");
    if (!p)
        return -1;
    p += strlen(": would hit ");
    for (size_t k = 0; k < C.cw.model.n; k++) {
        size_t n = strlen(C.cw.model.obj[k].name);
        if (strncmp(p, C.cw.model.obj[k].name, n) == 0 && p[n] == ' ')
            return (int)k;
    }
    if (strncmp(p, "the table ", 10) == 0)
        return MAX_OBJ;
    return -2;
}

/* Run text in the main task; count what came of it. */
static int run(const char *text)
{
    int code = 0;
    char msg[256];
    msg[0] = 0;
    if (fbrl_vmx_evaluate_catch(vm, text, strlen(text), &code, msg, sizeof msg) != FBRL_OK) {
        fprintf(stderr, "FAIL: %s: the VM could not run it\n", text);
        return -1000;
    }
    if (code == 0) {
        n_ok++;
    } else if (code == FBRL_CELL_THROW_COLLISION) {
        int o = named_obstacle(msg);
        n_refused++;
        if (o >= 0) {
            n_hit[o <= MAX_OBJ ? o : MAX_OBJ + 1]++;
        } else if (strstr(msg, ": the guard cannot check it: ") && strstr(msg, "; nothing was sent")) {
            n_unchecked++;
            if (getenv("GUARD_RANDOM_VERBOSE")) fprintf(stderr, "unchecked: %s: %s\n", text, msg);
        } else {
            n_bad_refusal++;
            fprintf(stderr, "FAIL: a refusal that names no obstacle: %s\n", msg);
        }
    } else if (code == FBRL_VM_THROW_OF_STATUS(FBRL_ECONTROLLER)) {
        n_ctrl++;
        int c = fbrl_robot_last_error(&C.robot);
        if (c >= 0 && c < 1000)
            ctrl_codes[c]++;
        if (c == 190)
            fprintf(stderr, "FAIL: %s: %s\n", text, msg);
    } else {
        n_other++;
        fprintf(stderr, "note: %s: %s (THROW %d)\n", text, msg, code);
    }
    return code;
}

static const char *num(char *b, double v)
{
    snprintf(b, 32, "%.4fE0", v);
    return b;
}

/* "x y z o a t NAME DEFINE-LOC" */
static void define(const char *name, const double p[6])
{
    char t[300], b[6][32];
    snprintf(t, sizeof t, "%s %s %s %s %s %s %s DEFINE-LOC", num(b[0], p[0]), num(b[1], p[1]), num(b[2], p[2]),
             num(b[3], p[3]), num(b[4], p[4]), num(b[5], p[5]), name);
    if (run(t) != 0)
        fprintf(stderr, "FAIL: %s\n", t);
    n_ok--; /* not an action */
}

/* After a stop: did the arm stand short of the target (the stop came mid-motion)? */
static void stopped_short(const double target[6])
{
    fbrl_rapl_pos p;
    if (run("FINISH") != 0)
        return;
    n_ok--;
    if (fbrl_link_where(&C.r.link, FBRL_RAPL_W2, &p) == FBRL_OK && p.nworld >= 3) {
        double d = sqrt((p.world[0] - target[0]) * (p.world[0] - target[0]) +
                        (p.world[1] - target[1]) * (p.world[1] - target[1]) +
                        (p.world[2] - target[2]) * (p.world[2] - target[2]));
        if (d > 0.01)
            n_short++;
    }
}

static void action(int kind)
{
    double p[6], q[5];
    char t[400], b[6][32];
    n_kind[kind]++;
    switch (kind) {
    case A_MOV:
    case A_MOV_STRT:
    case A_APPROACH:
        random_pose(p);
        define("TGT", p);
        if (kind == A_APPROACH)
            snprintf(t, sizeof t, "TGT %s APPROACH", num(b[0], uni(0.5, 3.0)));
        else
            snprintf(t, sizeof t, "TGT %s", kind == A_MOV ? "MOV" : "MOV-STRT");
        run(t);
        break;
    case A_MA:
        random_joints(q);
        snprintf(t, sizeof t, "%s %s %s %s %s MA", num(b[0], q[0] * PI / 180), num(b[1], q[1] * PI / 180),
                 num(b[2], q[2] * PI / 180), num(b[3], q[3] * PI / 180), num(b[4], q[4] * PI / 180));
        run(t);
        break;
    case A_MI:
        snprintf(t, sizeof t, "%s %s %s %s %s MI", num(b[0], uni(-0.5, 0.5)), num(b[1], uni(-0.3, 0.3)),
                 num(b[2], uni(-0.3, 0.3)), num(b[3], uni(-0.5, 0.5)), num(b[4], uni(-0.5, 0.5)));
        run(t);
        break;
    case A_JOG:
        snprintf(t, sizeof t, "%s %s %s JOG", num(b[0], uni(-2.5, 2.5)), num(b[1], uni(-2.5, 2.5)),
                 num(b[2], uni(-2.5, 2.5)));
        run(t);
        break;
    case A_DEPART: snprintf(t, sizeof t, "%s DEPART%s", num(b[0], uni(-3.0, 3.0)), rnd() & 1 ? "" : "-STRT"); run(t); break;
    case A_READY: run("READY"); break;
    case A_HALT:
    case A_POWER:
        random_pose(p);
        define("TGT", p);
        if (run("TGT MOV") != 0)
            break; /* refused or failed: nothing to stop */
        sleep_ms((unsigned)(rnd() % 25));
        if (kind == A_HALT) {
            run("RAPL HALT");
            n_ok--;
        } else {
            control("POWER 0"); /* the front panel's switch */
            sleep_ms(5 + (unsigned)(rnd() % 10));
            control("POWER 1");
            sleep_ms(10);
        }
        stopped_short(p);
        break;
    case A_TASKS: {
        fbrl_cell code = 0;
        random_pose(p);
        define("T2-TO", p);
        random_pose(p);
        define("TGT", p);
        /* the second task's move and the main task's, each waiting for the arm as it will */
        run("BOTH");
        if (run("T2-CODE @") == 0 && fbrl_vm_pop(vm, &code) == FBRL_OK) {
            n_ok--;
            if (code == 0)
                n_t2_ok++;
            else if (code == FBRL_CELL_THROW_COLLISION)
                n_t2_refused++;
            else
                n_t2_other++;
        }
        break;
    }
    default: break;
    }
}

/* Lines of fbrlsim's stamped log ("T RESULT LINE") whose result is res. */
static unsigned long log_results(const char *log, const char *res, unsigned long *motions)
{
    FILE *f = fopen(log, "r");
    char line[512];
    unsigned long n = 0;
    *motions = 0;
    if (!f)
        return (unsigned long)-1;
    while (fgets(line, sizeof line, f)) {
        char t[32], r[16], cmd[32];
        if (sscanf(line, "%31s %15s %31s", t, r, cmd) != 3)
            continue;
        if (strcmp(r, res) == 0)
            n++;
        if (strcmp(r, "OK") == 0 &&
            (!strncmp(cmd, "MOVE", 4) || !strcmp(cmd, "JOG") || !strcmp(cmd, "MA") || !strcmp(cmd, "MI") ||
             !strcmp(cmd, "APPRO") || !strcmp(cmd, "DEPART") || !strcmp(cmd, "READY")))
            (*motions)++;
    }
    fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    char dir[256], log_path[600], ctlout[600];
    unsigned long n = 2000, seed;
    if (argc < 3) {
        fprintf(stderr, "usage: guard_random FBRLSIM CELL [N [SEED]]\n");
        return 2;
    }
    if (argc > 3)
        n = strtoul(argv[3], NULL, 10);
    seed = argc > 4 ? strtoul(argv[4], NULL, 10) : (unsigned long)time(NULL);
    printf("guard_random: seed %lu (guard_random FBRLSIM CELL %lu %lu repeats this run)\n", seed, n, seed);
    fflush(stdout);
    seed_state = seed * 0x9E3779B97F4A7C15ull + 1;

    rig_tmpdir(dir, sizeof dir, "guard-random");
    snprintf(log_path, sizeof log_path, "%s/sim.log", dir);
    snprintf(ctl_path, sizeof ctl_path, "%s/ctl", dir);
    snprintf(ctlout, sizeof ctlout, "%s/ctl.out", dir);
    const char *args[] = {"--time-scale", SIM_SCALE, "--log", log_path, "--log-format", "stamped",
                          "--control", ctl_path, "--control-out", ctlout, NULL};
    static unsigned char mem[4 << 20] __attribute__((aligned(16)));
    const char *setup = "HOME READY CREATE-LOC TGT CREATE-LOC T2-TO TASK T2 VARIABLE T2-CODE "
                        ": T2-GO ( -- ) T2-TO ['] MOV CATCH T2-CODE ! ; "
                        ": BOTH ( -- ) ['] T2-GO T2 START TGT ['] MOV CATCH T2 AWAIT THROW ;";
    if (cell_rig_start(&C, argv[1], argv[2], args, mem, sizeof mem, fast_now_us, fast_sleep_ms) != 0)
        return 1;
    vm = C.vm;
    if (fbrl_vm_eval(vm, setup, strlen(setup)) != FBRL_OK) {
        fprintf(stderr, "FAIL: setup: %s\n", fbrl_vm_last_error(vm)->message);
        cell_rig_stop(&C);
        return 1;
    }
    uint64_t t0 = fbrl_clock_now_us();
    /* the mix: mostly moves, one in ten a stop, one in twenty two tasks */
    static const int mix[] = {A_MOV, A_MOV, A_MOV,      A_MOV_STRT, A_MA,   A_MA,    A_MI,    A_JOG, A_JOG,
                              A_JOG, A_APPROACH, A_DEPART, A_READY, A_HALT, A_POWER, A_TASKS, A_MOV, A_MA, A_JOG, A_MOV};
    for (unsigned long i = 0; i < n; i++) {
        action(mix[rnd() % (sizeof mix / sizeof mix[0])]);
        if (fbrl_robot_lost(&C.robot)) {
            fprintf(stderr, "FAIL: the controller went away after %lu actions\n", i + 1);
            break;
        }
    }
    double secs = (double)(fbrl_clock_now_us() - t0) / 1e6;
    unsigned long motions = 0, hits = log_results(log_path, "190", &motions);

    printf("actions %lu in %.1f s:", n, secs);
    for (int k = 0; k < A_KINDS; k++)
        printf(" %s %lu", kind_name[k], n_kind[k]);
    printf("\nmain task: %lu ran, %lu refused (%lu naming an obstacle, %lu the guard cannot check, %lu naming "
           "nothing), %lu controller errors, %lu other\n",
           n_ok, n_refused, n_refused - n_unchecked - n_bad_refusal, n_unchecked, n_bad_refusal, n_ctrl, n_other);
    printf("refusals by obstacle:");
    for (size_t k = 0; k < C.cw.model.n; k++)
        printf(" %s %lu", C.cw.model.obj[k].name, n_hit[k]);
    printf(" table %lu\n", n_hit[MAX_OBJ]);
    printf("controller errors by code:");
    for (int c = 0; c < 1000; c++)
        if (ctrl_codes[c])
            printf(" %03d x%d", c, ctrl_codes[c]);
    printf("\nsecond task: %lu ran, %lu refused, %lu other; stops that left the arm short of its target: %lu\n",
           n_t2_ok, n_t2_refused, n_t2_other, n_short);
    printf("fbrlsim's log: %lu motions ran, %lu ended in 190-COLLISION\n", motions, hits);
    int rc = hits != 0 || n_bad_refusal != 0 || motions == 0 || n_short == 0;
    if (rc)
        printf("FAIL (seed %lu; fbrlsim's log kept in %s)\n", seed, log_path);
    cell_rig_stop(&C);
    if (!rc) {
        unlink(log_path);
        unlink(ctl_path);
        unlink(ctlout);
        rmdir(dir);
    }
    return rc;
}
