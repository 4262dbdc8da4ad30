/* SPDX-License-Identifier: MIT */
/* bench_link_rate: the echo-verified link's throughput on fbrlsim's strict line (issue 11,
 * item 2), for a short and a long command at 9600, 38400 and 115200 baud.
 * Usage: bench_link_rate [FBRLSIM [SECONDS [CMD_TIME_MS [pty|tcp]]]]
 *        (defaults ./sim/fbrlsim, best of 3 runs of 0.7 s per figure (the machine is
 *        shared: the best run is the one least disturbed), the emulator's default --cmd-time 0,
 *        a pseudo-terminal; tcp: the same line model over loopback TCP, without the pty's
 *        kernel worker between the two processes)
 *
 * For an n-character command on an 8N1 line at B baud (one character = 10 bit times):
 *  - line-rate limit (B/10)/(n+1): the host sends n+1 bytes (text and CR);
 *  - echo bound (B/10)/(n+4): the controller sends n+4 bytes back (echo, CR LF, ">>"),
 *    so no client that reads the echo can do better;
 *  - protocol limit (B/10)/(n+5): a client that sends the CR only after the whole echo
 *    has come back whole (the link's invariant: a command whose echo does not match
 *    never runs) leaves the controller's output idle while the CR crosses the line, one
 *    character time per command, whatever it overlaps otherwise (docs/link.md 4).
 * A --cmd-time of c ms: fbrlsim echoes the CR as CR LF, then thinks for c before the
 * rest of the reply, so the output idles c - 2 byte times longer per command (nothing
 * when c is shorter than the CR LF); that is added to all three. Every figure is also given as
 * a share of each bound. Lines starting with "| " are rows of scripts/bench.sh's summary.
 * With --cmd-time 0 two clients without the link run on the same line for comparison
 * (bare uart, no fault handling): the pipelined protocol of docs/link.md 3.10 (the next
 * command's text right behind the CR), which still sends each CR after its echo, and
 * one that sends the CR before the echo (never allowed). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tests/e2e/rapl_harness.h"

#define SHORT_CMD "SPEED 50"
#define LONG_CMD  "POINT P1,14.2500,2.5000,8.1250,0.0000,90.0000,12.3456"

#define RUNS 3

static struct {
    long baud;
    size_t n;
    const char *cmd;
    double cps, line, echo, proto, ceiling, piped, unver;
} summary[8];
static size_t ns;

static double now_s(void) { return (double)fbrl_clock_now_us() / 1e6; }

/* Repeats line for `seconds`; commands per second, or 0 on a failure. */
static double rate(fbrl_link *l, const char *line, double seconds, unsigned long long *retypes)
{
    fbrl_link_stats s0, s1;
    int count = 0;
    fbrl_link_get_stats(l, &s0);
    for (int k = 0; k < 3; k++) /* settle into the steady state */
        if (fbrl_link_raw(l, line) != FBRL_OK)
            return 0;
    double t0 = now_s();
    while (now_s() - t0 < seconds) {
        fbrl_status st = fbrl_link_raw(l, line);
        if (st != FBRL_OK) {
            fprintf(stderr, "%s: %s\n", line, fbrl_status_name(st));
            return 0;
        }
        count++;
    }
    double r = count / (now_s() - t0);
    fbrl_link_get_stats(l, &s1);
    *retypes += (s1.attempts - s0.attempts) - (s1.commands - s0.commands);
    return r;
}

/* Reads exactly `want` (n bytes) from the uart; 0 when it all came, in order. */
static int await_bytes(fbrl_uart *u, const char *want, size_t n)
{
    size_t have = 0;
    while (have < n) {
        char buf[128];
        size_t got = 0, room = n - have < sizeof buf ? n - have : sizeof buf;
        if (fbrl_uart_read(u, buf, room, &got, 1000) != FBRL_OK && got == 0)
            return -1;
        if (memcmp(buf, want + have, got) != 0)
            return -1;
        have += got;
    }
    return 0;
}

/* The timing of the pipelined protocol of docs/link.md 3.10, with the uart alone and no
 * fault handling (the line is clean here): the next command's text goes out right behind
 * the CR, and the CR of a command only once its reply's prompt and the next echo came.
 * What the link could reach by pipelining, as a share of the same bounds. */
static double pipelined_rate(rig *r, const char *line, double seconds)
{
    char out[FBRL_LINK_LINE_MAX + 2], in[FBRL_LINK_LINE_MAX + 8];
    size_t n = strlen(line), wrote;
    if (fbrl_link_clear_line(&r->link) != FBRL_OK)
        return 0;
    for (;;) { /* the echo of clear_line's CAN, if it sent one */
        size_t got = 0;
        if (fbrl_uart_read(&r->uart, in, sizeof in, &got, 100) != FBRL_OK || got == 0)
            break;
    }
    out[0] = '\r';
    memcpy(out + 1, line, n);
    memcpy(in, "\r\n>>", 4);
    memcpy(in + 4, line, n);
    if (fbrl_uart_write(&r->uart, line, n, &wrote, 1000) != FBRL_OK || await_bytes(&r->uart, line, n))
        return 0;
    int count = 0;
    double t0 = now_s();
    while (now_s() - t0 < seconds) {
        if (fbrl_uart_write(&r->uart, out, n + 1, &wrote, 1000) != FBRL_OK ||
            await_bytes(&r->uart, in, n + 4))
            return 0;
        count++;
    }
    double rt = count / (now_s() - t0);
    /* the last text still waits for its CR: erase it, leaving the link a line to verify */
    static const char cr = '\r';
    if (fbrl_uart_write(&r->uart, &cr, 1, &wrote, 1000) != FBRL_OK || await_bytes(&r->uart, "\r\n>>", 4))
        return 0;
    return rt;
}

/* For comparison only, never what the link may do: a client that sends the CR right
 * behind the text, before its echo, with one command always in flight ahead. The
 * controller's output then never idles; this shows the line and fbrlsim can carry the
 * whole echo bound, and that the byte time the verified protocols lose is the CR's. */
static double unverified_rate(rig *r, const char *line, double seconds)
{
    char out[FBRL_LINK_LINE_MAX + 2], in[FBRL_LINK_LINE_MAX + 8];
    size_t n = strlen(line), wrote;
    memcpy(out, line, n);
    out[n] = '\r';
    memcpy(in, line, n);
    memcpy(in + n, "\r\n>>", 4);
    if (fbrl_uart_write(&r->uart, out, n + 1, &wrote, 1000) != FBRL_OK)
        return 0;
    int count = 0;
    double t0 = now_s();
    while (now_s() - t0 < seconds) {
        if (fbrl_uart_write(&r->uart, out, n + 1, &wrote, 1000) != FBRL_OK ||
            await_bytes(&r->uart, in, n + 4))
            return 0;
        count++;
    }
    double rt = count / (now_s() - t0);
    if (await_bytes(&r->uart, in, n + 4)) /* the one still in flight */
        return 0;
    return rt;
}

int main(int argc, char **argv)
{
    const char *sim = argc > 1 ? argv[1] : "./sim/fbrlsim";
    double seconds = argc > 2 ? atof(argv[2]) : 0.7;
    const char *cmd_time = argc > 3 ? argv[3] : "0";
    int tcp = argc > 4 && strcmp(argv[4], "tcp") == 0;
    static const long bauds[] = {9600, 38400, 115200};
    static const char *const lines[] = {SHORT_CMD, LONG_CMD};
    double ct = atof(cmd_time) / 1000.0;
    if (seconds <= 0)
        seconds = 0.7;
    printf("link on fbrlsim's strict line (--baud N --cmd-time %s) over %s, %.1f s per figure\n", cmd_time,
           tcp ? "TCP" : "a pty", seconds);
    printf("  %-6s %-9s %6s %9s %8s %8s %8s\n", "baud", "command", "bytes", "cmd/s", "of line", "of echo",
           "of proto");
    for (size_t b = 0; b < sizeof bauds / sizeof bauds[0]; b++) {
        char baud[16];
        snprintf(baud, sizeof baud, "%ld", bauds[b]);
        const char *args[] = {"--baud", baud, "--cmd-time", cmd_time, tcp ? "--tcp" : NULL, "0", NULL};
        fbrl_link_config cfg;
        fbrl_link_config_init(&cfg);
        cfg.check_units = 0; /* the command rate is measured, not the connect */
        rig r;
        if (rig_start(&r, sim, args, (uint32_t)bauds[b], FBRL_FLOW_NONE, &cfg) != 0 ||
            fbrl_link_connect(&r.link) != FBRL_OK) {
            fprintf(stderr, "cannot start %s at %ld baud\n", sim, bauds[b]);
            return 1;
        }
        for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++) {
            size_t n = strlen(lines[k]);
            double cps = (double)bauds[b] / 10.0, bt = 1.0 / cps;
            unsigned long long retypes = 0;
            double idle = ct > 2 * bt ? ct - 2 * bt : 0.0, got = 0;
            for (int run = 0; run < RUNS; run++) {
                double one = rate(&r.link, lines[k], seconds, &retypes);
                if (one > got)
                    got = one;
            }
            double piped = ct > 0 ? 0 : pipelined_rate(&r, lines[k], seconds);
            double unver = piped > 0 ? unverified_rate(&r, lines[k], seconds) : 0;
            if (piped > 0)
                printf("  %-6ld %-9s pipelined (bare uart, no faults): %.1f cmd/s, %.1f%% of the echo bound; "
                       "CR before the echo (unsafe): %.1f cmd/s, %.1f%%\n",
                       bauds[b], k ? "POINT" : SHORT_CMD, piped, 100 * piped * ((double)(n + 4) * bt), unver,
                       100 * unver * ((double)(n + 4) * bt));
            double limit = 1.0 / ((double)(n + 1) * bt + idle), echo = 1.0 / ((double)(n + 4) * bt + idle),
                   proto = 1.0 / ((double)(n + 5) * bt + idle);
            printf("  %-6ld %-9s %3zu+1 %9.1f %7.1f%% %7.1f%% %7.1f%%%s\n", bauds[b], k ? "POINT" : SHORT_CMD,
                   n, got, 100 * got / limit, 100 * got / echo, 100 * got / proto,
                   retypes ? " (retyped)" : "");
            summary[ns].baud = bauds[b];
            summary[ns].n = n;
            summary[ns].cmd = k ? "POINT P1,..." : SHORT_CMD;
            summary[ns].cps = got;
            summary[ns].piped = 100 * piped * ((double)(n + 4) * bt);
            summary[ns].unver = 100 * unver * ((double)(n + 4) * bt);
            summary[ns].line = 100 * got / limit;
            summary[ns].echo = 100 * got / echo;
            summary[ns].ceiling = 100 * proto / echo;
            summary[ns++].proto = 100 * got / proto;
        }
        rig_stop(&r);
    }
    char think[48] = "";
    if (ct > 0)
        snprintf(think, sizeof think, ", --cmd-time %s ms", cmd_time);
    for (size_t k = 0; k < ns; k++)
        printf(
            "| link, strict line, %ld baud, `%s` (%zu+1 bytes)%s | %.1f cmd/s | %.1f %% of the echo bound, "
            "%.1f %% of the line rate (%.1f %% of the protocol limit %.1f %%) |\n",
            summary[k].baud, summary[k].cmd, summary[k].n, think, summary[k].cps, summary[k].echo,
            summary[k].line, summary[k].proto, summary[k].ceiling);
    for (size_t k = 0; k < ns; k++)
        if (summary[k].piped > 0)
            printf("| without the link (bare uart, clean line), %ld baud, `%s`: next text behind the CR "
                   "(docs/link.md 3.10) / CR before the echo (unsafe, never done) | %.1f %% / %.1f %% of the "
                   "echo bound | the CR's byte time is what the verified protocols lose |\n",
                   summary[k].baud, summary[k].cmd, summary[k].piped, summary[k].unver);
    return 0;
}
