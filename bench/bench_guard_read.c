/* SPDX-License-Identifier: MIT */
/* bench_guard_read: what the guard's reading of the arm costs each motion it checks
 * (docs/workcell.md "The guard"), on fbrlsim's strict --baud 9600 line: the two readings
 * (one line of W1, the whole W2 block) alone, and ROUNDS moves between two places with no
 * cell described (nothing read) and with one (the guard reads the arm before each).
 * Usage: bench_guard_read [FBRLSIM] [ROUNDS]  (defaults ./sim/fbrlsim 10) */
#include <stdio.h>
#include <stdlib.h>

#include "../tests/e2e/rapl_harness.h"
#include "fbrl/cell_words.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"

static fbrl_vm *vm;

static void eval(const char *text)
{
    if (fbrl_vm_eval(vm, text, strlen(text)) != FBRL_OK) {
        fprintf(stderr, "%s: %s\n", text, fbrl_vm_last_error(vm)->message);
        exit(1);
    }
}

static double moves_ms(int rounds)
{
    uint64_t t0 = fbrl_clock_now_us();
    for (int k = 0; k < rounds; k++)
        eval("P1 MOV P2 MOV");
    eval("FINISH");
    return (double)(fbrl_clock_now_us() - t0) / 1000.0 / (2.0 * rounds);
}

int main(int argc, char **argv)
{
    static rig R;
    static fbrl_glossary g;
    static fbrl_robot r;
    static fbrl_cell_words cw;
    static unsigned char mem[2 << 20] __attribute__((aligned(16)));
    const char *sim = argc > 1 ? argv[1] : "./sim/fbrlsim";
    int rounds = argc > 2 ? atoi(argv[2]) : 10;
    const char *args[] = {"--baud", "9600", NULL};
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = sizeof mem;
    if (rig_start(&R, sim, args, 9600, FBRL_FLOW_XONXOFF, NULL) != 0 || fbrl_link_connect(&R.link) != FBRL_OK ||
        fbrl_vm_create(&vm, &cfg) != FBRL_OK || fbrl_glossary_install(vm, &g) != FBRL_OK ||
        fbrl_robot_install(vm, &r, &R.link, &g) != FBRL_OK || fbrl_cell_install(vm, &cw, &r, &g) != FBRL_OK)
        return 1;
    eval("HOME READY FINISH "
         "CREATE-LOC P1 12E0 4E0 10E0 0E0 -90E0 0E0 P1 DEFINE-LOC "
         "CREATE-LOC P2 12E0 -4E0 10E0 0E0 -90E0 0E0 P2 DEFINE-LOC");
    /* the readings alone, the arm standing */
    long pulses[FBRL_RAPL_MAX_AXES];
    unsigned n;
    fbrl_rapl_pos p;
    uint64_t t0 = fbrl_clock_now_us();
    for (int k = 0; k < rounds; k++)
        if (fbrl_robot_pulses(&r, "BENCH", pulses, &n) != FBRL_OK)
            return 1;
    double w1 = (double)(fbrl_clock_now_us() - t0) / 1000.0 / rounds;
    t0 = fbrl_clock_now_us();
    for (int k = 0; k < rounds; k++)
        if (fbrl_robot_position(&r, "BENCH", &p) != FBRL_OK)
            return 1;
    double w2 = (double)(fbrl_clock_now_us() - t0) / 1000.0 / rounds;
    double none = moves_ms(rounds);
    eval("0E0 CELL-TABLE 13E0 -1E0 0E0 15E0 1E0 6E0 CELL-BOX POST");
    double guarded = moves_ms(rounds);
    printf("9600 baud, %d rounds: a reading of the standing arm: W1 line %.0f ms, W2 block %.0f ms\n", rounds, w1,
           w2);
    printf("a move (POINT, MOVE, the wait for its end): %.0f ms with no cell, %.0f ms checked by the guard "
           "(+%.0f ms)\n",
           none, guarded, guarded - none);
    printf("| guard: reading the arm before a checked move, 9600 baud | +%.0f ms a move (W1 %.0f ms, W2 %.0f ms) |\n",
           guarded - none, w1, w2);
    rig_stop(&R);
    return 0;
}
