/* main.c - fbrlsim: a RAPL-II robot controller emulator on a pseudo-terminal.
 * Usage: see usage() and docs/fbrlsim.md. */
#include "fbrlsim.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef FBRL_VERSION
#define FBRL_VERSION "unknown"
#endif

static fbrl_sim *g_sim;

static void on_signal(int sig)
{
    (void)sig;
    fbrl_sim_stop(g_sim);
}

static void usage(FILE *f)
{
    fputs("usage: fbrlsim [options]\n"
          "  Emulates a CRS robot controller (RAPL-II) with a CRS arm on a pseudo-terminal\n"
          "  and prints the device path (or tcp:127.0.0.1:PORT) as the first line.\n"
          "  --link PATH         also make PATH a symlink to the pseudo-terminal\n"
          "  --tcp PORT          listen on 127.0.0.1:PORT instead (0 = any free port)\n"
          "  --baud N            a strict 8N1 line at N baud: each direction at most N/10\n"
          "                      characters per second, none before its start + 10 bit\n"
          "                      times; finite receive buffer, XON/XOFF, overrun drops\n"
          "  --cmd-time MS       the controller's own time to read a command line before it\n"
          "                      acts, in simulated ms (default 0)\n"
          "  --rx-buffer N       receive buffer size with --baud (default 128)\n"
          "  --time-scale N      run simulated time N times faster than real time\n"
          "  --model a255|a465   the arm: 5-axis A255 (default) or 6-axis A465; kept in --state\n"
          "  --state FILE        keep locations, variables, outputs and settings in FILE\n"
          "  --log FILE          append one line per command executed\n"
          "  --cell FILE         the work cell (CELL-* words): a motion into it stops\n"
          "                      there with 190-COLLISION\n"
          "  --inputs FILE       time-stamped control lines, e.g. '2.5 IN 3 1'\n"
          "  --control PATH      FIFO for control lines: IN n 0|1, POWER 0|1, OBJECT w, TEACH,\n"
          "                      GET POSITION|OUTPUTS|INPUTS|ERROR|MOTION|LINE\n"
          "  --faults SPEC       drop=P,corrupt=P,noise=P,stall=MS,seed=S (both directions)\n"
          "  --parity N|E|O      the line's parity (default N): with E or O a corrupted byte\n"
          "                      is a parity error, dropped inbound, marked 0xFF 0x00 outbound\n"
          "  --aci               start in ACI mode (clients switch it to terminal mode);\n"
          "                      Ctrl-Z Ctrl-Z returns to ACI mode\n"
          "  --nak               send NAK (0x15) before every error line\n"
          "  --status-extra      STATUS adds fbrlsim's own lines (power, I/O, gripper ...)\n"
          "  --echo-as-typed     echo lower case as typed (default: echo upper-cased)\n"
          "  --log-format F      plain (default): the line; stamped: 'T STATUS LINE'\n"
          "  --control-out FILE  append control-line answers and refusals to FILE\n"
          "                      (default: stdout)\n"
          "  --version           the version\n"
          "  --help              this text\n",
          f);
}

static int number(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double d = v ? strtod(v, &end) : NAN;
    if (!v || *end || end == v || !(d >= lo && d <= hi)) {
        fprintf(stderr, "fbrlsim: %s needs a number in %g..%g\n", opt, lo, hi);
        return -1;
    }
    *out = d;
    return 0;
}

int main(int argc, char **argv)
{
    fbrl_sim_options o;
    char err[512];
    struct sigaction sa;
    double d;
    int i;

    fbrl_sim_options_init(&o);
    o.control_out_stdout = 1;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int used = 1;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--version")) {
            printf("fbrlsim (libfbrl) %s\n", FBRL_VERSION);
            return 0;
        } else if (!strcmp(a, "--aci")) {
            o.aci = 1;
            used = 0;
        } else if (!strcmp(a, "--nak")) {
            o.nak = 1;
            used = 0;
        } else if (!strcmp(a, "--status-extra")) {
            o.status_extra = 1;
            used = 0;
        } else if (!strcmp(a, "--echo-as-typed")) {
            o.echo_as_typed = 1;
            used = 0;
        } else if (!strcmp(a, "--log-format") && v && (!strcmp(v, "plain") || !strcmp(v, "stamped"))) {
            o.log_stamped = !strcmp(v, "stamped");
        } else if (!strcmp(a, "--control-out") && v) {
            o.control_out = v;
        } else if (!strcmp(a, "--link") && v) {
            o.link_path = v;
        } else if (!strcmp(a, "--tcp")) {
            if (number(a, v, 0, 65535, &d))
                return 2;
            o.tcp_port = (int)d;
        } else if (!strcmp(a, "--baud")) {
            if (number(a, v, 1, 10000000, &d))
                return 2;
            o.baud = (long)d;
        } else if (!strcmp(a, "--rx-buffer")) {
            if (number(a, v, 4, 1 << 20, &d))
                return 2;
            o.rx_buffer = (int)d;
        } else if (!strcmp(a, "--time-scale")) {
            if (number(a, v, 1e-3, 1e6, &d))
                return 2;
            o.time_scale = d;
        } else if (!strcmp(a, "--model") && v) {
            o.model = v;
        } else if (!strcmp(a, "--cmd-time")) {
            if (number(a, v, 0, 10000, &d))
                return 2;
            o.cmd_time_ms = d;
        } else if (!strcmp(a, "--state") && v) {
            o.state_path = v;
        } else if (!strcmp(a, "--log") && v) {
            o.log_path = v;
        } else if (!strcmp(a, "--cell") && v) {
            o.cell_path = v;
        } else if (!strcmp(a, "--inputs") && v) {
            o.inputs_path = v;
        } else if (!strcmp(a, "--control") && v) {
            o.control_path = v;
        } else if (!strcmp(a, "--faults") && v) {
            o.faults = v;
        } else if (!strcmp(a, "--parity") && v && strlen(v) == 1 && strchr("NEO", v[0])) {
            o.parity = v[0];
        } else {
            fprintf(stderr, "fbrlsim: unknown option or missing value: %s\n", a);
            usage(stderr);
            return 2;
        }
        i += used;
    }
    if (fbrl_sim_create(&g_sim, &o, err, sizeof err) != FBRL_OK) {
        fprintf(stderr, "fbrlsim: %s\n", err);
        return 1;
    }
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    printf("%s\n", fbrl_sim_path(g_sim));
    fflush(stdout);
    i = fbrl_sim_run(g_sim) == FBRL_OK ? 0 : 1;
    fbrl_sim_destroy(g_sim);
    return i;
}
