/* SPDX-License-Identifier: MIT */
/* fuzz_eval.c - fuzz target for the FBRL evaluator: any input text, evaluated
 * in a fresh VM, must never crash, hang or touch memory outside the VM, and the
 * VM must stay usable afterwards.
 *
 * The VM lives in a static buffer with the whole language the monitor has (the
 * glossary words, and the robot words offline), and no host services except
 * output (discarded), so the input cannot open files, sleep or move an arm. An input that loops
 * forever (legal Forth: BEGIN AGAIN) is stopped the way the monitor's Ctrl-C
 * stops it: a CPU-time alarm calls fbrl_vm_interrupt(), and the engine throws
 * -28 at its next loop step. (SIGVTALRM, because libFuzzer keeps SIGALRM for
 * its own -timeout, which still catches a loop the engine would not stop.) */
#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <sys/time.h>

#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"

#define FUZZ_MEM_BYTES    (512u * 1024u)
#define FUZZ_CPU_LIMIT_US 200000

/* long double makes the buffer 16-byte aligned, as fbrl_vm_config asks (C99 has no _Alignas). */
static union {
    long double align;
    unsigned char bytes[FUZZ_MEM_BYTES];
} vm_mem;
static fbrl_glossary glossary;
static fbrl_robot robot;
static fbrl_vm *volatile running_vm;

static void on_vtalrm(int sig)
{
    fbrl_vm *vm = running_vm;
    (void)sig;
    if (vm != NULL)
        fbrl_vm_interrupt(vm);
}

static void discard(void *user, const char *s, size_t n)
{
    (void)user;
    (void)s;
    (void)n;
}

static void arm_timer(long us)
{
    struct itimerval it;
    memset(&it, 0, sizeof it);
    it.it_value.tv_sec = us / 1000000;
    it.it_value.tv_usec = us % 1000000;
    it.it_interval = it.it_value; /* repeat: one request may land between two evaluations */
    setitimer(ITIMER_VIRTUAL, &it, NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int installed;
    fbrl_vm_config cfg;
    fbrl_vm *vm = NULL;

    if (!installed) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_vtalrm;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;
        sigaction(SIGVTALRM, &sa, NULL);
        installed = 1;
    }
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = vm_mem.bytes;
    cfg.mem_size = sizeof vm_mem.bytes;
    cfg.host.write = discard;
    if (fbrl_vm_create(&vm, &cfg) != FBRL_OK || fbrl_glossary_install(vm, &glossary) != FBRL_OK ||
        fbrl_robot_install(vm, &robot, NULL, &glossary) != FBRL_OK)
        return 0;
    running_vm = vm;
    arm_timer(FUZZ_CPU_LIMIT_US);
    /* Whatever happened, the VM must still evaluate. */
    if (fbrl_vm_eval(vm, (const char *)data, size) != FBRL_OK && !fbrl_vm_bye(vm))
        fbrl_vm_eval(vm, "1 2 + DROP", 10);
    arm_timer(0);
    running_vm = NULL;
    return 0;
}
