/* SPDX-License-Identifier: MIT */
/* rapl_e2e_commands: every command of the RAPL table, encoded by rapl_encode, sent by
 * the link over a real pty to the real fbrlsim binary, and its effect checked: position
 * read-backs after moves, errors 011 029 040 041 042-046, STATUS rows, variables, I/O.
 * Usage: rapl_e2e_commands FBRLSIM keyword|token */
#include <math.h>

#include "rapl_harness.h"

static int failures;
#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            failures++;                                                              \
        }                                                                            \
    } while (0)

static fbrl_link *L;
static char lines[8192]; /* the LINES/STREAM output of the last command */

static void on_line(void *ctx, const char *line, size_t len, int flawed)
{
    (void)ctx;
    (void)flawed;
    if (strlen(lines) + len + 2 < sizeof lines) {
        strncat(lines, line, len);
        strcat(lines, "\n");
    }
}

#define ARGS(...)                           \
    ((const fbrl_rapl_arg[]){__VA_ARGS__}), \
        (sizeof((const fbrl_rapl_arg[]){__VA_ARGS__}) / sizeof(fbrl_rapl_arg))
#define NOARGS NULL, 0
#define I(v)   fbrl_rapl_int(v)
#define R(v)   fbrl_rapl_real(v)
#define S(v)   fbrl_rapl_str(v)

/* Run a command expecting success. */
static void ok_(int line, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n, int straight)
{
    lines[0] = '\0';
    fbrl_status st = fbrl_link_cmd(L, cmd, a, n, straight);
    if (st != FBRL_OK) {
        int code;
        const char *text;
        fbrl_link_error(L, &code, &text);
        fprintf(stderr, "line %d: %s failed: %s (controller %d %s)\n", line, L->line, fbrl_status_name(st),
                code, text);
        failures++;
    }
}
#define OK(cmd, args)  ok_(__LINE__, cmd, args, 0)
#define OKS(cmd, args) ok_(__LINE__, cmd, args, 1)

/* Run a command expecting controller error `code`. */
static void err_(int line, int code, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n, int straight)
{
    fbrl_status st = fbrl_link_cmd(L, cmd, a, n, straight);
    int got = -1;
    const char *text;
    fbrl_link_error(L, &got, &text);
    if (st != FBRL_ECONTROLLER || got != code) {
        fprintf(stderr, "line %d: %s: wanted error %03d, got %s code %d\n", line, L->line, code,
                fbrl_status_name(st), got);
        failures++;
    } else if (strcmp(text, fbrl_rapl_error_text(code)) != 0) {
        fprintf(stderr, "line %d: error text '%s'\n", line, text);
        failures++;
    }
}
#define ERR(code, cmd, args)  err_(__LINE__, code, cmd, args, 0)
#define ERRS(code, cmd, args) err_(__LINE__, code, cmd, args, 1)

static fbrl_rapl_pos where(void)
{
    fbrl_rapl_pos p;
    memset(&p, 0, sizeof p);
    OK(FBRL_RAPL_FINISH, NOARGS);
    fbrl_status st = fbrl_link_where(L, FBRL_RAPL_W2, &p);
    CHECK(st == FBRL_OK);
    CHECK(p.kind == 'A');
    return p;
}

static double tol = 0.001; /* inches and degrees */
static int near(double a, double b) { return fabs(a - b) <= tol; }

/* x y z and pitch of the flange after a move agree with the target. */
static void at_xyz_(int line, double x, double y, double z, double pitch)
{
    fbrl_rapl_pos p = where();
    if (!near(p.world[0], x) || !near(p.world[1], y) || !near(p.world[2], z) || !near(p.world[4], pitch)) {
        fprintf(stderr, "line %d: at %.4f %.4f %.4f pitch %.4f, wanted %.4f %.4f %.4f pitch %.4f\n", line,
                p.world[0], p.world[1], p.world[2], p.world[4], x, y, z, pitch);
        failures++;
    }
}
#define AT(x, y, z, pitch) at_xyz_(__LINE__, x, y, z, pitch)

static void joints_(int line, const double *j)
{
    fbrl_rapl_pos p = where();
    for (int k = 0; k < 5; k++)
        if (!near(p.joints[k], j[k])) {
            fprintf(stderr, "line %d: joint %d = %.4f, wanted %.4f\n", line, k + 1, p.joints[k], j[k]);
            failures++;
        }
}
#define JOINTS(...) joints_(__LINE__, (const double[]){__VA_ARGS__})

static fbrl_rapl_status_info status(void)
{
    fbrl_rapl_status_info s;
    memset(&s, 0, sizeof s);
    CHECK(fbrl_link_status(L, &s) == FBRL_OK);
    return s;
}

/* The raw STATUS text, for the lines the parser does not read. */
static int status_says(const char *text)
{
    lines[0] = '\0';
    CHECK(fbrl_link_raw(L, "STATUS") == FBRL_OK);
    return strstr(lines, text) != NULL;
}

static double typev(const char *expr)
{
    double v = NAN;
    CHECK(fbrl_link_typev(L, expr, &v) == FBRL_OK);
    return v;
}

/* The connect reads the controller's units (docs/link.md 1): a controller left in METRIC
 * (kept in fbrlsim's state file, as in a controller's memory) is refused with FBRL_EUNITS,
 * the link stays usable so NOMETRIC can switch it, and the next connect succeeds. The
 * connect's STATUS lines are not the caller's. */
static void units_at_connect(void)
{
    CHECK(fbrl_link_units(L) == FBRL_LINK_UNITS_INCH);
    CHECK(fbrl_link_raw(L, "METRIC") == FBRL_OK);
    CHECK(fbrl_link_units(L) == FBRL_LINK_UNITS_MM);
    lines[0] = '\0';
    CHECK(fbrl_link_connect(L) == FBRL_EUNITS);
    CHECK(fbrl_link_units(L) == FBRL_LINK_UNITS_MM);
    CHECK(lines[0] == '\0');
    CHECK(fbrl_link_raw(L, "NOMETRIC") == FBRL_OK);
    CHECK(fbrl_link_connect(L) == FBRL_OK);
    CHECK(fbrl_link_units(L) == FBRL_LINK_UNITS_INCH);
}

static void run_all(void)
{
    const double ready[5] = {0, 90, -90, 0, 0};
    CHECK(fbrl_link_connect(L) == FBRL_OK); /* NOHELP, STATUS */
    units_at_connect();

    /* motion before HOME: 041 */
    ERR(41, FBRL_RAPL_READY, NOARGS);
    ERR(41, FBRL_RAPL_JOINT, ARGS(I(1), R(5)));
    OK(FBRL_RAPL_HOME, NOARGS);
    OK(FBRL_RAPL_READY, NOARGS);
    JOINTS(0, 90, -90, 0, 0);
    AT(12, 0, 20, 0);
    OK(FBRL_RAPL_SPEED, ARGS(I(50)));
    fbrl_rapl_status_info s = status();
    CHECK(s.speed == 50.0 && s.homed && s.last_error == 41);

    /* cartesian points, joint and straight moves */
    OK(FBRL_RAPL_POINT, ARGS(S("P1"), R(14), R(2), R(8), R(0), R(-90), R(0)));
    OK(FBRL_RAPL_MOVE, ARGS(S("P1")));
    AT(14, 2, 8, -90);
    OK(FBRL_RAPL_READY, NOARGS);
    OKS(FBRL_RAPL_MOVE, ARGS(S("P1")));
    AT(14, 2, 8, -90);
    OK(FBRL_RAPL_APPRO, ARGS(S("P1"), R(2)));
    AT(14, 2, 10, -90);
    OKS(FBRL_RAPL_APPRO, ARGS(S("P1"), R(1)));
    AT(14, 2, 9, -90);
    OK(FBRL_RAPL_DEPART, ARGS(R(1)));
    AT(14, 2, 10, -90);
    OKS(FBRL_RAPL_DEPART, ARGS(R(1.5)));
    AT(14, 2, 11.5, -90);
    OK(FBRL_RAPL_JOG, ARGS(R(1), R(-1), R(-0.5)));
    AT(15, 1, 11, -90);
    OK(FBRL_RAPL_HERE, ARGS(S("H1")));
    OK(FBRL_RAPL_ACTUAL, ARGS(S("#A1")));
    OK(FBRL_RAPL_READY, NOARGS);
    OK(FBRL_RAPL_MOVE, ARGS(S("H1")));
    AT(15, 1, 11, -90);
    OK(FBRL_RAPL_READY, NOARGS);
    OK(FBRL_RAPL_MOVE, ARGS(S("#A1")));
    tol = 0.05; /* a precision point is whole motor pulses: 1 pulse of joint 4 = 0.0225 deg */
    AT(15, 1, 11, -90);
    tol = 0.001;

    /* joints, motors, radians */
    OK(FBRL_RAPL_READY, NOARGS);
    OK(FBRL_RAPL_JOINT, ARGS(I(1), R(10)));
    JOINTS(10, 90, -90, 0, 0);
    OK(FBRL_RAPL_MOTOR, ARGS(I(1), I(-400)));
    JOINTS(8, 90, -90, 0, 0);
    OK(FBRL_RAPL_MA, ARGS(R(0), R(M_PI / 2), R(-M_PI / 2), R(0), R(0)));
    JOINTS(0, 90, -90, 0, 0);
    OK(FBRL_RAPL_MI, ARGS(R(0.1), R(0), R(0), R(0), R(0)));
    JOINTS(0.1 * 180 / M_PI, 90, -90, 0, 0);
    OKS(FBRL_RAPL_MA, ARGS(R(0), R(M_PI / 2), R(-M_PI / 2), R(0), R(0)));
    JOINTS(0, 90, -90, 0, 0);
    OKS(FBRL_RAPL_MI, ARGS(R(0), R(0), R(0), R(-0.2), R(0)));
    fbrl_rapl_pos before = where();
    CHECK(near(before.joints[3], -0.2 * 180 / M_PI));
    OK(FBRL_RAPL_ALIGN, NOARGS); /* keeps the tool point, pitch to the nearest of -90 0 90 */
    AT(before.world[0], before.world[1], before.world[2], 0);

    /* precision point, SET, SHIFTA, TOOL */
    OK(FBRL_RAPL_POINT, ARGS(S("#PP"), I(0), I(18000), I(-18000), I(0), I(0)));
    OK(FBRL_RAPL_MOVE, ARGS(S("P1")));
    OK(FBRL_RAPL_MOVE, ARGS(S("#PP")));
    JOINTS(0, 90, -90, 0, 0);
    OK(FBRL_RAPL_SET, ARGS(S("Q1"), S("P1")));
    OK(FBRL_RAPL_POINT, ARGS(S("D"), R(1), R(0), R(0.5), R(0), R(0), R(0)));
    OK(FBRL_RAPL_SHIFTA, ARGS(S("Q1"), S("D")));
    OK(FBRL_RAPL_MOVE, ARGS(S("Q1")));
    AT(15, 2, 8.5, -90);
    OK(FBRL_RAPL_POINT, ARGS(S("TL"), R(0), R(0), R(1), R(0), R(0), R(0)));
    OK(FBRL_RAPL_TOOL, ARGS(S("TL")));
    AT(15, 2, 7.5, -90); /* the tool point is 1 in beyond the flange, straight down */
    OK(FBRL_RAPL_TOOL, NOARGS);
    AT(15, 2, 8.5, -90);

    /* errors: unreachable 029, joint limits 042-046, undefined 011 */
    OK(FBRL_RAPL_READY, NOARGS);
    OK(FBRL_RAPL_POINT, ARGS(S("FAR"), R(30), R(0), R(10), R(0), R(-90), R(0)));
    ERR(29, FBRL_RAPL_MOVE, ARGS(S("FAR")));
    ERR(29, FBRL_RAPL_APPRO, ARGS(S("FAR"), R(1)));
    ERR(42, FBRL_RAPL_JOINT, ARGS(I(1), R(200)));
    ERR(43, FBRL_RAPL_JOINT, ARGS(I(2), R(30)));
    ERR(44, FBRL_RAPL_JOINT, ARGS(I(3), R(100)));
    ERR(45, FBRL_RAPL_JOINT, ARGS(I(4), R(120)));
    ERR(46, FBRL_RAPL_JOINT, ARGS(I(5), R(200)));
    ERR(42, FBRL_RAPL_MA, ARGS(R(3.1), R(M_PI / 2), R(-M_PI / 2), R(0), R(0)));
    ERR(11, FBRL_RAPL_MOVE, ARGS(S("NOPE")));
    ERR(11, FBRL_RAPL_APPRO, ARGS(S("NOPE"), R(1)));
    JOINTS(0, 90, -90, 0, 0); /* failed motions did not move the arm */
    s = status();
    CHECK(s.last_error == 11);

    /* LIMP / NOLIMP, LOCK / UNLOCK */
    OK(FBRL_RAPL_LIMP, ARGS(I(2)));
    s = status();
    CHECK(s.limp[1] == 1 && s.limp[0] == 0);
    ERR(18, FBRL_RAPL_READY, NOARGS);
    OK(FBRL_RAPL_NOLIMP, NOARGS);
    s = status();
    CHECK(s.limp[1] == 0);
    OK(FBRL_RAPL_LIMP, NOARGS);
    CHECK(status().limp[4] == 1);
    OK(FBRL_RAPL_NOLIMP, NOARGS);
    OK(FBRL_RAPL_LOCK, ARGS(I(1), I(3)));
    s = status();
    CHECK(s.lock[0] == 1 && s.lock[1] == 0 && s.lock[2] == 1);
    OK(FBRL_RAPL_UNLOCK, ARGS(I(3)));
    CHECK(status().lock[2] == 0);
    OK(FBRL_RAPL_UNLOCK, NOARGS);
    CHECK(status().lock[0] == 0);

    /* gripper */
    OK(FBRL_RAPL_GRIP, ARGS(R(1.25)));
    CHECK(near(typev("GRIPPER"), 1.25));
    OK(FBRL_RAPL_GRIP, ARGS(R(0.5), I(30)));
    CHECK(near(typev("GRIPPER"), 0.5));
    OK(FBRL_RAPL_OPEN, NOARGS);
    CHECK(near(typev("GRIPPER"), 2.0));
    OK(FBRL_RAPL_CLOSE, ARGS(I(40)));
    CHECK(near(typev("GRIPPER"), 0.0));
    OK(FBRL_RAPL_OPEN, ARGS(I(60)));
    OK(FBRL_RAPL_CLOSE, NOARGS);

    /* I/O: outputs, inputs (set by the --inputs schedule: input 5 on at 0.3 s) */
    OK(FBRL_RAPL_OUTPUT, ARGS(I(3), I(-4), I(16)));
    s = status();
    CHECK(s.outputs == ((1u << 2) | (1u << 15)));
    long iv = -1;
    CHECK(fbrl_link_typei(L, "OSIG(3)", &iv) == FBRL_OK && iv == 1);
    OK(FBRL_RAPL_OUTPUT, ARGS(I(-3)));
    CHECK(fbrl_link_typei(L, "OSIG(3)", &iv) == FBRL_OK && iv == 0);
    OK(FBRL_RAPL_WAIT, ARGS(I(5), I(-6)));
    int on = -1;
    CHECK(fbrl_link_input(L, 5, &on) == FBRL_OK && on == 1);
    CHECK(fbrl_link_input(L, 6, &on) == FBRL_OK && on == 0);
    CHECK(fbrl_link_input(L, 17, &on) == FBRL_ERANGE);

    /* variables */
    OK(FBRL_RAPL_ASSIGN, ARGS(S("V1"), R(2.25)));
    CHECK(near(typev("V1"), 2.25));
    CHECK(fbrl_link_typei(L, "V1", &iv) == FBRL_OK && iv == 2);
    OK(FBRL_RAPL_ASSIGN, ARGS(S("COUNT"), I(-7)));
    CHECK(fbrl_link_typei(L, "COUNT", &iv) == FBRL_OK && iv == -7);
    OK(FBRL_RAPL_TYPEI, ARGS(S("COUNT")));
    OK(FBRL_RAPL_TYPEV, ARGS(S("V1")));
    ERR(10, FBRL_RAPL_TYPEV, ARGS(S("NOVAR")));

    /* serial settings, lamp, manual, teach, arm power, halt, gain, extra axis, run */
    OK(FBRL_RAPL_CONFIG, ARGS(I(1), I(4800), S("E"), I(7), I(2), S("N"), I(1)));
    OK(FBRL_RAPL_SERIAL, NOARGS);
    CHECK(strstr(lines, "CHANNEL 1: BAUD 4800 PARITY E DATA 7 STOP 2 HANDSHAKE N ECHO 1") != NULL);
    OK(FBRL_RAPL_FLASH, ARGS(I(2)));
    CHECK(status_says("PENDANT LAMP IS FLASHING"));
    OK(FBRL_RAPL_NOFLASH, NOARGS);
    CHECK(status_says("PENDANT LAMP IS OFF"));
    OK(FBRL_RAPL_MANUAL, ARGS(S("CYL")));
    CHECK(status_says("MANUAL MODE STATUS IS ON"));
    OK(FBRL_RAPL_NOMANUAL, NOARGS);
    CHECK(status_says("MANUAL MODE STATUS IS OFF"));
    OK(FBRL_RAPL_MANUAL, NOARGS);
    OK(FBRL_RAPL_NOMANUAL, NOARGS);
    OK(FBRL_RAPL_TEACH, ARGS(S("TCH")));
    CHECK(status_says("TEACH MODE IS ON"));
    OK(FBRL_RAPL_NOTEACH, NOARGS);
    CHECK(status_says("TEACH MODE IS OFF"));
    OK(FBRL_RAPL_ARM, ARGS(S("OFF")));
    ERR(40, FBRL_RAPL_MOVE, ARGS(S("P1")));
    OK(FBRL_RAPL_ARM, ARGS(S("ON")));
    OK(FBRL_RAPL_MOVE, ARGS(S("P1")));
    OK(FBRL_RAPL_HALT, NOARGS);
    OK(FBRL_RAPL_GAIN, ARGS(I(1), R(2.5)));
    OK(FBRL_RAPL_GAIN, ARGS(I(1)));
    CHECK(strstr(lines, "GAIN MOTOR 1: +2.5000") != NULL);
    OK(FBRL_RAPL_XCAL, ARGS(I(6)));
    OK(FBRL_RAPL_XHOME, ARGS(I(6)));
    OK(FBRL_RAPL_XZERO, ARGS(I(6)));
    ERR(65, FBRL_RAPL_XHOME, ARGS(I(7)));
    ERR(17, FBRL_RAPL_RUN, ARGS(S("NOPROG")));
    ERR(17, FBRL_RAPL_RUN, ARGS(S("NOPROG"), I(2)));
    OK(FBRL_RAPL_NOHELP, NOARGS);

    /* read-backs: W0 W4, and the continuous ones */
    OK(FBRL_RAPL_READY, NOARGS);
    OK(FBRL_RAPL_FINISH, NOARGS);
    fbrl_rapl_pos p;
    CHECK(fbrl_link_where(L, FBRL_RAPL_W0, &p) == FBRL_OK && p.kind == 'C' && near(p.joints[2], -90));
    CHECK(fbrl_link_where(L, FBRL_RAPL_W4, &p) == FBRL_OK && p.kind == 'E' && near(p.joints[1], 90));
    static const fbrl_rapl_cmd streams[] = {FBRL_RAPL_W1,  FBRL_RAPL_W3,  FBRL_RAPL_W5,
                                            FBRL_RAPL_WE1, FBRL_RAPL_WE3, FBRL_RAPL_WE5};
    for (size_t k = 0; k < 6; k++) {
        lines[0] = '\0';
        CHECK(fbrl_link_stream(L, streams[k], 2) == FBRL_OK);
        CHECK(strstr(lines, k < 3 ? "(MOTOR PULSES):" : "EXTRA AXIS") != NULL ||
              strstr(lines, "VELOCITY") != NULL);
    }
    lines[0] = '\0';
    CHECK(fbrl_link_stream(L, FBRL_RAPL_W1, 3) == FBRL_OK);
    CHECK(strstr(lines, "+0000018000 -0000018000") != NULL); /* READY pulses */
    JOINTS(ready[0], ready[1], ready[2], ready[3], ready[4]);

    /* the link is still in step after all that */
    fbrl_link_stats stt;
    fbrl_link_get_stats(L, &stt);
    fprintf(stderr, "commands %llu executed %llu attempts %llu mismatches %llu probes %llu failed %llu\n",
            (unsigned long long)stt.commands, (unsigned long long)stt.executed,
            (unsigned long long)stt.attempts, (unsigned long long)stt.echo_mismatch,
            (unsigned long long)stt.probes, (unsigned long long)stt.failed);
    CHECK(stt.failed == 0);
}

/* Token form: fbrlsim knows every /NNN number of the library's table (it reads the same
 * table). Each command that needs arguments is sent as its bare token: the controller
 * must refuse it for the arguments, never as an unknown command (012). */
static void every_token_is_known(void)
{
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++) {
        const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)c);
        if (!ci->token || !ci->sig[0] || ci->sig[0] == '[')
            continue;
        char text[8];
        snprintf(text, sizeof text, "/%03u", (unsigned)ci->token);
        fbrl_status st = fbrl_link_raw(L, text);
        int code = -1;
        fbrl_link_error(L, &code, NULL);
        if ((st != FBRL_OK && st != FBRL_ECONTROLLER) || code == 12) {
            fprintf(stderr, "%s (%s): %s, code %d\n", text, ci->keyword, fbrl_status_name(st), code);
            failures++;
        }
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s FBRLSIM keyword|token\n", argv[0]);
        return 2;
    }
    char dir[64], state[128], inputs[128];
    rig_tmpdir(dir, sizeof dir, "rapl");
    snprintf(state, sizeof state, "%s/state", dir);
    snprintf(inputs, sizeof inputs, "%s/inputs", dir);
    FILE *f = fopen(inputs, "w");
    if (!f)
        return 1;
    fputs("0.3 IN 5 1\n", f);
    fclose(f);
    const char *args[] = {"--time-scale", "50", "--state", state, "--inputs", inputs, NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    cfg.form = strcmp(argv[2], "token") == 0 ? FBRL_RAPL_TOKEN : FBRL_RAPL_KEYWORD;
    cfg.on_line = on_line;
    cfg.wait_timeout_ms = 30000;
    rig r;
    if (rig_start(&r, argv[1], args, 115200, FBRL_FLOW_NONE, &cfg) != 0)
        return 1;
    L = &r.link;
    run_all();
    if (cfg.form == FBRL_RAPL_TOKEN)
        every_token_is_known();
    rig_stop(&r);
    remove(state);
    remove(inputs);
    rmdir(dir);
    if (failures)
        fprintf(stderr, "%d failures\n", failures);
    else
        fprintf(stderr, "all commands ok (%s form)\n", argv[2]);
    return failures ? 1 : 0;
}
