/* SPDX-License-Identifier: MIT */
/* audit_replay.c - fbrl-audit replay: the controller commands a run recorded, sent again
 * to a fresh fbrlsim through the library's link, and fbrlsim's own command log compared
 * with the recorded commands byte for byte (and each command's result with the recorded
 * one). The emulator is a separate process, as a controller is. */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fbrl/link.h"
#include "fbrl/port.h"
#include "fbrl/rapl_encode.h"
#include "fbrl_audit.h"

#define LINE_MAX_CMD 256
#define SIM_WAIT_MS 5000
#define TIME_SCALE "200"
/* fbrlsim on this host over a pty has no line noise: a late echo is a busy host (the suite
 * under ASan on two cores held one past the link's 100 ms and the replay reported a
 * recorded "ran" as "may-have-run"), not a lost byte */
#define REPLAY_ECHO_TIMEOUT_MS 2000

typedef struct cmd {
    char line[LINE_MAX_CMD];
    char status[16]; /* ran, refused, may-have-run, reply-damaged */
    long code;
    unsigned count;  /* a folded poll: the same line this many times */
} cmd;

/* fbrlsim next to this program's build (sim/ beside apps/), else on PATH. */
static void find_fbrlsim(char *out, size_t cap)
{
    char self[1024];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            if ((size_t)snprintf(out, cap, "%s/../sim/fbrlsim", self) < cap && access(out, X_OK) == 0)
                return;
            if ((size_t)snprintf(out, cap, "%s/fbrlsim", self) < cap && access(out, X_OK) == 0)
                return;
        }
    }
    snprintf(out, cap, "fbrlsim");
}

/* The commands of run number `which` (1..; 0 = the last), into *out (malloc'd). */
static long run_commands(const audit_text *t, long which, cmd **out, size_t *n, char *method, size_t mcap)
{
    long runs = 0, chosen;
    char type[32], buf[LINE_MAX_CMD];
    size_t cap = 256;
    for (size_t i = 0; i < t->nlines; i++) {
        const char *l = t->buf + t->start[i];
        size_t ln = t->start[i + 1] - t->start[i];
        ln -= ln && l[ln - 1] == '\n';
        runs += fbrl_audit_field_str(l, ln, "type", type, sizeof type) == FBRL_OK && strcmp(type, "header") == 0;
    }
    chosen = which > 0 ? which : runs;
    if (chosen < 1 || chosen > runs)
        return -1;
    *out = malloc(cap * sizeof **out);
    *n = 0;
    for (size_t i = 0, r = 0; *out && i < t->nlines; i++) {
        const char *l = t->buf + t->start[i];
        size_t ln = t->start[i + 1] - t->start[i];
        long long v;
        ln -= ln && l[ln - 1] == '\n';
        if (fbrl_audit_field_str(l, ln, "type", type, sizeof type) != FBRL_OK)
            continue;
        if (strcmp(type, "header") == 0 && ++r == (size_t)chosen)
            fbrl_audit_field_str(l, ln, "method", method, mcap);
        if (r != (size_t)chosen)
            continue;
        if (strcmp(type, "seal") == 0)
            break;
        if (strcmp(type, "command") != 0 && strcmp(type, "poll") != 0)
            continue;
        if (*n == cap) {
            cmd *b = realloc(*out, 2 * cap * sizeof **out);
            if (b == NULL) {
                free(*out);
                *out = NULL;
                break;
            }
            *out = b;
            cap *= 2;
        }
        cmd *c = &(*out)[*n];
        memset(c, 0, sizeof *c);
        if (fbrl_audit_field_str(l, ln, "line", buf, sizeof buf) != FBRL_OK)
            continue;
        memcpy(c->line, buf, sizeof c->line);
        fbrl_audit_field_str(l, ln, "status", c->status, sizeof c->status);
        c->code = fbrl_audit_field_num(l, ln, "code", &v) == FBRL_OK ? (long)v : -1;
        c->count = fbrl_audit_field_num(l, ln, "count", &v) == FBRL_OK && v > 0 ? (unsigned)v : 1;
        (*n)++;
    }
    return *out ? chosen : -1;
}

static pid_t start_sim(const char *sim, const char *dir)
{
    char link[1100], log[1100], state[1100], out[1100];
    pid_t pid;
    snprintf(link, sizeof link, "%s/robot", dir);
    snprintf(log, sizeof log, "%s/sim.log", dir);
    snprintf(state, sizeof state, "%s/state", dir);
    snprintf(out, sizeof out, "%s/sim.out", dir);
    pid = fork();
    if (pid == 0) {
        FILE *o = freopen(out, "w", stdout);
        (void)o;
        execlp(sim, sim, "--link", link, "--log", log, "--state", state, "--time-scale", TIME_SCALE, (char *)NULL);
        fprintf(stderr, "fbrl-audit: cannot run %s: %s\n", sim, strerror(errno));
        _exit(127);
    }
    /* fbrlsim makes the link when its pty is ready */
    for (int i = 0; pid > 0 && i < SIM_WAIT_MS / 10; i++) {
        struct timespec ts = {0, 10 * 1000 * 1000};
        if (access(link, F_OK) == 0)
            return pid;
        if (waitpid(pid, NULL, WNOHANG) == pid)
            return -1;
        nanosleep(&ts, NULL);
    }
    if (pid > 0)
        kill(pid, SIGTERM), waitpid(pid, NULL, 0);
    return -1;
}

static size_t file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (size_t)sb.st_size : 0;
}

/* One recorded line, run as the link ran it: a stream (W5 ...) for one line, else raw. */
static fbrl_status send_line(fbrl_link *l, const char *line)
{
    fbrl_rapl_cmd c;
    if (fbrl_rapl_cmd_find(line, &c) == FBRL_OK && fbrl_rapl_cmd_info(c)->reply == FBRL_LINK_REPLY_STREAM &&
        strcmp(fbrl_rapl_cmd_info(c)->keyword, line) == 0)
        return fbrl_link_stream(l, c, 1);
    return fbrl_link_raw(l, line);
}

static const char *result_word(fbrl_status st)
{
    return st == FBRL_OK ? "ran" : st == FBRL_ECONTROLLER ? "refused" : st == FBRL_EMAYBE ? "may-have-run" : "not-run";
}

int audit_replay(const char *path, long which, const char *fbrlsim, int home, int keep)
{
    audit_text t, logt;
    cmd *cmds = NULL;
    size_t n = 0, offset, sent = 0, want_len = 0, differ = 0;
    char sim[1024], dir[] = "/tmp/fbrl-replay-XXXXXX", logp[1100], robot[1100], method[128] = "";
    static fbrl_port port;
    static fbrl_link link;
    fbrl_port_options po;
    fbrl_link_config lc;
    fbrl_status st;
    pid_t pid;
    long run;
    int rc = AUDIT_EXIT_OK;
    char *want;

    {
        /* only a trustworthy record is replayed */
        static fbrl_audit_verifier v;
        static fbrl_audit_key kb[64];
        audit_keys none = {kb, 0, 64, NULL};
        unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE] = NULL;
        st = audit_verify(path, &none, &v, &hashes);
        free(hashes);
        if (st != FBRL_OK) {
            printf("%s: %s: not replayed\n", path, st == FBRL_ECHECKSUM ? v.where : fbrl_status_str(st));
            return AUDIT_EXIT_BROKEN;
        }
    }
    if (audit_text_read(path, &t) != 0) {
        fprintf(stderr, "fbrl-audit: %s: cannot be read\n", path);
        return AUDIT_EXIT_BROKEN;
    }
    run = run_commands(&t, which, &cmds, &n, method, sizeof method);
    audit_text_free(&t);
    if (run < 0) {
        fprintf(stderr, "fbrl-audit: %s: no run %ld\n", path, which);
        return AUDIT_EXIT_USAGE;
    }
    if (fbrlsim == NULL)
        find_fbrlsim(sim, sizeof sim);
    else
        snprintf(sim, sizeof sim, "%s", fbrlsim);
    if (mkdtemp(dir) == NULL || (pid = start_sim(sim, dir)) < 0) {
        fprintf(stderr, "fbrl-audit: cannot start fbrlsim (%s)\n", sim);
        free(cmds);
        return AUDIT_EXIT_USAGE;
    }
    snprintf(robot, sizeof robot, "%s/robot", dir);
    snprintf(logp, sizeof logp, "%s/sim.log", dir);
    fbrl_port_options_init(&po);
    fbrl_link_config_init(&lc);
    lc.query_reads = 1; /* each recorded query line is one the controller ran */
    lc.echo_timeout_ms = REPLAY_ECHO_TIMEOUT_MS;
    st = fbrl_port_open(&port, robot, &po);
    if (st == FBRL_OK)
        st = fbrl_link_init(&link, fbrl_port_uart(&port), &lc);
    if (st == FBRL_OK)
        st = fbrl_link_connect(&link);
    if (st == FBRL_OK && home) /* the arm of a run stood homed: set up before the run's commands */
        st = fbrl_link_raw(&link, "HOME");
    if (st != FBRL_OK) {
        fprintf(stderr, "fbrl-audit: fbrlsim on %s does not answer: %s\n", robot, fbrl_status_str(st));
        rc = AUDIT_EXIT_USAGE;
        goto out;
    }
    offset = file_size(logp);
    for (size_t i = 0; i < n; i++) {
        for (unsigned k = 0; k < cmds[i].count; k++) {
            st = send_line(&link, cmds[i].line);
            sent++;
            if (strcmp(result_word(st), cmds[i].status) != 0 && !(st == FBRL_OK && !strcmp(cmds[i].status, "reply-damaged"))) {
                int code = -1;
                const char *text = "";
                fbrl_link_error(&link, &code, &text);
                if (differ++ < 10)
                    printf("command %zu '%s': recorded %s, the replay %s%s%s\n", i + 1, cmds[i].line, cmds[i].status,
                           result_word(st), st == FBRL_ECONTROLLER ? ": " : "", st == FBRL_ECONTROLLER ? text : "");
            }
            if (st != FBRL_OK && st != FBRL_ECONTROLLER && st != FBRL_EMAYBE) {
                printf("replay stopped at command %zu '%s': %s\n", i + 1, cmds[i].line, fbrl_status_str(st));
                rc = AUDIT_EXIT_BROKEN;
                goto out;
            }
        }
        want_len += (strlen(cmds[i].line) + 1) * cmds[i].count;
    }
out:
    fbrl_port_close(&port);
    kill(pid, SIGTERM);
    waitpid(pid, NULL, 0);
    if (rc == AUDIT_EXIT_OK) {
        /* the recorded commands, one a line, against what fbrlsim logged after the set-up */
        want = malloc(want_len + 1);
        size_t o = 0;
        for (size_t i = 0; want && i < n; i++)
            for (unsigned k = 0; k < cmds[i].count; k++)
                o += (size_t)sprintf(want + o, "%s\n", cmds[i].line);
        if (want == NULL || audit_text_read(logp, &logt) != 0) {
            fprintf(stderr, "fbrl-audit: %s: cannot be read\n", logp);
            rc = AUDIT_EXIT_USAGE;
        } else {
            const char *got = logt.buf + (offset <= logt.len ? offset : logt.len);
            size_t glen = logt.len - (size_t)(got - logt.buf), at = 0, line = 1;
            while (at < glen && at < o && got[at] == want[at])
                line += got[at++] == '\n';
            if (at == glen && at == o && differ == 0) {
                printf("%s: run %ld (%s, %zu commands): fbrlsim's log is the recorded one, byte for byte (%zu bytes)\n",
                       path, run, method, sent, o);
            } else {
                if (at != glen || at != o)
                    printf("%s: run %ld (%s): fbrlsim's log differs from the recorded commands at command %zu "
                           "(byte %zu): recorded '%.*s', logged '%.*s'\n",
                           path, run, method, line, at, (int)strcspn(want + at, "\n"),
                           want + at, (int)strcspn(got + at, "\n"), got + at);
                else
                    printf("%s: run %ld (%s): the log is the same, %zu result%s differ\n", path, run, method, differ,
                           differ == 1 ? "" : "s");
                rc = AUDIT_EXIT_BROKEN;
            }
            audit_text_free(&logt);
        }
        free(want);
    }
    if (keep) {
        printf("fbrlsim's files kept in %s\n", dir);
    } else {
        char p[1200];
        const char *files[] = {"sim.log", "sim.out", "state", "robot"};
        for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
            snprintf(p, sizeof p, "%s/%s", dir, files[i]);
            unlink(p);
        }
        rmdir(dir);
    }
    free(cmds);
    return rc;
}
