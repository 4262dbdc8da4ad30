/* SPDX-License-Identifier: MIT */
/* bench_robot.c - what the robot words cost on the host side, without a controller: the
 * word dispatch with parameters from the stack, the same word reading its parameter after
 * it (GETINT-style parsing of the input), and building a RAPL line with SEND-* (with
 * mapping off and on). Each figure is a Forth loop of N runs minus the empty loop. The
 * controller round trip itself is in bench_rapl (link over a pty to fbrlsim). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "bench_util.h"

#define N 200000L

static fbrl_vm *vm;

int main(void)
{
    static fbrl_glossary g;
    static fbrl_robot r;
    size_t size = 4 << 20;
    void *mem = malloc(size);
    fbrl_vm_config cfg;
    char src[256];
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = size;
    if (!mem || fbrl_vm_create(&vm, &cfg) != FBRL_OK || fbrl_glossary_install(vm, &g) != FBRL_OK ||
        fbrl_robot_install(vm, &r, NULL, &g) != FBRL_OK)
        return 1;
    bench_eval(vm, ": EMPTY 0 DO LOOP ;\n"
                   ": STACK 0 DO 5 SHIFT-RIGHT 2DROP LOOP ;\n"
                   ": EMPTY-EVAL 0 DO S\" 5 DROP\" EVALUATE LOOP ;\n"
                   ": LINE-EVAL 0 DO S\" SHIFT-RIGHT 5 2DROP\" EVALUATE LOOP ;\n"
                   ": STACK-EVAL 0 DO S\" 5 SHIFT-RIGHT 2DROP\" EVALUATE LOOP ;\n"
                   "CREATE-LOC P  12E0 3E0 8E0 0E0 -90E0 0E0 P DEFINE-LOC "
                   ": BUILD 0 DO 50 SEND-COM S\" PX\" SEND-TEXT SEND-COMMA P SEND-LOC LOOP ;\n"
                   "CREATE-CAL C1 CREATE-CAL C2 CREATE-CAL-STRU S "
                   "CREATE-LOC Q 10E0 -2E0 6E0 0E0 -90E0 0E0 Q DEFINE-LOC C1 1 Q SET-CAL C2 1 Q SET-CAL "
                   "14E0 Q SETX C1 2 Q SET-CAL 13E0 Q SETX 1E0 Q SETY C2 2 Q SET-CAL "
                   "10E0 Q SETX 2E0 Q SETY C1 3 Q SET-CAL 9E0 Q SETX 3E0 Q SETY C2 3 Q SET-CAL "
                   "C2 C1 S CALIBRATE S WITH-CAL");
    snprintf(src, sizeof src, "%ld EMPTY", N);
    double empty = bench_eval(vm, src);
    snprintf(src, sizeof src, "%ld STACK", N);
    double stack = bench_eval(vm, src) - empty;
    snprintf(src, sizeof src, "%ld EMPTY-EVAL", N);
    double eempty = bench_eval(vm, src);
    snprintf(src, sizeof src, "%ld STACK-EVAL", N);
    double estack = bench_eval(vm, src) - eempty;
    snprintf(src, sizeof src, "%ld LINE-EVAL", N);
    double eline = bench_eval(vm, src) - eempty;
    snprintf(src, sizeof src, "%ld BUILD", N);
    double build = bench_eval(vm, src) - empty;
    bench_eval(vm, "MAP-ON");
    snprintf(src, sizeof src, "%ld BUILD", N);
    double build_map = bench_eval(vm, src) - empty;
    printf("robot word, parameters from the stack:          %7.1f ns\n", stack / N * 1e9);
    printf("  interpreted: '5 SHIFT-RIGHT' (stack)           %7.1f ns\n", estack / N * 1e9);
    printf("  interpreted: 'SHIFT-RIGHT 5' (after the word)  %7.1f ns\n", eline / N * 1e9);
    printf("SEND-COM + SEND-TEXT + SEND-COMMA + SEND-LOC:     %7.1f ns (mapping off)\n", build / N * 1e9);
    printf("                                                 %7.1f ns (MAP-ON)\n", build_map / N * 1e9);
    free(mem);
    return 0;
}
