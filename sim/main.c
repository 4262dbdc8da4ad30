/* SPDX-License-Identifier: MIT */
/* main.c - fbrlsim: a RAPL-II robot controller emulator on a pseudo-terminal.
 * Usage: see usage() and docs/fbrlsim.md. */
#include "fbrlsim.h"

#include "fbrl/version.h"

#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
          "  --time-scale N      run simulated time N times faster than real time\n",
          f);
    {
        char names[64];
        fbrl_arm_names(names, sizeof names, '|');
        fprintf(f,
                "  --model %-11s the arm (default %s; fbrlmon --arm, docs/robot.md); kept\n"
                "                      in --state\n",
                names, fbrl_arm_model(0)->name);
    }
    fputs("  --state FILE        keep locations, variables, outputs and settings in FILE\n"
          "  --log FILE          append one line per command executed\n"
          "  --cell FILE         the work cell (CELL-* words): a motion into it stops\n"
          "                      there with 190-COLLISION\n"
          "  --inputs FILE       time-stamped control lines, e.g. '2.5 IN 3 1'\n"
          "  --control PATH      FIFO for control lines: IN n 0|1, POWER 0|1, OBJECT w,\n"
          "                      TEACH, GET POSITION|OUTPUTS|INPUTS|ERROR|MOTION|LINE\n"
          "  --faults SPEC       drop=P,corrupt=P,noise=P,stall=MS,seed=S (both directions)\n"
          "  --parity N|E|O      the line's parity (default N): with E or O a corrupted\n"
          "                      byte is a parity error, dropped inbound, marked 0xFF 0x00\n"
          "                      outbound\n"
          "  --aci               start in ACI mode (clients switch it to terminal mode);\n"
          "                      Ctrl-Z Ctrl-Z returns to ACI mode\n"
          "  --nak               send NAK (0x15) before every error line\n"
          "  --status-extra      STATUS adds fbrlsim's own lines (power, I/O, gripper ...)\n"
          "  --echo-as-typed     echo lower case as typed (default: echo upper-cased)\n"
          "  --greet-pty         send the prompt when a program opens the pty (a\n"
          "                      controller on a serial line cannot; TCP always greets)\n"
          "  --log-format F      plain (default): the line; stamped: 'T STATUS LINE'\n"
          "  --control-out FILE  append control-line answers and refusals to FILE\n"
          "                      (default: stdout)\n"
          "  -h, --help          this text\n"
          "  -V, --version       the version\n"
          "  (a value may follow '=': --baud=9600)\n",
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

/* Long options without a short form; values past CHAR_MAX never meet a letter. */
enum {
    OPT_LINK = 1000,
    OPT_TCP,
    OPT_BAUD,
    OPT_RX_BUFFER,
    OPT_TIME_SCALE,
    OPT_MODEL,
    OPT_CMD_TIME,
    OPT_STATE,
    OPT_LOG,
    OPT_INPUTS,
    OPT_CONTROL,
    OPT_FAULTS,
    OPT_PARITY,
    OPT_CELL,
    OPT_ACI,
    OPT_NAK,
    OPT_STATUS_EXTRA,
    OPT_ECHO_AS_TYPED,
    OPT_GREET_PTY,
    OPT_LOG_FORMAT,
    OPT_CONTROL_OUT
};

/* ":" first: a missing value comes back as ':' so the message is ours. */
static const char short_options[] = ":hV";

static const struct option long_options[] = {{"link", required_argument, NULL, OPT_LINK},
                                             {"tcp", required_argument, NULL, OPT_TCP},
                                             {"baud", required_argument, NULL, OPT_BAUD},
                                             {"rx-buffer", required_argument, NULL, OPT_RX_BUFFER},
                                             {"time-scale", required_argument, NULL, OPT_TIME_SCALE},
                                             {"model", required_argument, NULL, OPT_MODEL},
                                             {"cmd-time", required_argument, NULL, OPT_CMD_TIME},
                                             {"state", required_argument, NULL, OPT_STATE},
                                             {"log", required_argument, NULL, OPT_LOG},
                                             {"inputs", required_argument, NULL, OPT_INPUTS},
                                             {"control", required_argument, NULL, OPT_CONTROL},
                                             {"faults", required_argument, NULL, OPT_FAULTS},
                                             {"parity", required_argument, NULL, OPT_PARITY},
                                             {"cell", required_argument, NULL, OPT_CELL},
                                             {"aci", no_argument, NULL, OPT_ACI},
                                             {"nak", no_argument, NULL, OPT_NAK},
                                             {"status-extra", no_argument, NULL, OPT_STATUS_EXTRA},
                                             {"echo-as-typed", no_argument, NULL, OPT_ECHO_AS_TYPED},
                                             {"greet-pty", no_argument, NULL, OPT_GREET_PTY},
                                             {"log-format", required_argument, NULL, OPT_LOG_FORMAT},
                                             {"control-out", required_argument, NULL, OPT_CONTROL_OUT},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, 'V'},
                                             {NULL, 0, NULL, 0}};

/* The option's name for messages ("--baud", "-h"). */
static const char *option_name(int c, char *buf, size_t n)
{
    size_t i;
    for (i = 0; long_options[i].name != NULL; i++)
        if (long_options[i].val == c) {
            snprintf(buf, n, "--%s", long_options[i].name);
            return buf;
        }
    snprintf(buf, n, "-%c", c);
    return buf;
}

/* Returns -1 on a bad command line (message printed), 1 to exit 0 (--help,
 * --version), 0 to run. */
static int parse_args(int argc, char **argv, fbrl_sim_options *o)
{
    char name[32];
    double d;
    int c;
    opterr = 0;
    while ((c = getopt_long(argc, argv, short_options, long_options, NULL)) != -1) {
        const char *v = optarg;
        switch (c) {
        case 'h': usage(stdout); return 1;
        case 'V': printf("fbrlsim (libfbrl) %s\n", fbrl_version()); return 1;
        case OPT_LINK: o->link_path = v; break;
        case OPT_TCP:
            if (number("--tcp", v, 0, 65535, &d))
                return -1;
            o->tcp_port = (int)d;
            break;
        case OPT_BAUD:
            if (number("--baud", v, 1, 10000000, &d))
                return -1;
            o->baud = (long)d;
            break;
        case OPT_RX_BUFFER:
            if (number("--rx-buffer", v, 4, 1 << 20, &d))
                return -1;
            o->rx_buffer = (int)d;
            break;
        case OPT_TIME_SCALE:
            if (number("--time-scale", v, 1e-3, 1e6, &d))
                return -1;
            o->time_scale = d;
            break;
        case OPT_MODEL: o->model = v; break;
        case OPT_CMD_TIME:
            if (number("--cmd-time", v, 0, 10000, &d))
                return -1;
            o->cmd_time_ms = d;
            break;
        case OPT_STATE: o->state_path = v; break;
        case OPT_LOG: o->log_path = v; break;
        case OPT_INPUTS: o->inputs_path = v; break;
        case OPT_CONTROL: o->control_path = v; break;
        case OPT_FAULTS: o->faults = v; break;
        case OPT_CELL: o->cell_path = v; break;
        case OPT_ACI: o->aci = 1; break;
        case OPT_NAK: o->nak = 1; break;
        case OPT_STATUS_EXTRA: o->status_extra = 1; break;
        case OPT_ECHO_AS_TYPED: o->echo_as_typed = 1; break;
        case OPT_GREET_PTY: o->greet_pty = 1; break;
        case OPT_CONTROL_OUT: o->control_out = v; break;
        case OPT_LOG_FORMAT:
            if (strcmp(v, "plain") != 0 && strcmp(v, "stamped") != 0) {
                fprintf(stderr, "fbrlsim: --log-format: plain or stamped, not '%s'\n", v);
                return -1;
            }
            o->log_stamped = strcmp(v, "stamped") == 0;
            break;
        case OPT_PARITY:
            if (strlen(v) != 1 || !strchr("NEO", v[0])) {
                fprintf(stderr, "fbrlsim: --parity needs N, E or O, not '%s'\n", v);
                usage(stderr);
                return -1;
            }
            o->parity = v[0];
            break;
        case ':':
            fprintf(stderr, "fbrlsim: unknown option or missing value: %s\n",
                    optopt != 0 ? option_name(optopt, name, sizeof name) : argv[optind - 1]);
            usage(stderr);
            return -1;
        default: /* '?': unknown, ambiguous, or a value on an option that takes none */
            if (optopt != 0 && optopt < OPT_LINK)
                fprintf(stderr, "fbrlsim: unknown option or missing value: -%c\n", optopt);
            else
                fprintf(stderr, "fbrlsim: unknown option or missing value: %s\n", argv[optind - 1]);
            usage(stderr);
            return -1;
        }
    }
    if (optind < argc) { /* fbrlsim takes no operands */
        fprintf(stderr, "fbrlsim: unknown option or missing value: %s\n", argv[optind]);
        usage(stderr);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    fbrl_sim_options o;
    char err[512];
    struct sigaction sa;
    int i;

    fbrl_sim_options_init(&o);
    o.control_out_stdout = 1;
    i = parse_args(argc, argv, &o);
    if (i != 0)
        return i < 0 ? 2 : 0;
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
