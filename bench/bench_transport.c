/* SPDX-License-Identifier: MIT */
/* bench_transport: what the transport layer costs on a real-rate line (fbrlsim --baud).
 * Usage: bench_transport [FBRLSIM [SECONDS [PARTS]]]  (default ./sim/fbrlsim, 3 s per run,
 * parts "123"; "3n" = part 3 with fbrl_link_poll_many only)
 *
 *  1. POINT commands per second at 9600 baud with the old four-decimal text and with
 *     the encoder's shortest text, each against its line-rate and echo bounds.
 *  2. An event-driven host (poll() on the port's fd, then fbrl_link_poll(l, 0)) against
 *     the blocking fbrl_link_cmd loop, at 9600 baud.
 *  3. Many robots from one thread at 9600 baud (one fbrlsim each): per-robot command
 *     rates for 1, 8 and 32 robots and the host's CPU (getrusage, this process only),
 *     with fbrl_link_poll_many and with the scan it replaced (every link in turn from
 *     link 0, 1 ms each, return at the first finished command), written here with the
 *     public calls.
 *
 * Bounds for an n-character command on an 8N1 line at B baud: the line-rate limit
 * (B/10)/(n+1) (the host sends n+1 bytes) and the echo bound (B/10)/(n+4) (the
 * controller sends the echo, CR LF and ">>"). Only public calls of libfbrl are used, so
 * the same file builds against an older tree for "before" figures. Lines starting with
 * "| " are rows of scripts/bench.sh's summary. */
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "../tests/e2e/rapl_harness.h"

#define BAUD       9600u
#define MAX_ROBOTS 32
#define SHORT_CMD  "SPEED 50"

static double seconds = 3.0;

static double now_s(void) { return (double)fbrl_clock_now_us() / 1e6; }

static double cpu_s(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_stime.tv_sec +
           ((double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_usec) / 1e6;
}

static double line_limit(size_t n) { return (BAUD / 10.0) / (double)(n + 1); }
static double echo_bound(size_t n) { return (BAUD / 10.0) / (double)(n + 4); }

static int start_rig(rig *r, const char *sim)
{
    static const char *const args[] = {"--baud", "9600", NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    cfg.check_units = 0; /* the command rate is measured, not the connect */
    if (rig_start(r, sim, args, BAUD, FBRL_FLOW_NONE, &cfg) != 0)
        return -1;
    if (fbrl_link_connect(&r->link) != FBRL_OK) {
        fprintf(stderr, "connect %s failed\n", r->path);
        return -1;
    }
    return 0;
}

/* ---- 1. POINT text ---- */

static double run_raw(fbrl_link *l, const char *line)
{
    int count = 0;
    double t0 = now_s();
    while (now_s() - t0 < seconds) {
        fbrl_status st = fbrl_link_raw(l, line);
        if (st != FBRL_OK) {
            fprintf(stderr, "%s: %s\n", line, fbrl_status_name(st));
            return 0;
        }
        count++;
    }
    return count / (now_s() - t0);
}

static void point_text(const char *sim)
{
    static const double v[6] = {14.25, 2.5, 8.125, 0.0, 90.0, 12.3456};
    char four[96], shortest[FBRL_RAPL_LINE_MAX];
    size_t n;
    snprintf(four, sizeof four, "POINT P1,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f", v[0], v[1], v[2], v[3], v[4], v[5]);
    fbrl_rapl_arg a[7] = {fbrl_rapl_str("P1")};
    for (int k = 0; k < 6; k++)
        a[k + 1] = fbrl_rapl_real(v[k]);
    if (fbrl_rapl_encode(shortest, sizeof shortest, &n, FBRL_RAPL_KEYWORD, FBRL_RAPL_POINT, a, 7, 0) !=
        FBRL_OK)
        return;
    rig r;
    if (start_rig(&r, sim) != 0)
        return;
    printf("1. POINT text at %u baud (fbrlsim --baud), link's blocking calls\n", BAUD);
    double cps[2];
    const char *lines[2] = {four, shortest};
    const char *names[2] = {"four decimals", "encoder"};
    for (int k = 0; k < 2; k++) {
        size_t len = strlen(lines[k]);
        cps[k] = run_raw(&r.link, lines[k]);
        printf("   %-13s %-54s %2zu+1 bytes: %5.1f cmd/s = %5.1f %% of the line-rate limit %5.1f, %5.1f %% "
               "of the"
               " echo bound %5.1f\n",
               names[k], lines[k], len, cps[k], 100 * cps[k] / line_limit(len), line_limit(len),
               100 * cps[k] / echo_bound(len), echo_bound(len));
    }
    if (cps[0] > 0)
        printf("   encoder / four decimals: %.2fx POINT commands per second\n", cps[1] / cps[0]);
    for (int k = 0; k < 2; k++) {
        size_t len = strlen(lines[k]);
        printf("| POINT at %u baud, %s (%zu+1 bytes) | %.1f cmd/s | %.1f %% of the line rate, %.1f %% of the "
               "echo "
               "bound |\n",
               BAUD, k ? "shortest text (encoder)" : "four decimals (before)", len, cps[k],
               100 * cps[k] / line_limit(len), 100 * cps[k] / echo_bound(len));
    }
    if (cps[0] > 0)
        printf("| POINT commands per second, shortest text / four decimals | %.2fx | |\n", cps[1] / cps[0]);
    rig_stop(&r);
}

/* ---- 2. event-driven host ---- */

static void event_driven(const char *sim)
{
    rig r;
    if (start_rig(&r, sim) != 0)
        return;
    size_t n = strlen(SHORT_CMD);
    printf("2. event-driven host at %u baud: '%s' (%zu+1 bytes)\n", BAUD, SHORT_CMD, n);
    double blocking = run_raw(&r.link, SHORT_CMD);
    /* The event loop: wait for the fd (at most 100 ms, as a GUI or a select loop would),
     * then let the link act on what is there. A CR left in the ring would stall each
     * command for the whole wait. */
    int fd = fbrl_uart_posix_fd(&r.port), count = 0, stalls = 0;
    double t0 = now_s();
    while (now_s() - t0 < seconds) {
        if (fbrl_link_start(&r.link, SHORT_CMD, FBRL_LINK_REPLY_NONE) != FBRL_OK)
            break;
        int done = 0;
        fbrl_status st = fbrl_link_poll(&r.link, 0, &done);
        while (!done) {
            struct pollfd f = {fd, POLLIN, 0};
            if (poll(&f, 1, 100) == 0)
                stalls++;
            st = fbrl_link_poll(&r.link, 0, &done);
        }
        if (st != FBRL_OK) {
            fprintf(stderr, "event loop: %s\n", fbrl_status_name(st));
            break;
        }
        count++;
    }
    double ev = count / (now_s() - t0);
    printf("   blocking calls: %5.1f cmd/s (%5.1f %% of the echo bound %5.1f)\n", blocking,
           100 * blocking / echo_bound(n), echo_bound(n));
    printf("   event loop:     %5.1f cmd/s (%5.1f %% of the echo bound), %d waits of 100 ms ran out\n", ev,
           100 * ev / echo_bound(n), stalls);
    printf(
        "| event-driven host at %u baud (`poll()`, then `fbrl_link_poll(l, 0)`), `%s` | %.1f cmd/s | %.1f %% "
        "of the echo bound (blocking calls %.1f %%) |\n",
        BAUD, SHORT_CMD, ev, 100 * ev / echo_bound(n), 100 * blocking / echo_bound(n));
    rig_stop(&r);
}

/* ---- 3. many robots ---- */

/* The scan fbrl_link_poll_many used to do: links in index order, 1 ms each, return at
 * the first one finished. */
static fbrl_status scan_from_zero(fbrl_link *const *links, size_t n, uint32_t timeout_ms, size_t *index)
{
    uint64_t end = fbrl_clock_now_us() + (uint64_t)timeout_ms * 1000u;
    *index = n;
    for (;;) {
        for (size_t k = 0; k < n; k++) {
            int done = 0;
            if (!fbrl_link_busy(links[k]))
                continue;
            fbrl_status st = fbrl_link_poll(links[k], 1, &done);
            if (done) {
                *index = k;
                return st;
            }
        }
        if (fbrl_clock_now_us() >= end)
            return FBRL_ETIMEOUT;
    }
}

typedef fbrl_status (*poll_fn)(fbrl_link *const *, size_t, uint32_t, size_t *);

/* Every robot repeats SHORT_CMD for `seconds`; rate[k] = its commands per second. */
static int many(rig *rigs, size_t n, poll_fn fn, double *rate, double *cpu, int *failed)
{
    fbrl_link *links[MAX_ROBOTS];
    long count[MAX_ROBOTS] = {0};
    *failed = 0;
    for (size_t k = 0; k < n; k++) {
        links[k] = &rigs[k].link;
        if (fbrl_link_start(links[k], SHORT_CMD, FBRL_LINK_REPLY_NONE) != FBRL_OK)
            return -1;
    }
    double c0 = cpu_s(), t0 = now_s(), t;
    while ((t = now_s()) - t0 < seconds) {
        size_t idx;
        fbrl_status st = fn(links, n, 100, &idx);
        if (idx >= n)
            continue;
        if (st == FBRL_OK)
            count[idx]++;
        else
            (*failed)++;
        if (fbrl_link_start(links[idx], SHORT_CMD, FBRL_LINK_REPLY_NONE) != FBRL_OK)
            return -1;
    }
    double wall = t - t0;
    *cpu = (cpu_s() - c0) / wall;
    /* let the commands in flight finish, so the next run starts clean */
    size_t idx;
    double t1 = now_s();
    while (now_s() - t1 < 5 && fbrl_link_poll_many(links, n, 100, &idx) != FBRL_EEMPTY)
        ;
    for (size_t k = 0; k < n; k++)
        rate[k] = count[k] / wall;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void many_robots(const char *sim, int with_old)
{
    static rig rigs[MAX_ROBOTS];
    static const size_t counts[] = {1, 8, 32};
    size_t n = strlen(SHORT_CMD);
    size_t started = 0;
    for (; started < MAX_ROBOTS; started++)
        if (start_rig(&rigs[started], sim) != 0)
            break;
    printf("3. robots from one thread at %u baud, '%s' repeated, %.0f s per run; echo bound %.1f cmd/s per "
           "robot\n",
           BAUD, SHORT_CMD, seconds, echo_bound(n));
    static const struct {
        const char *name;
        poll_fn fn;
    } algs[] = {
        {"fbrl_link_poll_many", fbrl_link_poll_many},
        {"old scan from link 0", scan_from_zero},
    };
    for (size_t a = 0; a < (with_old ? 2u : 1u); a++) {
        double alone = 0;
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
            size_t robots = counts[c];
            double rate[MAX_ROBOTS], sorted[MAX_ROBOTS], cpu = 0, total = 0;
            int failed = 0;
            if (robots > started || many(rigs, robots, algs[a].fn, rate, &cpu, &failed) != 0) {
                printf("   %-20s %2zu robots: could not run\n", algs[a].name, robots);
                continue;
            }
            for (size_t k = 0; k < robots; k++)
                total += sorted[k] = rate[k];
            qsort(sorted, robots, sizeof sorted[0], cmp_double);
            if (robots == 1)
                alone = rate[0];
            printf("   %-20s %2zu robots: per robot min %5.1f median %5.1f max %5.1f cmd/s (min = %5.1f %% "
                   "of alone,"
                   " %5.1f %% of the echo bound), total %6.1f cmd/s, host CPU %4.1f %% of one core%s\n",
                   algs[a].name, robots, sorted[0], sorted[robots / 2], sorted[robots - 1],
                   alone > 0 ? 100 * sorted[0] / alone : 0.0, 100 * sorted[0] / echo_bound(n), total,
                   100 * cpu, failed ? ", FAILURES" : "");
            if (a == 0)
                printf(
                    "| %zu robot%s at %u baud, `fbrl_link_poll_many` | per robot %.1f .. %.1f cmd/s, total "
                    "%.1f, "
                    "host CPU %.1f %% of one core | min = %.1f %% of alone, %.1f %% of the echo bound%s |\n",
                    robots, robots > 1 ? "s" : "", BAUD, sorted[0], sorted[robots - 1], total, 100 * cpu,
                    alone > 0 ? 100 * sorted[0] / alone : 0.0, 100 * sorted[0] / echo_bound(n),
                    failed ? ", FAILURES" : "");
            if (robots == MAX_ROBOTS) {
                printf("      per robot:");
                for (size_t k = 0; k < robots; k++)
                    printf(" %.0f", rate[k]);
                printf("\n");
            }
        }
    }
    for (size_t k = 0; k < started; k++)
        rig_stop(&rigs[k]);
}

int main(int argc, char **argv)
{
    const char *sim = argc > 1 ? argv[1] : "./sim/fbrlsim";
    if (argc > 2)
        seconds = atof(argv[2]);
    if (seconds <= 0)
        seconds = 3;
    const char *parts = argc > 3 ? argv[3] : "123";
    if (strchr(parts, '1'))
        point_text(sim);
    if (strchr(parts, '2'))
        event_driven(sim);
    if (strchr(parts, '3'))
        many_robots(sim, strchr(parts, 'n') == NULL);
    return 0;
}
