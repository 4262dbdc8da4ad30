/* SPDX-License-Identifier: MIT */
/* sample_prep.c - a short version of examples/sample_prep.fbrl driven from C through the
 * public API: the POSIX serial backend, the echo-verified RAPL link, and an FBRL VM with
 * the data glossary and the robot words evaluating a few lines of the plan.
 *
 *   1. link:  connect (NOHELP), HOME, READY, SPEED 50             (fbrl_link_cmd)
 *   2. FBRL:  the heating block's tubes (RECTMAT) and locating pins; teach where the pins
 *             are today by moving the arm there and reading it back (ARM-HERE); CALIBRATE,
 *             WITH-CAL, MAP-ON; visit tubes A1..A3; dispense 2 ml; pulse the vacuum valve
 *   3. link:  the separation unit's tube sensor (TYPEI SIG(3)), READY, FINISH and where
 *             the arm ended (W2)                          (fbrl_link_input/finish/where)
 *
 * Usage: sample_prep PORT    (a serial device, a pty such as fbrlsim's, or tcp:HOST:PORT)
 * Exit status 0 when every step worked; 1 with one line on stderr saying what failed. */
#define _POSIX_C_SOURCE 200809L /* posix_memalign */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fbrl/clock.h"
#include "fbrl/glossary.h"
#include "fbrl/link.h"
#include "fbrl/robot.h"
#include "fbrl/uart_posix.h"
#include "fbrl/vm.h"

#define VM_BYTES (1u << 20)

/* The plan's FBRL part: each string is evaluated as one line. */
static const char *const plan[] = {
    /* the heating block: 4 x 6 tubes 0.75 in apart, and its three locating pins as taught */
    "CREATE-LOC A1  10E0 -2E0 3E0 0E0 -90E0 0E0 A1 DEFINE-LOC",
    "A1 0.75E0 0.75E0 0E0 RECTMAT BLOCK-TUBE",
    "CREATE-LOC PIN-1   9.5E0 -2.5E0 2.5E0 0E0 -90E0 0E0 PIN-1 DEFINE-LOC",
    "CREATE-LOC PIN-2  13.5E0 -2.5E0 2.5E0 0E0 -90E0 0E0 PIN-2 DEFINE-LOC",
    "CREATE-LOC PIN-3   9.5E0  2.5E0 2.5E0 0E0 -90E0 0E0 PIN-3 DEFINE-LOC",
    "CREATE-CAL AS-TAUGHT  AS-TAUGHT 1 PIN-1 SET-CAL  AS-TAUGHT 2 PIN-2 SET-CAL"
    "  AS-TAUGHT 3 PIN-3 SET-CAL",
    /* the block was cleaned and put back: bring the gripper onto each pin as it stands
     * today and take the arm's position (mapping is off: physical coordinates) */
    "CREATE-CAL TODAY  CREATE-CAL-STRU HEATING-BLOCK  CREATE-LOC NOW",
    ": TEACH ( cal slot -- ) NOW ARM-HERE  NOW SET-CAL ;",
    "PIN-1 0.5E0 APPROACH  JOG 0.30 -0.40 -0.45  TODAY 1 TEACH",
    "PIN-2 0.5E0 APPROACH  JOG 0.30 -0.26 -0.45  TODAY 2 TEACH",
    "PIN-3 0.5E0 APPROACH  JOG 0.13 -0.40 -0.45  TODAY 3 TEACH",
    "TODAY AS-TAUGHT HEATING-BLOCK CALIBRATE  HEATING-BLOCK WITH-CAL  1E0 DEPART-STRT",
    ".( tube A1 stored: ) A1 DISPLAY-LOC",
    "MAP-ON .( tube A1 today:  ) A1 DISPLAY-LOC",
    /* the first three tubes, through the calibration */
    "CREATE-LOC SPOT",
    ": VISIT ( col -- ) 0 SWAP 0 SPOT BLOCK-TUBE  SPOT 1E0 APPROACH  SPOT MOV-STRT"
    "  1E0 DEPART-STRT ;",
    "0 VISIT  1 VISIT  2 VISIT  MAP-OFF",
    /* peripherals by name */
    "1 OUTPUT-DEVICE BUFFER-PUMP  50 BUFFER-PUMP PULSE-WIDTH  2E0 BUFFER-PUMP DISPENSE",
    "5 OUTPUT-DEVICE SEPARATOR-VACUUM  100 SEPARATOR-VACUUM PULSE",
    ".( dispensed 2 ml, vacuum pulsed) CR",
};

static void con_write(void *user, const char *s, size_t n)
{
    (void)user;
    fwrite(s, 1, n, stdout);
}

static uint64_t con_now_us(void *user)
{
    (void)user;
    return fbrl_clock_now_us();
}

static void con_sleep_ms(void *user, uint32_t ms)
{
    (void)user;
    fbrl_clock_sleep_us((uint64_t)ms * 1000u);
}

static int failed(const char *what, fbrl_status st)
{
    fprintf(stderr, "sample_prep: %s: %s\n", what, fbrl_status_str(st));
    return 1;
}

/* One command through the link, with the controller's own message on an error. */
static int cmd(fbrl_link *link, fbrl_rapl_cmd c, const fbrl_rapl_arg *args, size_t nargs, const char *what)
{
    fbrl_status st = fbrl_link_cmd(link, c, args, nargs, 0);
    if (st == FBRL_ECONTROLLER) {
        int code = 0;
        const char *text = "";
        fbrl_link_error(link, &code, &text);
        fprintf(stderr, "sample_prep: %s: controller error %03d-%s\n", what, code, text);
        return 1;
    }
    return st == FBRL_OK ? 0 : failed(what, st);
}

static int run_plan(fbrl_vm *vm)
{
    size_t i;
    for (i = 0; i < sizeof plan / sizeof plan[0]; i++) {
        if (fbrl_vm_eval(vm, plan[i], strlen(plan[i])) != FBRL_OK) {
            const fbrl_vm_error *e = fbrl_vm_last_error(vm);
            fflush(stdout);
            fprintf(stderr, "sample_prep: error %d: %s in %s (plan line %lu)\n", e->throw_code, e->message,
                    e->word, (unsigned long)i + 1);
            return 1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    static unsigned char rx[4096], tx[4096];
    static fbrl_uart_posix port;
    static fbrl_uart uart;
    static fbrl_link link;
    static fbrl_glossary glossary;
    static fbrl_robot robot;
    fbrl_uart_config line = FBRL_UART_CONFIG_DEFAULT; /* 9600 8N1, XON/XOFF */
    fbrl_link_config lc;
    fbrl_vm_config vc;
    fbrl_vm *vm = NULL;
    fbrl_rapl_pos pos;
    fbrl_rapl_arg speed = fbrl_rapl_int(50);
    void *mem = NULL;
    fbrl_status st;
    int tube = 0, rc = 1;

    if (argc != 2) {
        fprintf(stderr, "usage: %s PORT\n", argv[0]);
        return 2;
    }
    st = fbrl_uart_posix_open(&port, &uart, argv[1], &line, rx, sizeof rx, tx, sizeof tx, NULL);
    if (st != FBRL_OK)
        return failed(argv[1], st);

    fbrl_link_config_init(&lc);
    lc.echo_timeout_ms = 500; /* a loaded host may stall us; the controller is not slow */
    st = fbrl_link_init(&link, &uart, &lc);
    if (st == FBRL_OK)
        st = fbrl_link_connect(&link);
    if (st != FBRL_OK) {
        rc = failed("no controller answers", st);
        goto out;
    }

    /* 1. straight through the link */
    if (cmd(&link, FBRL_RAPL_HOME, NULL, 0, "HOME") || cmd(&link, FBRL_RAPL_READY, NULL, 0, "READY") ||
        cmd(&link, FBRL_RAPL_SPEED, &speed, 1, "SPEED"))
        goto out;

    /* 2. the FBRL part: a VM whose robot words use the same link */
    if (posix_memalign(&mem, 16, VM_BYTES) != 0) {
        fprintf(stderr, "sample_prep: no memory for the VM\n");
        goto out;
    }
    memset(&vc, 0, sizeof vc);
    vc.mem = mem;
    vc.mem_size = VM_BYTES;
    vc.host.write = con_write;
    vc.host.now_us = con_now_us;
    vc.host.sleep_ms = con_sleep_ms;
    st = fbrl_vm_create(&vm, &vc);
    if (st == FBRL_OK)
        st = fbrl_glossary_install(vm, &glossary);
    if (st == FBRL_OK)
        st = fbrl_robot_install(vm, &robot, &link, &glossary);
    if (st != FBRL_OK) {
        rc = failed("VM setup", st);
        goto out;
    }
    if (run_plan(vm))
        goto out;

    /* 3. back to the link: the sensor, home position, where the arm is */
    st = fbrl_link_input(&link, 3, &tube);
    if (st != FBRL_OK) {
        rc = failed("tube sensor", st);
        goto out;
    }
    printf("tube on the separation unit: %s\n", tube ? "yes" : "no");
    if (cmd(&link, FBRL_RAPL_READY, NULL, 0, "READY"))
        goto out;
    st = fbrl_link_finish(&link); /* the motion's end, not a point on the way */
    if (st == FBRL_OK)
        st = fbrl_link_where(&link, FBRL_RAPL_W2, &pos);
    if (st != FBRL_OK) {
        rc = failed("W2", st);
        goto out;
    }
    printf("arm at X %.4f Y %.4f Z %.4f in\n", pos.world[0], pos.world[1], pos.world[2]);
    rc = 0;
out:
    fflush(stdout);
    fbrl_uart_close(&uart);
    free(mem);
    return rc;
}
