/* SPDX-License-Identifier: MIT */
/* bench_glossary.c - cost of the data glossary words as a program sees them: each figure is
 * a Forth loop running one word (plus the loop and its arguments) a million times, and the
 * same loop empty, so the word's own cost is the difference. Also the C interface the robot
 * words use per move (fbrl_glossary_map_out). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "fbrl/glossary.h"
#include "fbrl/vm.h"
#include "bench_util.h"

#define N 1000000L

static fbrl_vm *vm;

static void ev(const char *src) { (void)bench_eval(vm, src); }

int main(void)
{
    static fbrl_glossary g;
    size_t size = 4 << 20;
    void *mem = malloc(size);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = size;
    if (!mem || fbrl_vm_create(&vm, &cfg) != FBRL_OK || fbrl_glossary_install(vm, &g) != FBRL_OK) {
        fprintf(stderr, "setup failed\n");
        return 1;
    }
    /* P's tool points straight down: a 5-axis arm follows a block's turn about z only with
     * its tool axis in the waist plane, so MAP refuses a tilted tool turned across the arm
     * (docs/calibration.md); this one maps, orientation included. */
    ev("CREATE-LOC P 1E0 2E0 3E0 30E0 -90E0 10E0 P DEFINE-LOC CREATE-LOC Q "
       "P 0.75E0 0.75E0 0.5E0 RECTMAT MAT  P 0.2E0 0.5E0 1E0 RADMAT RM "
       "CREATE-CAL-STRU S 0E0 S 1 CAL-STRU! -1E0 S 2 CAL-STRU! 10E0 S 4 CAL-STRU! "
       "1E0 S 5 CAL-STRU! 0E0 S 6 CAL-STRU! 5E0 S 8 CAL-STRU! S WITH-CAL");
    ev(": EMPTY-LOOP 1000000 0 DO Q DROP LOOP ; "
       ": GETX-LOOP 1000000 0 DO P GETX FDROP LOOP ; "
       ": SETX-LOOP 1000000 0 DO 1E0 Q SETX LOOP ; "
       ": DEFINE-LOOP 1000000 0 DO 1E0 2E0 3E0 0E0 -90E0 0E0 Q DEFINE-LOC LOOP ; "
       ": MAT-LOOP 1000000 0 DO I 3 AND 1 2 Q MAT LOOP ; "
       ": RM-LOOP 1000000 0 DO I 3 AND 1 2 Q RM LOOP ; "
       ": MAP-LOOP 1000000 0 DO S P (MAP) LOOP ; "
       ": UNMAP-LOOP 1000000 0 DO S P UNMAP LOOP ;");
    double base = bench_eval(vm, "EMPTY-LOOP");
    struct {
        const char *what, *src;
    } w[] = {
        {"GETX", "GETX-LOOP"},
        {"SETX (float literal)", "SETX-LOOP"},
        {"DEFINE-LOC (6 float literals)", "DEFINE-LOOP"},
        {"RECTMAT run (i j k loc)", "MAT-LOOP"},
        {"RADMAT run (ring idx k loc)", "RM-LOOP"},
        {"(MAP) (position and orientation)", "MAP-LOOP"},
        {"UNMAP", "UNMAP-LOOP"},
    };
    printf("empty loop (loop + 1 literal): %.1f ns per iteration\n", base / N * 1e9);
    for (size_t i = 0; i < sizeof w / sizeof w[0]; i++) {
        double t = bench_eval(vm, w[i].src);
        printf("%-36s %8.1f ns per call (loop included %.1f ns)\n", w[i].what, (t - base) / N * 1e9,
               t / N * 1e9);
    }
    ev("MAP-ON");
    fbrl_loc l = {1, 2, 3, 30, -90, 10}, m;
    double t0 = bench_now();
    for (long i = 0; i < N; i++) {
        m = l;
        if (fbrl_glossary_map_out(&g, &m, NULL, NULL) != FBRL_OK)
            return 1;
    }
    printf("%-36s %8.1f ns per call\n", "fbrl_glossary_map_out (MAP-ON)", (bench_now() - t0) / N * 1e9);
    free(mem);
    return 0;
}
