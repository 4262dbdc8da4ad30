/* fbrlmon - the FBRL monitor: the language at a terminal, or running files.
 *
 *   fbrlmon [options] [FILE...]
 *
 * Evaluates -e texts and FILEs in command-line order; then, when standard input
 * is a terminal, an interactive session (line editing, history, completion);
 * otherwise standard input line by line. See docs/fbrlmon.md. */
#include <errno.h>
#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mon.h"
#include "mon_conn.h"
#include "mon_relink.h"
#include "mon_safe.h"
#include "mon_ws.h"

#ifndef FBRL_VERSION
#define FBRL_VERSION "unknown"
#endif

#define DICT_BYTES_DEFAULT (8u * 1024u * 1024u)

/* A FILE or -e TEXT, kept in command-line order. */
typedef struct action {
    int is_text;
    const char *arg;
} action;

typedef struct options {
    action *actions;
    size_t n_actions;
    size_t dict_bytes;
    int list_ports;
    int conn_default;      /* no --port, --sim or --offline given */
    const char *workspace; /* --workspace FILE */
    const char *printer;   /* --printer: PRINT-LOC's destination instead of the controller's line */
    mon_conn_options conn;
} options;

static void usage(FILE *f)
{
    fputs("usage: fbrlmon [options] [FILE...]\n"
          "Evaluate FBRL (Forth) source FILEs in order, then read commands from a\n"
          "terminal (interactive session) or from piped standard input.\n"
          "\n"
          "options:\n"
          "  -e TEXT          evaluate TEXT (in order with the FILEs)\n"
          "  --port PATH      controller on a serial device, pty or tcp:HOST:PORT\n"
          "  --baud N         line speed (default 9600)\n"
          "  --data-bits N    5, 6, 7 or 8 (default 8)\n"
          "  --parity P       none, even or odd (default none)\n"
          "  --stop-bits N    1 or 2 (default 1)\n"
          "  --flow F         none or xonxoff (default xonxoff)\n"
          "  --low-latency on|off  USB-serial low-latency mode (default on)\n"
          "  --axes N         the arm's axes (default 5; the emulator's own with --sim)\n"
#ifdef FBRLMON_HAVE_SIM
          "  --sim            built-in emulated controller (the default without --port)\n"
          "  --sim-state FILE the emulator's persistent memory (default: none kept)\n"
          "  --sim-model M    the emulated arm: a255 (default) or a465 (6 axes)\n"
          "  --sim-inputs FILE the emulator's inputs over time, lines \"T IN n v\"\n"
          "                   (fbrlsim --inputs; default: all inputs off)\n"
#endif
          "  --offline        no controller: robot words report an error\n"
          "  --printer PATH   PRINT-LOC appends to PATH (a file, a printer, a second\n"
          "                   serial line) instead of the controller's line\n"
          "  --workspace FILE load the workspace FILE (if it exists) first; at exit offer\n"
          "                   to save changes to it (docs/workspace.md)\n"
          "  --list-ports     list the serial ports and exit\n"
          "  --dict BYTES     dictionary size (default 8M; suffix K or M)\n"
          "  -h, --help       show this help and exit\n"
          "  -V, --version    show the version and exit\n"
          "\n"
          "exit status: 0 no error, 1 an error aborted a file, -e text or piped line,\n"
          "             2 bad command line, 3 could not start\n",
          f);
}

static int parse_size(const char *s, size_t *out)
{
    char *end;
    unsigned long long v;
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno != 0 || end == s)
        return -1;
    if (*end == 'K' || *end == 'k')
        v *= 1024u, end++;
    else if (*end == 'M' || *end == 'm')
        v *= 1024u * 1024u, end++;
    if (*end != '\0' || v == 0 || v > (1ull << 32))
        return -1;
    *out = (size_t)v;
    return 0;
}

/* Options that take a value (other than -e and --dict). */
static int is_valued(const char *a)
{
    static const char *const names[] = {
        "--port",      "--baud",       "--data-bits", "--parity",    "--stop-bits", "--flow", "--low-latency",
        "--sim-state", "--sim-inputs", "--printer",   "--workspace", "--sim-model", "--axes", NULL};
    int i;
    for (i = 0; names[i] != NULL; i++)
        if (strcmp(a, names[i]) == 0)
            return 1;
    return 0;
}

static int set_valued(options *o, const char *a, const char *v)
{
    if (strcmp(a, "--port") == 0) {
        o->conn.kind = MON_CONN_PORT;
        o->conn.port = v;
    } else if (strcmp(a, "--workspace") == 0) {
        o->workspace = v;
    } else if (strcmp(a, "--sim-state") == 0) {
        o->conn.sim_state = v;
    } else if (strcmp(a, "--sim-model") == 0) {
        o->conn.sim_model = v;
    } else if (strcmp(a, "--axes") == 0) {
        char *end;
        unsigned long n = strtoul(v, &end, 10);
        if (end == v || *end != '\0' || v[0] == '-' || n < 1 || n > FBRL_RAPL_MAX_AXES)
            return -1;
        o->conn.axes = (unsigned)n;
    } else if (strcmp(a, "--printer") == 0) {
        o->printer = v;
    } else if (strcmp(a, "--sim-inputs") == 0) {
        o->conn.sim_inputs = v;
    } else if (fbrl_port_set_option(&o->conn.line, a + 2, v) != FBRL_OK) {
        /* --baud, --data-bits, --parity, --stop-bits, --flow, --low-latency: the library's option text */
        return -1;
    }
    return 0;
}

/* Returns -1 to exit with `*status`, 0 to go on. */
static int parse_args(int argc, char **argv, options *o, int *status)
{
    int i, only_files = 0, explicit_conn = 0;
    fbrl_port_options_init(&o->conn.line);
    o->actions = calloc((size_t)argc, sizeof *o->actions);
    o->dict_bytes = DICT_BYTES_DEFAULT;
    if (o->actions == NULL) {
        *status = MON_EXIT_CONNECT;
        return -1;
    }
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (only_files || a[0] != '-' || strcmp(a, "-") == 0) {
            o->actions[o->n_actions].is_text = 0;
            o->actions[o->n_actions++].arg = a;
        } else if (strcmp(a, "--") == 0) {
            only_files = 1;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            *status = MON_EXIT_OK;
            return -1;
        } else if (strcmp(a, "-V") == 0 || strcmp(a, "--version") == 0) {
            printf("fbrlmon (libfbrl) %s\n", FBRL_VERSION);
            *status = MON_EXIT_OK;
            return -1;
        } else if (strcmp(a, "--offline") == 0) {
            o->conn.kind = MON_CONN_OFFLINE;
            explicit_conn = 1;
#ifdef FBRLMON_HAVE_SIM
        } else if (strcmp(a, "--sim") == 0) {
            o->conn.kind = MON_CONN_SIM;
            explicit_conn = 1;
#endif
        } else if (strcmp(a, "--list-ports") == 0) {
            o->list_ports = 1;
        } else if (is_valued(a)) {
            const char *v = i + 1 < argc ? argv[++i] : NULL;
            if (v == NULL) {
                fprintf(stderr, "fbrlmon: %s needs an argument\n", a);
                goto bad;
            }
            if (set_valued(o, a, v) != 0) {
                fprintf(stderr, "fbrlmon: %s: bad value '%s'\n", a, v);
                goto bad;
            }
            if (strcmp(a, "--port") == 0)
                explicit_conn = 1;
        } else if (strcmp(a, "-e") == 0 || strcmp(a, "--dict") == 0) {
            if (i + 1 >= argc) {
                fprintf(stderr, "fbrlmon: %s needs an argument\n", a);
                goto bad;
            }
            if (a[1] == 'e') {
                o->actions[o->n_actions].is_text = 1;
                o->actions[o->n_actions++].arg = argv[++i];
            } else if (parse_size(argv[++i], &o->dict_bytes) != 0) {
                fprintf(stderr, "fbrlmon: --dict: bad size '%s'\n", argv[i]);
                goto bad;
            }
        } else {
            fprintf(stderr, "fbrlmon: unknown option '%s'\n", a);
            goto bad;
        }
    }
    /* Inputs for the emulator ask for the emulator: one that cannot start is an error. */
    if (!explicit_conn && o->conn.sim_inputs != NULL)
        explicit_conn = 1, o->conn.kind = MON_CONN_SIM;
    o->conn_default = !explicit_conn;
    if (!explicit_conn)
#ifdef FBRLMON_HAVE_SIM
        o->conn.kind = MON_CONN_SIM;
#else
        o->conn.kind = MON_CONN_OFFLINE;
#endif
    return 0;
bad:
    fputs("Try 'fbrlmon --help'.\n", stderr);
    *status = MON_EXIT_USAGE;
    return -1;
}

static mon_conn g_conn; /* fixed address while open, as the uart backend needs */

/* --printer: PRINT-LOC's lines appended to a file or device, each put out at once
 * (a printer or a second line shows it as it is printed). */
static void print_to_printer(void *ctx, const char *s, size_t n)
{
    FILE *f = ctx;
    if (fwrite(s, 1, n, f) != n || fflush(f) != 0)
        fprintf(stderr, "fbrlmon: --printer: write failed: %s\n", strerror(errno));
}

int main(int argc, char **argv)
{
    options opt;
    static mon m; /* fixed address for the words; large */
    int status = MON_EXIT_OK, stopped = 0;
    size_t i;
    FILE *printer = NULL;

    /* The user's locale (the terminal's character set for line editing). libfbrl reads
     * and prints numbers the same in every locale, and so does fbrlmon (fbrl_num). */
    setlocale(LC_ALL, "");
    memset(&opt, 0, sizeof opt);
    if (parse_args(argc, argv, &opt, &status) != 0) {
        free(opt.actions);
        return status;
    }
    if (opt.list_ports) {
        fbrl_status st = mon_conn_list_ports(stdout);
        free(opt.actions);
        if (st != FBRL_OK) {
            fprintf(stderr, "fbrlmon: --list-ports: %s\n",
                    st == FBRL_EUNSUPPORTED ? "this fbrlmon was built without libserialport"
                                            : fbrl_status_str(st));
            return MON_EXIT_CONNECT;
        }
        return MON_EXIT_OK;
    }
    {
        char err[512];
        if (mon_conn_open(&g_conn, &opt.conn, err, sizeof err) != FBRL_OK) {
            if (!opt.conn_default) {
                fprintf(stderr, "fbrlmon: %s\n", err);
                free(opt.actions);
                return MON_EXIT_CONNECT;
            }
            /* Nobody asked for the emulator: say why it is missing and go on
             * without a controller rather than refuse to run Forth at all. */
            fprintf(stderr, "fbrlmon: %s; running offline\n", err);
            opt.conn.kind = MON_CONN_OFFLINE;
            mon_conn_open(&g_conn, &opt.conn, err, sizeof err);
        }
    }
    if (mon_open(&m, opt.dict_bytes, g_conn.open ? &g_conn.link : NULL) != 0) {
        mon_conn_close(&g_conn);
        free(opt.actions);
        return MON_EXIT_CONNECT;
    }
    m.conn = g_conn.open ? &g_conn : NULL;
    if (mon_relink_install(&m) != FBRL_OK) {
        fprintf(stderr, "fbrlmon: cannot define RECONNECT and RESUME\n");
        mon_close(&m);
        mon_conn_close(&g_conn);
        free(opt.actions);
        return MON_EXIT_CONNECT;
    }
    mon_safe_install(&m);

    if (opt.printer != NULL) {
        printer = fopen(opt.printer, "a");
        if (printer == NULL) {
            fprintf(stderr, "fbrlmon: --printer %s: %s\n", opt.printer, strerror(errno));
            mon_close(&m);
            mon_conn_close(&g_conn);
            free(opt.actions);
            return MON_EXIT_CONNECT;
        }
        fbrl_glossary_set_port_writer(&m.glossary, print_to_printer, printer);
    }
    if (opt.workspace != NULL && mon_ws_start(&m, opt.workspace) != 0) {
        if (printer != NULL)
            fclose(printer);
        mon_close(&m);
        mon_conn_close(&g_conn);
        free(opt.actions);
        return MON_EXIT_CONNECT;
    }

    /* Ctrl-C in a file or -e text: the safe stop, and the rest of the command line is
     * skipped (docs/fbrlmon.md "Ctrl-C") */
    for (i = 0; i < opt.n_actions && !fbrl_vm_bye(m.vm) && !stopped; i++) {
        const action *a = &opt.actions[i];
        mon_safe_begin(&m);
        if (a->is_text) {
            unsigned long lines = 1;
            const char *p;
            for (p = a->arg; *p; p++)
                lines += *p == '\n';
            if (mon_eval(&m, a->arg, strlen(a->arg), "-e", 1, 1) == 0)
                mon_check_closed(&m, "text", "-e", lines);
        } else {
            mon_include(&m, a->arg);
        }
        stopped = mon_safe_end(&m, a->is_text ? "-e" : a->arg, a->is_text ? 1 : 0);
    }

    /* after a Ctrl-C, only a terminal goes on (at the prompt); piped input ends */
    if (!fbrl_vm_bye(m.vm) && !mon_safe_quit() && (!stopped || m.host.in_is_tty)) {
        if (m.host.in_is_tty) {
            char desc[512];
            mon_conn_describe(&g_conn, desc, sizeof desc);
            printf("fbrlmon %s - %s. HELP name, WORDS; BYE or Ctrl-D ends.\n", FBRL_VERSION, desc);
            /* a person at the prompt: motions say what they started and when a wait ended */
            if (m.host.out_is_tty)
                fbrl_robot_set_console(&m.robot, mon_host_progress, &m.host, 1);
            mon_interactive(&m);
        } else {
            unsigned long ln = 0;
            const char *line;
            size_t len;
            while (!fbrl_vm_bye(m.vm) && !stopped && (line = mon_host_read_line(&m.host, &len)) != NULL) {
                mon_safe_begin(&m);
                mon_eval(&m, line, len, "stdin", ++ln, 1);
                stopped = mon_safe_end(&m, "stdin", ln);
            }
            if (m.host.line_too_long) {
                fprintf(stderr, "stdin:%lu: error: input stopped: line %lu has no end within %ld bytes\n", ln,
                        ln, MON_HOST_LINE_MAX);
                m.errors++;
            }
            if (!fbrl_vm_bye(m.vm) && !stopped)
                mon_check_closed(&m, "input", "stdin", ln);
        }
    }

    mon_ws_finish(&m);
    mon_close(&m);
    if (printer != NULL && fclose(printer) != 0)
        fprintf(stderr, "fbrlmon: --printer: %s\n", strerror(errno));
    status = m.errors ? MON_EXIT_ERROR : MON_EXIT_OK;
    if (mon_safe_quit() || (stopped && !m.host.in_is_tty))
        status = MON_EXIT_INTERRUPT;
    mon_conn_close(&g_conn);
    free(opt.actions);
    return status;
}
