/* SPDX-License-Identifier: MIT */
/* guard_link.c - the guard for C callers (docs/workcell.md "The guard"), against fbrlsim
 * --cell with the same cell (tests/e2e/cell/cell.fbrl) and its stamped log:
 *  - the robot layer from C (fbrl_robot_motion: TEACH's and a station's way): a move into
 *    the post is refused with FBRL_EGUARD and the guard's message, nothing sent; a clear one
 *    runs; one the controller refuses says so (FBRL_ECONTROLLER and its code);
 *  - the link's own commands on a link whose robot has a cell: a motion is refused with
 *    FBRL_EGUARD (fate "not run"), nothing typed; a query still runs; fbrl_link_unguarded
 *    sends the next one around the guard, and the robot's event callback (the run log's
 *    source, fbrl_robot_set_events) is told "UNGUARDED" with the line; the guard then reads
 *    where that left the arm;
 *  - a robot taken off its link (fbrl_robot_set_link NULL) leaves the link without a gate;
 *  - a controller program (RAPL-RUN) is refused while the guard is on: it cannot follow it;
 *  - raw bytes (TYPE-COM) that end a motion line are refused while the guard is on.
 * fbrlsim's log must hold no 190 and none of the refused lines.
 *   guard_link FBRLSIM CELL */
#include "cell_rig.h"

static cell_rig C;
static fbrl_vm *vm; /* C.vm */
static int fails;
static char told[256];
static int ntold;

#define CHECK(cond, ...)                      \
    do {                                      \
        if (!(cond)) {                        \
            fprintf(stderr, "FAIL: " __VA_ARGS__); \
            fprintf(stderr, "\n");            \
            fails++;                          \
        }                                     \
    } while (0)

static void on_event(void *ctx, const fbrl_robot_event *ev)
{
    (void)ctx;
    if (ev->line && strcmp(ev->word, "UNGUARDED") == 0) {
        snprintf(told, sizeof told, "%s", ev->line);
        ntold++;
    }
}

static int in_log(const char *path, const char *text)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int n = 0;
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f))
        n += strstr(line, text) != NULL;
    fclose(f);
    return n;
}

static fbrl_status eval(const char *text) { return fbrl_vm_eval(vm, text, strlen(text)); }

int main(int argc, char **argv)
{
    char dir[256], log_path[600], msg[256];
    if (argc < 3) {
        fprintf(stderr, "usage: guard_link FBRLSIM CELL\n");
        return 2;
    }
    rig_tmpdir(dir, sizeof dir, "guard-link");
    snprintf(log_path, sizeof log_path, "%s/sim.log", dir);
    const char *args[] = {"--time-scale", "50", "--log", log_path, "--log-format", "stamped", NULL};
    static unsigned char mem[2 << 20] __attribute__((aligned(16)));
    if (cell_rig_start(&C, argv[1], argv[2], args, mem, sizeof mem, NULL, NULL) != 0)
        return 1;
    vm = C.vm;
    if (eval("HOME READY FINISH") != FBRL_OK)
        return 1;
    fbrl_robot_set_events(&C.robot, on_event, NULL);

    /* the robot layer from C */
    fbrl_robot_move m;
    memset(&m, 0, sizeof m);
    m.kind = FBRL_ROBOT_MOVE_POSE;
    m.word = "STATION";
    double in_post[6] = {14, 0, 3, 0, -90, 0}, beside[6] = {12, -6, 4, 0, -90, 0};
    memcpy(m.v, in_post, sizeof in_post);
    fbrl_status st = fbrl_robot_motion(&C.robot, &m, msg, sizeof msg);
    CHECK(st == FBRL_EGUARD, "fbrl_robot_motion into the post: %s, want FBRL_EGUARD", fbrl_status_name(st));
    CHECK(strstr(msg, "STATION: would hit POST with the ") == msg && strstr(msg, "; nothing was sent"),
          "its message: \"%s\"", msg);
    memcpy(m.v, beside, sizeof beside);
    st = fbrl_robot_motion(&C.robot, &m, msg, sizeof msg);
    CHECK(st == FBRL_OK && msg[0] == 0, "fbrl_robot_motion beside the post: %s \"%s\"", fbrl_status_name(st), msg);
    memset(&m, 0, sizeof m);
    m.kind = FBRL_ROBOT_MOVE_JOINTS; /* past the elbow's limit (0): the controller's to refuse */
    m.v[1] = 90, m.v[2] = 20;
    st = fbrl_robot_motion(&C.robot, &m, msg, sizeof msg);
    CHECK(st == FBRL_ECONTROLLER && fbrl_robot_last_error(&C.robot) == 44 && strstr(msg, "MOTION: controller error 044"),
          "fbrl_robot_motion past a limit: %s %d \"%s\"", fbrl_status_name(st), fbrl_robot_last_error(&C.robot), msg);
    m.kind = FBRL_ROBOT_MOVE_OTHER;
    CHECK(fbrl_robot_motion(&C.robot, &m, msg, sizeof msg) == FBRL_EINVAL, "a kind fbrl_robot_motion cannot send");

    /* the link's own commands */
    fbrl_rapl_arg down[3] = {fbrl_rapl_real(0), fbrl_rapl_real(0), fbrl_rapl_real(-8)};
    st = fbrl_link_cmd(&C.r.link, FBRL_RAPL_JOG, down, 3, 0); /* from beside the post: through the table */
    CHECK(st == FBRL_EGUARD && fbrl_link_fate_of(st) == FBRL_LINK_NOT_RUN, "a JOG on the link: %s",
          fbrl_status_name(st));
    CHECK(fbrl_link_raw(&C.r.link, "mi 0,0,0,-1,0") == FBRL_EGUARD, "a raw MI in lower case on the link");
    CHECK(fbrl_link_raw(&C.r.link, "/005 0,0,-8") == FBRL_EGUARD, "a JOG by its /NNN token on the link");
    CHECK(fbrl_link_raw(&C.r.link, "FBRLPROG") == FBRL_EGUARD, "a word the host does not know (a program?)");
    CHECK(in_log(log_path, "JOG") == 0 && in_log(log_path, " MI ") == 0 && in_log(log_path, "FBRLPROG") == 0,
          "a refused line reached fbrlsim");
    fbrl_rapl_pos pos;
    CHECK(fbrl_link_where(&C.r.link, FBRL_RAPL_W2, &pos) == FBRL_OK, "a query on the guarded link");
    fbrl_rapl_arg up[3] = {fbrl_rapl_real(0), fbrl_rapl_real(0), fbrl_rapl_real(1)};
    CHECK(fbrl_link_unguarded(&C.r.link) == FBRL_OK, "fbrl_link_unguarded");
    st = fbrl_link_cmd(&C.r.link, FBRL_RAPL_JOG, up, 3, 0);
    CHECK(st == FBRL_OK, "the unguarded JOG: %s", fbrl_status_name(st));
    CHECK(ntold == 1 && strcmp(told, "JOG 0,0,1") == 0, "the event told %d times: \"%s\"", ntold, told);
    CHECK(fbrl_link_cmd(&C.r.link, FBRL_RAPL_JOG, up, 3, 0) == FBRL_EGUARD, "unguarded is for one line only");
    /* the guard reads where the unguarded JOG left the arm: 5 in down is into the table now
     * (the tool 0.5 in past the tool point), not from where it checked last */
    st = eval("0E0 0E0 -5E0 JOG");
    CHECK(st != FBRL_OK && strstr(fbrl_vm_last_error(vm)->message, "JOG: would hit the table"),
          "the word's JOG after the unguarded one: %s", fbrl_vm_last_error(vm)->message);

    /* a controller program may move the arm: the guard cannot follow it */
    st = eval("RAPL-RUN PICK");
    CHECK(st != FBRL_OK &&
              strstr(fbrl_vm_last_error(vm)->message, "RAPL-RUN: the guard cannot follow this motion"),
          "RAPL-RUN with the guard on: %s", fbrl_vm_last_error(vm)->message);
    CHECK(in_log(log_path, "RUN PICK") == 0, "the refused RUN reached fbrlsim");

    /* raw bytes */
    st = eval("S\" JOG 0,0,-8\" SWAP TYPE-COM 13 EMIT-COM");
    CHECK(st != FBRL_OK && strstr(fbrl_vm_last_error(vm)->message, "EMIT-COM: JOG 0,0,-8 would move the arm unchecked by the guard"),
          "raw bytes ending a JOG line: %s", fbrl_vm_last_error(vm)->message);
    st = eval("S\" V1=5\" SWAP TYPE-COM 13 EMIT-COM 1 RESET-COMM");
    CHECK(st == FBRL_OK, "raw bytes ending an assignment: %s", fbrl_vm_last_error(vm)->message);

    /* off the link: the link alone knows no cell */
    fbrl_robot_set_link(&C.robot, NULL);
    CHECK(C.r.link.gate == NULL, "the robot's gate stayed on the link it left");
    CHECK(fbrl_link_cmd(&C.r.link, FBRL_RAPL_JOG, up, 3, 0) == FBRL_OK, "a JOG on a link without a robot");

    CHECK(in_log(log_path, " 190 ") == 0, "a motion hit the cell (fbrlsim's log %s)", log_path);
    CHECK(in_log(log_path, "JOG 0,0,-8") == 0 && in_log(log_path, "POINT FBRLT1,14,0,3,") == 0 &&
              in_log(log_path, "POINT FBRLT2,14,0,3,") == 0,
          "a refused motion reached fbrlsim");
    cell_rig_stop(&C);
    if (fails == 0) {
        unlink(log_path);
        rmdir(dir);
        printf("guard_link: all checks passed\n");
    }
    return fails ? 1 : 0;
}
