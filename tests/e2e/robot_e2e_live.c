/* SPDX-License-Identifier: MIT */
/* robot_e2e_live: readings while the arm moves (docs/robot.md "Live and final
 * positions"). ROUNDS times: a joint-interpolated MOVE between two points, then after a
 * random delay (0 to the motion's duration) the words W2, W0 and ACTUAL (live: they must
 * not wait for the motion) and ARM-HERE (final: it waits). Every call must succeed; every
 * live reading must lie within 0.01 in of fbrlsim's trajectory at the time it was taken;
 * every ARM-HERE must equal the target.
 * The trajectory is the emulator's, not the library's: joint angles from fbrlsim's own
 * inverse kinematics (sim/arm.c), interpolated linearly from the start of the motion at
 * the emulator's joint speeds (docs/fbrlsim.md "The arm model"), the tool point from
 * fbrlsim's forward kinematics. The time of a reading is bracketed by the host clock
 * before and after the word.
 * Usage: robot_e2e_live FBRLSIM [ROUNDS] [SEED] */
#include <math.h>

#include "rapl_harness.h"
#include "fbrl/arm.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "support/vm_host.h"

#define AXES          5 /* the A255, fbrlsim's default model */
#define SPEED_PCT     50.0
#define MOTION_REAL_S 0.08 /* each motion lasts this long on the host's clock */
#define TOL_IN        0.01
#define SLACK_S       0.003 /* host scheduling around a reading's bracket */

static vmh_text out;
static const fbrl_arm *arm; /* fbrlsim's own A255 */
static fbrl_vm *vm;
static int failures;

static uint32_t rng = 1;
static double uniform(void)
{
    rng = rng * 1664525u + 1013904223u;
    return (rng >> 8) / 16777216.0;
}

static double now_s(void) { return fbrl_clock_now_us() / 1e6; }

static int eval(const char *text)
{
    out.n = 0;
    out.s[0] = 0;
    fbrl_status st = fbrl_vm_eval(vm, text, strlen(text));
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(vm);
        fprintf(stderr, "'%s' failed: %s\n", text, e ? e->message : fbrl_status_str(st));
        failures++;
        fbrl_vm_reset(vm);
        return -1;
    }
    return 0;
}

/* x y z of the last WORLD line the words printed */
static int printed_world(double xyz[3])
{
    const char *w = NULL, *p = out.s;
    while ((p = strstr(p, "WORLD")) != NULL)
        w = p++;
    return w && sscanf(w, "WORLD %lf %lf %lf", &xyz[0], &xyz[1], &xyz[2]) == 3 ? 0 : -1;
}

static int loc_xyz(const char *name, double xyz[3])
{
    fbrl_cell addr;
    fbrl_loc *l;
    if (eval(name) != 0 || fbrl_vm_pop(vm, &addr) != FBRL_OK || fbrl_glossary_loc(vm, addr, &l) != FBRL_OK)
        return -1;
    xyz[0] = l->x, xyz[1] = l->y, xyz[2] = l->z;
    return 0;
}

typedef struct motion {
    double qa[AXES], qb[AXES], pb[6];
    double t_lo, t_hi; /* the motion began between these host times */
    double dur;        /* host seconds */
} motion;

/* Distance from xyz to the emulator's path while f runs over [f0, f1]. */
static double off_path(const motion *m, const double xyz[3], double f0, double f1)
{
    double best = 1e9;
    /* before the start the arm is at the start, after the end at the end */
    f0 = f0 < 0 ? 0 : f0 > 1 ? 1 : f0;
    f1 = f1 < 0 ? 0 : f1 > 1 ? 1 : f1;
    for (int k = 0; k <= 400; k++) {
        double f = f0 + (f1 - f0) * k / 400.0, q[AXES], pose[6];
        for (int j = 0; j < AXES; j++)
            q[j] = m->qa[j] + (m->qb[j] - m->qa[j]) * f;
        fbrl_arm_fk(arm, q, 0.0, pose);
        double d = sqrt((pose[0] - xyz[0]) * (pose[0] - xyz[0]) + (pose[1] - xyz[1]) * (pose[1] - xyz[1]) +
                        (pose[2] - xyz[2]) * (pose[2] - xyz[2]));
        if (d < best)
            best = d;
    }
    return best;
}

static void live(const motion *m, const char *word, const char *loc, long *moving_reads)
{
    double xyz[3], t0 = now_s();
    int ok = eval(word) == 0 && (loc ? loc_xyz(loc, xyz) : printed_world(xyz)) == 0;
    double t1 = now_s();
    if (!ok) {
        fprintf(stderr, "%s: no reading\n", word);
        failures++;
        return;
    }
    double f0 = (t0 - m->t_hi - SLACK_S) / m->dur, f1 = (t1 - m->t_lo + SLACK_S) / m->dur;
    double d = off_path(m, xyz, f0, f1);
    if (f0 > 0 && f1 < 1)
        (*moving_reads)++;
    if (d > TOL_IN) {
        fprintf(stderr, "%s at f %.3f..%.3f: %.4f %.4f %.4f is %.4f in off the emulator's path\n", word, f0,
                f1, xyz[0], xyz[1], xyz[2], d);
        failures++;
    }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s FBRLSIM [ROUNDS] [SEED]\n", argv[0]);
        return 2;
    }
    long rounds = argc > 2 ? atol(argv[2]) : 200;
    rng = argc > 3 ? (uint32_t)atol(argv[3]) : 1;
    /* two cartesian points, pitch straight down, far enough apart for a long motion */
    static const double pa[6] = {14.0, -6.0, 6.0, 0.0, -90.0, 0.0},
                        pb[6] = {9.0, 8.0, 12.0, 0.0, -90.0, 30.0};
    double qa[AXES], qb[AXES];
    static const double zero[AXES] = {0};
    arm = fbrl_arm_find("A255");
    if (!arm || arm->naxes != AXES || fbrl_arm_ik(arm, pa, 0.0, zero, qa, NULL) ||
        fbrl_arm_ik(arm, pb, 0.0, qa, qb, NULL)) {
        fprintf(stderr, "test points unreachable\n");
        return 1;
    }
    double t_sim = 0;
    for (int j = 0; j < AXES; j++) {
        double t = fabs(qb[j] - qa[j]) / (arm->speed[j] * SPEED_PCT / 100.0);
        if (t > t_sim)
            t_sim = t;
    }
    char scale[32];
    snprintf(scale, sizeof scale, "%.6f", t_sim / MOTION_REAL_S);
    const char *args[] = {"--time-scale", scale, NULL};
    fbrl_link_config lc;
    fbrl_link_config_init(&lc);
    static fbrl_arm bogus; /* pulses that never agree with the joints */
    bogus = *fbrl_arm_model(0);
    for (unsigned k = 0; k < bogus.naxes; k++)
        bogus.ppd[k] = 1.0;
    if (getenv("LIVE_NO_SELFCHECK"))
        lc.arm = &bogus; /* the older rule: two equal replies */
    rig r;
    if (rig_start(&r, argv[1], args, 115200, FBRL_FLOW_NONE, &lc) != 0 ||
        fbrl_link_connect(&r.link) != FBRL_OK)
        return 1;
    static unsigned char mem[1 << 20] __attribute__((aligned(16)));
    static fbrl_glossary g;
    static fbrl_robot robot;
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = sizeof mem;
    cfg.host.write = vmh_write;
    cfg.host.user = &out;
    vmh_use_clock(&cfg.host);
    if (fbrl_vm_create(&vm, &cfg) != FBRL_OK || fbrl_glossary_install(vm, &g) != FBRL_OK ||
        fbrl_robot_install(vm, &robot, &r.link, &g) != FBRL_OK) {
        fprintf(stderr, "VM setup failed\n");
        return 1;
    }
    char setup[1024]; /* room for any %g: a Debug build's -Wformat-truncation counts the worst case */
    int setup_len = snprintf(
        setup, sizeof setup,
        "CREATE-LOC L1 CREATE-LOC L2 RAPL HOME\nRAPL SPEED %d\nRAPL POINT PA,%g,%g,%g,%g,%g,%g\n"
        "RAPL POINT PB,%g,%g,%g,%g,%g,%g\nRAPL MOVE PA\nRAPL FINISH",
        (int)SPEED_PCT, pa[0], pa[1], pa[2], pa[3], pa[4], pa[5], pb[0], pb[1], pb[2], pb[3], pb[4], pb[5]);
    if (setup_len < 0 || (size_t)setup_len >= sizeof setup) {
        fprintf(stderr, "setup text too long\n");
        return 1;
    }
    for (char *line = strtok(setup, "\n"); line; line = strtok(NULL, "\n"))
        if (eval(line) != 0)
            return 1;
    long moving_reads = 0, finals = 0;
    double t_start = now_s();
    for (long k = 0; k < rounds; k++) {
        motion m;
        int to_b = k % 2 == 0;
        memcpy(m.qa, to_b ? qa : qb, sizeof m.qa);
        memcpy(m.qb, to_b ? qb : qa, sizeof m.qb);
        memcpy(m.pb, to_b ? pb : pa, sizeof m.pb);
        m.dur = MOTION_REAL_S;
        m.t_lo = now_s();
        if (fbrl_link_raw(&r.link, to_b ? "MOVE PB" : "MOVE PA") !=
            FBRL_OK) { /* the prompt: the motion began */
            fprintf(stderr, "MOVE failed\n");
            failures++;
            continue;
        }
        m.t_hi = now_s();
        fbrl_clock_sleep_us((uint64_t)(uniform() * MOTION_REAL_S * 1e6));
        live(&m, "W2", NULL, &moving_reads);
        live(&m, "W0", NULL, &moving_reads);
        live(&m, "L1 ACTUAL", "L1", &moving_reads);
        double xyz[3];
        if (eval("L2 ARM-HERE") == 0 && loc_xyz("L2", xyz) == 0) {
            double d =
                sqrt((xyz[0] - m.pb[0]) * (xyz[0] - m.pb[0]) + (xyz[1] - m.pb[1]) * (xyz[1] - m.pb[1]) +
                     (xyz[2] - m.pb[2]) * (xyz[2] - m.pb[2]));
            finals++;
            if (d > 0.001) {
                fprintf(stderr, "ARM-HERE: %.4f %.4f %.4f, the target is %.4f in away\n", xyz[0], xyz[1],
                        xyz[2], d);
                failures++;
            }
        }
    }
    fbrl_link_stats s;
    fbrl_link_get_stats(&r.link, &s);
    rig_stop(&r);
    printf("%ld motions of %.0f ms: %ld live readings (W2 W0 ACTUAL), %ld taken while the arm surely moved, "
           "%ld ARM-HERE at the target; %d failures; %llu position blocks believed on their own consistency, "
           "%llu reads repeated; %.1f s\n",
           rounds, MOTION_REAL_S * 1e3, 3 * rounds, moving_reads, finals, failures,
           (unsigned long long)s.self_checked, (unsigned long long)s.requeries, now_s() - t_start);
    return failures == 0 && moving_reads > rounds ? 0 : 1;
}
