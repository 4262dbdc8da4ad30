/* SPDX-License-Identifier: MIT */
/* fbrlmon - the FBRL monitor: the language at a terminal, or running files.
 *
 *   fbrlmon [options] [FILE...]
 *
 * Evaluates -e texts and FILEs in command-line order; then, when standard input
 * is a terminal, an interactive session (line editing, history, completion) -
 * unless FILEs or -e texts ran with the output not on a terminal (a run, ended);
 * otherwise standard input line by line. See docs/fbrlmon.md. */
#include <errno.h>
#include <limits.h>
#include <getopt.h>
#include <locale.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fbrl/version.h"
#include "mon.h"
#include "mon_conn.h"
#include "mon_dry.h"
#include "mon_relink.h"
#include "lab.h"
#include "mon_runlog.h"
#include "console.h"
#include "mon_safe.h"
#include "mon_tasks.h"
#include "mon_ws.h"

#define DICT_BYTES_DEFAULT (8u * 1024u * 1024u)
#define DEFAULT_COLUMNS    80 /* a terminal that does not say its width */

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
    int dry_run;     /* --dry-run (apps/mon_dry.c) */
    const char *svg; /* --svg FILE */
    mon_dry_options dry;
    console_options console; /* --console, --methods, --level; --run-log, --operator */
    const char *lab;         /* --lab DIR: the lab's users and audit trail (docs/compliance.md) */
} options;

static void usage(FILE *f)
{
    fputs("usage: fbrlmon [options] [FILE...]\n"
          "Evaluate FBRL (Forth) source FILEs in order, then read commands from a\n"
          "terminal (interactive session) or from piped standard input. FILEs or -e\n"
          "with the output redirected (fbrlmon plan.fbrl > log) run and end.\n"
          "\n"
          "options:\n"
          "  -e TEXT          evaluate TEXT (in order with the FILEs; also -eTEXT)\n"
          "  --port PATH      controller on a serial device, pty or tcp:HOST:PORT\n"
          "  --baud N         line speed (default 9600)\n"
          "  --data-bits N    5, 6, 7 or 8 (default 8)\n"
          "  --parity P       none, even or odd (default none)\n"
          "  --stop-bits N    1 or 2 (default 1)\n"
          "  --flow F         none or xonxoff (default xonxoff)\n"
          "  --low-latency on|off  USB-serial low-latency mode (default on)\n"
          "  --axes N         the axes in the controller's readouts (default: the arm's)\n",
          f);
    {
        char names[64];
        fbrl_arm_names(names, sizeof names, '|');
        fprintf(f,
                "  --arm %-10s the arm (default %s): its kinematics, limits, pulses per\n"
                "                   degree and READY for the link's position check, the cell's\n"
                "                   guard and the robot words; the emulator is that arm\n",
                names, fbrl_arm_model(0)->name);
    }
    fputs(
#ifdef FBRLMON_HAVE_SIM
          "  --sim            built-in emulated controller (the default without --port)\n"
          "  --sim-state FILE the emulator's persistent memory (default: none kept)\n"
          "  --sim-model M    the same as --arm (its older name)\n"
          "  --sim-inputs FILE the emulator's inputs over time, lines \"T IN n v\"\n"
          "                   (fbrlsim --inputs; default: all inputs off)\n"
#endif
          "  --offline        no controller: robot words report an error\n"
          "  --printer PATH   PRINT-LOC appends to PATH (a file, a printer, a second\n"
          "                   serial line) instead of the controller's line\n"
          "  --workspace FILE load the workspace FILE (if it exists) first; at exit offer\n"
          "                   to save changes to it (docs/workspace.md)\n"
          "  --dry-run        run the FILEs against the built-in emulator with every wait\n"
          "                   skipped, then report duration, moves, clearance, errors,\n"
          "                   pulses and waits, and draw the cell (docs/workcell.md)\n"
          "  --svg FILE       the dry run's picture (default: the last FILE's name .svg)\n"
          "  --keep-files     the dry run writes the plan's files (default: a scratch dir)\n"
          "  --dry-run-json FILE  the dry run's path, motion by motion, as JSON lines:\n"
          "                   tool points, clearance, what a refused one would hit\n"
          "  --run-log FILE   every RUN-METHOD appends its run log (JSON lines) to FILE\n"
          "  --operator NAME  the operator named in run logs (default: $USER)\n"
          "  --lab DIR        the lab's users and audit trail: runs need a\n"
          "                   signed-in user and a Released method (docs/compliance.md)\n"
          "  --console        the operator console (full screen) after the FILEs\n"
          "  --methods DIR    the console's method library (default: methods)\n"
          "  --level L        the console's level: operator (default), developer or\n"
          "                   programmer\n"
          "  --list-ports     list the serial ports and exit\n"
          "  --dict BYTES     dictionary size (default 8M; suffix K or M)\n"
          "  -h, --help       show this help and exit\n"
          "  (a long option's value may follow '=': --dict=1M; an unambiguous prefix\n"
          "  of a long option's name is enough: --off)\n"
          "  -V, --version    show the version and exit\n"
          "\n"
          "exit status: 0 no error, 1 an error aborted a file, -e text or piped line,\n"
          "             2 bad command line, 3 could not start, 4 a method run did not\n"
          "             complete (its run log says how each sample ended)\n",
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

/* Long options that have no short form; the values follow CHAR_MAX so they never
 * collide with a short option's letter. */
enum {
    OPT_PORT = 1000,
    OPT_BAUD,
    OPT_DATA_BITS,
    OPT_PARITY,
    OPT_STOP_BITS,
    OPT_FLOW,
    OPT_LOW_LATENCY,
    OPT_AXES,
    OPT_ARM,
    OPT_SIM,
    OPT_SIM_STATE,
    OPT_SIM_MODEL,
    OPT_SIM_INPUTS,
    OPT_OFFLINE,
    OPT_PRINTER,
    OPT_WORKSPACE,
    OPT_LIST_PORTS,
    OPT_DICT,
    OPT_DRY_RUN,
    OPT_KEEP_FILES,
    OPT_DRY_RUN_JSON,
    OPT_SVG,
    OPT_CONSOLE,
    OPT_RUN_LOG,
    OPT_OPERATOR,
    OPT_METHODS,
    OPT_LEVEL,
    OPT_LAB
};

/* "-" first: FILEs come back as option 1 in command-line order (they run in order
 * with the -e texts); ":" next: a missing value is reported as ':' (our message). */
static const char short_options[] = "-:e:hV";

static const struct option long_options[] = {{"port", required_argument, NULL, OPT_PORT},
                                             {"baud", required_argument, NULL, OPT_BAUD},
                                             {"data-bits", required_argument, NULL, OPT_DATA_BITS},
                                             {"parity", required_argument, NULL, OPT_PARITY},
                                             {"stop-bits", required_argument, NULL, OPT_STOP_BITS},
                                             {"flow", required_argument, NULL, OPT_FLOW},
                                             {"low-latency", required_argument, NULL, OPT_LOW_LATENCY},
                                             {"axes", required_argument, NULL, OPT_AXES},
                                             {"arm", required_argument, NULL, OPT_ARM},
#ifdef FBRLMON_HAVE_SIM
                                             {"sim", no_argument, NULL, OPT_SIM},
                                             {"dry-run", no_argument, NULL, OPT_DRY_RUN},
                                             {"keep-files", no_argument, NULL, OPT_KEEP_FILES},
                                             {"dry-run-json", required_argument, NULL, OPT_DRY_RUN_JSON},
#endif
                                             {"svg", required_argument, NULL, OPT_SVG},
                                             {"console", no_argument, NULL, OPT_CONSOLE},
                                             {"run-log", required_argument, NULL, OPT_RUN_LOG},
                                             {"operator", required_argument, NULL, OPT_OPERATOR},
                                             {"lab", required_argument, NULL, OPT_LAB},
                                             {"methods", required_argument, NULL, OPT_METHODS},
                                             {"level", required_argument, NULL, OPT_LEVEL},
                                             {"sim-state", required_argument, NULL, OPT_SIM_STATE},
                                             {"sim-model", required_argument, NULL, OPT_SIM_MODEL},
                                             {"sim-inputs", required_argument, NULL, OPT_SIM_INPUTS},
                                             {"offline", no_argument, NULL, OPT_OFFLINE},
                                             {"printer", required_argument, NULL, OPT_PRINTER},
                                             {"workspace", required_argument, NULL, OPT_WORKSPACE},
                                             {"list-ports", no_argument, NULL, OPT_LIST_PORTS},
                                             {"dict", required_argument, NULL, OPT_DICT},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, 'V'},
                                             {NULL, 0, NULL, 0}};

/* The option's name as the user typed it, for messages. */
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

/* A valued option other than -e and --dict; the line settings (--baud, --data-bits,
 * --parity, --stop-bits, --flow, --low-latency) are the library's option text. */
static int set_valued(options *o, int c, const char *v)
{
    switch (c) {
    case OPT_PORT:
        o->conn.kind = MON_CONN_PORT;
        o->conn.port = v;
        return 0;
    case OPT_WORKSPACE: o->workspace = v; return 0;
    case OPT_SIM_STATE: o->conn.sim_state = v; return 0;
    case OPT_ARM:
    case OPT_SIM_MODEL: return (o->conn.arm = fbrl_arm_find(v)) != NULL ? 0 : -1;
    case OPT_SIM_INPUTS: o->conn.sim_inputs = v; return 0;
    case OPT_PRINTER: o->printer = v; return 0;
    case OPT_LAB: o->lab = v; return 0;
    case OPT_SVG: o->svg = v; return 0;
    case OPT_DRY_RUN_JSON: o->dry.json = v; return 0;
    case OPT_RUN_LOG:
    case OPT_OPERATOR:
    case OPT_METHODS:
    case OPT_LEVEL: { /* console.c's options */
        char name[32];
        return console_option(&o->console, option_name(c, name, sizeof name), v);
    }
    case OPT_AXES: {
        char *end;
        unsigned long n = strtoul(v, &end, 10);
        if (end == v || *end != '\0' || v[0] == '-' || n < 1 || n > FBRL_RAPL_MAX_AXES)
            return -1;
        o->conn.axes = (unsigned)n;
        return 0;
    }
    default: {
        char name[32];
        return fbrl_port_set_option(&o->conn.line, option_name(c, name, sizeof name) + 2, v) == FBRL_OK ? 0
                                                                                                        : -1;
    }
    }
}

/* Returns -1 to exit with `*status`, 0 to go on. */
static int parse_args(int argc, char **argv, options *o, int *status)
{
    int c, explicit_conn = 0;
    char name[32];
    fbrl_port_options_init(&o->conn.line);
    o->actions = calloc((size_t)argc, sizeof *o->actions);
    o->dict_bytes = DICT_BYTES_DEFAULT;
    if (o->actions == NULL) {
        *status = MON_EXIT_CONNECT;
        return -1;
    }
    opterr = 0;
    while ((c = getopt_long(argc, argv, short_options, long_options, NULL)) != -1) {
        switch (c) {
        case 1: /* a FILE ("-" is standard input) */
            o->actions[o->n_actions].is_text = 0;
            o->actions[o->n_actions++].arg = optarg;
            break;
        case 'e':
            o->actions[o->n_actions].is_text = 1;
            o->actions[o->n_actions++].arg = optarg;
            break;
        case 'h':
            usage(stdout);
            *status = MON_EXIT_OK;
            return -1;
        case 'V':
            printf("fbrlmon (libfbrl) %s\n", fbrl_version());
            *status = MON_EXIT_OK;
            return -1;
        case OPT_OFFLINE:
            o->conn.kind = MON_CONN_OFFLINE;
            explicit_conn = 1;
            break;
        case OPT_SIM:
            o->conn.kind = MON_CONN_SIM;
            explicit_conn = 1;
            break;
        case OPT_LIST_PORTS: o->list_ports = 1; break;
        case OPT_DRY_RUN: o->dry_run = 1; break;
        case OPT_KEEP_FILES: o->dry.keep_files = 1; break;
        case OPT_CONSOLE: o->console.on = 1; break;
        case OPT_DICT:
            if (parse_size(optarg, &o->dict_bytes) != 0) {
                fprintf(stderr, "fbrlmon: --dict: bad size '%s'\n", optarg);
                goto bad;
            }
            break;
        case ':':
            fprintf(stderr, "fbrlmon: %s needs an argument\n",
                    optopt != 0 ? option_name(optopt, name, sizeof name) : argv[optind - 1]);
            goto bad;
        case '?':
            if (optopt != 0 && optopt < OPT_PORT)
                fprintf(stderr, "fbrlmon: unknown option '-%c'\n", optopt);
            else if (optopt != 0) /* a flag given a value: --offline=x */
                fprintf(stderr, "fbrlmon: %s takes no value\n", option_name(optopt, name, sizeof name));
            else
                fprintf(stderr, "fbrlmon: unknown option '%s'\n", argv[optind - 1]);
            goto bad;
        default:
            if (set_valued(o, c, optarg) != 0) {
                int arm = c == OPT_ARM || c == OPT_SIM_MODEL;
                char names[64];
                fbrl_arm_names(names, sizeof names, '|');
                fprintf(stderr, "fbrlmon: %s: bad value '%s'%s%s%s\n", option_name(c, name, sizeof name), optarg,
                        arm ? " (" : "", arm ? names : "", arm ? ")" : "");
                goto bad;
            }
            if (c == OPT_PORT)
                explicit_conn = 1;
            break;
        }
    }
    if (o->conn.arm != NULL && o->conn.axes != 0 && o->conn.axes != o->conn.arm->naxes) {
        fprintf(stderr, "fbrlmon: --axes %u does not fit the %s (%u axes)\n", o->conn.axes, o->conn.arm->name,
                o->conn.arm->naxes);
        goto bad;
    }
    for (; optind < argc; optind++) { /* after "--": FILEs only */
        o->actions[o->n_actions].is_text = 0;
        o->actions[o->n_actions++].arg = argv[optind];
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

static mon_conn g_conn;     /* fixed address while open, as the uart backend needs */
static mon_runlog g_runlog; /* the link reports every executed line to it */

/* A line typed at the prompt changes what it likes (TEACH, a place, a parameter): with a run
 * log (an audit trail) kept, it is a record, by the operator's name, as the console's Forth
 * line is (docs/compliance.md). */
/* The typed lines' records end with the session's seal, as the console's do. */
static void seal_typed(mon_runlog *L)
{
    mon_audit *A = &L->audit;
    if (A->path[0] == '\0' || A->user[0] == '\0')
        return; /* nothing was recorded */
    mon_audit_set_user(A, "fbrlmon", 0, FBRL_ROLE_OPERATOR); /* the program closes the session */
    if (mon_audit_open(A) == 0)
        mon_audit_close(A, 1);
}

#define TYPED_RECORD_MAX 1000 /* bytes of a typed line kept in its record */

static void record_typed(void *ctx, const char *line, size_t len)
{
    mon_runlog *L = ctx;
    mon_audit *A = &L->audit;
    char text[TYPED_RECORD_MAX + 1], detail[96];
    if (A->path[0] == '\0')
        snprintf(A->path, sizeof A->path, "%s", L->path);
    if (A->path[0] == '\0')
        return; /* no audit trail kept */
    if (!A->user[0] || !A->signed_in)
        mon_audit_set_user(A, L->operator_id[0] ? L->operator_id : "-", 0, FBRL_ROLE_OPERATOR);
    snprintf(text, sizeof text, "%.*s", (int)(len < TYPED_RECORD_MAX ? len : TYPED_RECORD_MAX), line);
    if (len > TYPED_RECORD_MAX)
        snprintf(detail, sizeof detail, "typed at the prompt (its first %d of %zu bytes)", TYPED_RECORD_MAX, len);
    else
        snprintf(detail, sizeof detail, "typed at the prompt");
    if (mon_audit_action(A, "forth", text, detail) != 0)
        fprintf(stderr, "error: %s\n", A->err);
}
static lab g_lab;          /* --lab: its users and chain */

/* --printer: PRINT-LOC's lines appended to a file or device, each put out at once
 * (a printer or a second line shows it as it is printed). */
static void print_to_printer(void *ctx, const char *s, size_t n)
{
    FILE *f = ctx;
    if (fwrite(s, 1, n, f) != n || fflush(f) != 0)
        fprintf(stderr, "fbrlmon: --printer: write failed: %s\n", strerror(errno));
}

/* --dry-run: file names absolute (the plan runs in a scratch directory), the picture's
 * name, the shared clock. */
/* A line for a person at a terminal, broken at spaces so no word is cut by the terminal's
 * own wrap (a port's name longer than the width stands alone on its line). */
static void print_wrapped(const char *text, int width)
{
    const char *p = text;
    while (*p) {
        size_t n = strlen(p), cut = n;
        if (n > (size_t)width) {
            cut = (size_t)width;
            while (cut > 0 && p[cut] != ' ')
                cut--;
            if (cut == 0)
                cut = strcspn(p, " ");
        }
        printf("%.*s\n", (int)cut, p);
        p += cut;
        while (*p == ' ')
            p++;
    }
}

static int dry_prepare(options *o)
{
    static char paths[64][PATH_MAX], svg[PATH_MAX];
    size_t n = 0;
    for (size_t i = 0; i < o->n_actions; i++) {
        if (o->actions[i].is_text)
            continue;
        if (n == 64 || realpath(o->actions[i].arg, paths[n]) == NULL) {
            fprintf(stderr, "fbrlmon: --dry-run: %s: %s\n", o->actions[i].arg,
                    n == 64 ? "too many files" : strerror(errno));
            return -1;
        }
        o->actions[i].arg = paths[n++];
    }
    if (o->svg == NULL && n > 0) {
        const char *base = strrchr(paths[n - 1], '/') ? strrchr(paths[n - 1], '/') + 1 : paths[n - 1];
        size_t len = strlen(base);
        if (len > 5 && strcmp(base + len - 5, ".fbrl") == 0)
            len -= 5;
        snprintf(svg, sizeof svg, "%.*s.svg", (int)len, base);
        o->svg = svg;
    }
    if (o->svg != NULL && o->svg[0] != '/') { /* where the user is, not the scratch directory */
        static char abs_svg[PATH_MAX];
        char cwd[PATH_MAX];
        if (getcwd(cwd, sizeof cwd) == NULL)
            return -1;
        if (strlen(cwd) + 1 + strlen(o->svg) >= sizeof abs_svg) {
            fprintf(stderr, "fbrlmon: --svg %s: the path is too long\n", o->svg);
            return -1;
        }
        memcpy(abs_svg, cwd, strlen(cwd));
        abs_svg[strlen(cwd)] = '/';
        memcpy(abs_svg + strlen(cwd) + 1, o->svg, strlen(o->svg) + 1);
        o->svg = abs_svg;
    }
    o->conn_default = 0;
    return mon_dry_setup(&o->dry, &o->conn);
}

int main(int argc, char **argv)
{
    options opt;
    static mon m; /* fixed address for the words; large */
    int status = MON_EXIT_OK, stopped = 0, run_only;
    size_t i;
    FILE *printer = NULL;

    /* The user's locale: the terminal's character set, for line editing and the console.
     * Only at a terminal: nothing else reads it (libfbrl reads and prints numbers the same in
     * every locale, and so does fbrlmon: fbrl_num), and loading it costs a script about a
     * quarter of fbrlmon's memory beyond the C library (docs/performance.md). */
    if (isatty(STDIN_FILENO) || isatty(STDOUT_FILENO))
        setlocale(LC_ALL, "");
    /* a file size limit (ulimit -f) is an error the write reports (EFBIG: "no space left"),
     * not the end of the run with a temporary file left behind */
    signal(SIGXFSZ, SIG_IGN);
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
                    st == FBRL_EUNSUPPORTED ? "no sysfs, and this fbrlmon was built without libserialport"
                                            : fbrl_status_str(st));
            return MON_EXIT_CONNECT;
        }
        return MON_EXIT_OK;
    }
    opt.conn.on_exec = mon_runlog_exec;
    opt.conn.exec_ctx = &g_runlog;
    if (opt.dry.json && !opt.dry_run) {
        fprintf(stderr, "fbrlmon: --dry-run-json is the dry run's path: it needs --dry-run\n");
        free(opt.actions);
        return MON_EXIT_USAGE;
    }
    if (opt.dry_run && dry_prepare(&opt) != 0) {
        free(opt.actions);
        return MON_EXIT_CONNECT;
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
            memset(&g_conn, 0, sizeof g_conn);
            mon_conn_open(&g_conn, &opt.conn, err, sizeof err);
        }
        if (g_conn.note[0])
            fprintf(stderr, "fbrlmon: %s\n", g_conn.note);
    }
    if (mon_open(&m, opt.dict_bytes, g_conn.open ? &g_conn.link : NULL) != 0) {
        mon_conn_close(&g_conn);
        free(opt.actions);
        return MON_EXIT_CONNECT;
    }
    m.conn = g_conn.open ? &g_conn : NULL;
    m.runlog = &g_runlog.log;
    /* the guard computes the arm the link checks positions of (and the emulator is) */
    fbrl_cell_set_arm(&m.cell->model, g_conn.arm ? g_conn.arm : fbrl_arm_model(0), 0.0);
    if (mon_relink_install(&m) != FBRL_OK) {
        fprintf(stderr, "fbrlmon: cannot define RECONNECT and RESUME\n");
        mon_close(&m);
        mon_conn_close(&g_conn);
        free(opt.actions);
        return MON_EXIT_CONNECT;
    }
    mon_safe_install(&m);
    {
        char desc[256];
        mon_conn_describe(&g_conn, desc, sizeof desc);
        if (mon_runlog_install(&g_runlog, &m, "fbrlmon " FBRL_VERSION_STRING, desc) != 0) {
            fprintf(stderr, "fbrlmon: cannot define RUN-LOG\n");
            mon_close(&m);
            mon_conn_close(&g_conn);
            free(opt.actions);
            return MON_EXIT_CONNECT;
        }
        mon_runlog_set_path(&g_runlog, opt.console.run_log);
        if (opt.console.operator_id != NULL)
            snprintf(g_runlog.operator_id, sizeof g_runlog.operator_id, "%s", opt.console.operator_id);
        if (opt.lab != NULL) {
            /* the lab: its users sign in; its chain is the run log unless --run-log names one */
            if (lab_init(&g_lab, opt.lab, NULL, opt.console.run_log) != 0 || lab_load_users(&g_lab) != 0) {
                fprintf(stderr, "fbrlmon: %s\n", g_lab.err);
                mon_close(&m);
                mon_conn_close(&g_conn);
                free(opt.actions);
                return MON_EXIT_CONNECT;
            }
            g_runlog.audit.lab = &g_lab;
            mon_runlog_set_path(&g_runlog, g_lab.chain_path);
        }
        m.typed_hook = record_typed;
        m.typed_ctx = &g_runlog;
    }

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

    if (opt.dry_run)
        mon_dry_start(&m, &g_runlog);
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

    run_only = m.host.in_is_tty && opt.n_actions > 0 && !m.host.out_is_tty;
    if (opt.dry_run && mon_dry_finish(&m, NULL, stdout, opt.svg) != 0)
        m.errors++;
    /* after a Ctrl-C, only a terminal goes on (at the prompt); piped input ends */
    if (opt.console.on && !fbrl_vm_bye(m.vm) && !mon_safe_quit() && !stopped) {
        if (console_run(&m, &g_runlog, &opt.console) != 0)
            m.errors++;
    } else if (!opt.dry_run && !fbrl_vm_bye(m.vm) && !mon_safe_quit() && (!stopped || m.host.in_is_tty)) {
        if (run_only) {
            /* FILEs or -e texts with the output going elsewhere (fbrlmon plan.fbrl > run.log):
             * a run, not a session; nobody would see a prompt, so the terminal is not read */
        } else if (m.host.in_is_tty) {
            char desc[512], hello[640];
            mon_conn_describe(&g_conn, desc, sizeof desc);
            snprintf(hello, sizeof hello, "fbrlmon %s - %s. HELP name, WORDS; BYE or Ctrl-D ends.", fbrl_version(),
                     desc);
            print_wrapped(hello, (m.host.width > 0 ? m.host.width : DEFAULT_COLUMNS) - 1); /* the last column would wrap */
            /* a person at the prompt: motions say what they started and when a wait ended */
            if (m.host.out_is_tty)
                fbrl_robot_set_console(&m.robot, mon_host_progress, &m.host, 1);
            mon_interactive(&m);
            seal_typed(&g_runlog);
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

    if (!fbrl_vm_bye(m.vm) && !mon_safe_quit())
        mon_tasks_finish(&m); /* what a file started runs to its end */
    if (!opt.dry_run)         /* a dry run changes no file it was not asked to */
        mon_ws_finish(&m);
    mon_close(&m);
    if (printer != NULL && fclose(printer) != 0)
        fprintf(stderr, "fbrlmon: --printer: %s\n", strerror(errno));
    status = m.errors ? MON_EXIT_ERROR : MON_EXIT_OK;
    if (m.runs_incomplete) /* the more telling: a run's outcome is in its run log */
        status = MON_EXIT_RUN;
    if (mon_safe_quit() || (stopped && (!m.host.in_is_tty || run_only)))
        status = MON_EXIT_INTERRUPT;
    mon_conn_close(&g_conn);
    free(opt.actions);
    return status;
}
