/* SPDX-License-Identifier: MIT */
/* burst_relay: a serial line that loses bursts, as a flaky USB adapter or a loose
 * connector does. It opens PEER (a pty path, e.g. fbrlsim's), makes a new pty, prints
 * its path on the first line of stdout, and copies bytes both ways; in each direction
 * every byte starts a lost run of RUN bytes (itself and the RUN - 1 after it) with
 * probability P. Runs until SIGTERM/SIGINT or until PEER closes; then prints the counts
 * on stderr ("relay: host->peer N bytes, M lost in K runs; peer->host ...").
 * Usage: burst_relay PEER [P] [RUN] [SEED]   (defaults 0.002 50 1) */
#define _XOPEN_SOURCE 700 /* posix_openpt */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

typedef struct dir {
    uint64_t rng;
    long left; /* bytes of the current run still to drop */
    unsigned long bytes, lost, runs;
} dir;

static double p_start = 0.002;
static long run_len = 50;
static volatile sig_atomic_t stop;

static void on_signal(int sig)
{
    (void)sig;
    stop = 1;
}

/* xorshift64*: a private, reproducible generator per direction */
static double uniform(dir *d)
{
    d->rng ^= d->rng >> 12;
    d->rng ^= d->rng << 25;
    d->rng ^= d->rng >> 27;
    return (double)((d->rng * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

static int raw(int fd)
{
    struct termios t;
    if (tcgetattr(fd, &t) != 0)
        return -1;
    cfmakeraw(&t);
    return tcsetattr(fd, TCSANOW, &t);
}

/* Copy what is readable on from to to, losing the bursts. 0 at EOF/hangup. */
static int pass(int from, int to, dir *d)
{
    unsigned char in[4096], out[4096];
    ssize_t n = read(from, in, sizeof in);
    if (n < 0)
        return errno == EAGAIN || errno == EINTR ? 1 : 0;
    if (n == 0)
        return 0;
    size_t k = 0;
    for (ssize_t i = 0; i < n; i++) {
        d->bytes++;
        if (d->left == 0 && uniform(d) < p_start) {
            d->left = run_len;
            d->runs++;
        }
        if (d->left > 0) {
            d->left--;
            d->lost++;
            continue;
        }
        out[k++] = in[i];
    }
    for (size_t w = 0; w < k;) {
        ssize_t m = write(to, out + w, k - w);
        if (m < 0 && errno != EAGAIN && errno != EINTR)
            return 0;
        if (m > 0)
            w += (size_t)m;
        else
            usleep(100);
    }
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PEER [P] [RUN] [SEED]\n", argv[0]);
        return 2;
    }
    if (argc > 2)
        p_start = atof(argv[2]);
    if (argc > 3)
        run_len = atol(argv[3]);
    unsigned long seed = argc > 4 ? strtoul(argv[4], NULL, 10) : 1;
    dir up = {0x9E3779B97F4A7C15ull ^ seed, 0, 0, 0, 0},
        down = {0xD1B54A32D192ED03ull ^ (seed * 7919u), 0, 0, 0, 0};
    int peer = open(argv[1], O_RDWR | O_NOCTTY | O_NONBLOCK);
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    if (peer < 0 || master < 0 || grantpt(master) || unlockpt(master) || raw(peer) != 0) {
        perror("burst_relay");
        return 1;
    }
    /* keep the host side open ourselves, raw, so the client may come and go */
    int keep = open(ptsname(master), O_RDWR | O_NOCTTY);
    if (keep < 0 || raw(keep) != 0) {
        perror("burst_relay: pty");
        return 1;
    }
    fcntl(master, F_SETFL, O_NONBLOCK);
    signal(SIGTERM, on_signal);
    signal(SIGINT, on_signal);
    printf("%s\n", ptsname(master));
    fflush(stdout);
    while (!stop) {
        struct pollfd p[2] = {{master, POLLIN, 0}, {peer, POLLIN, 0}};
        if (poll(p, 2, 100) < 0)
            continue;
        if ((p[0].revents & POLLIN) && !pass(master, peer, &up))
            break;
        if ((p[1].revents & (POLLIN | POLLHUP)) && !pass(peer, master, &down))
            break;
    }
    fprintf(stderr,
            "relay: host->peer %lu bytes, %lu lost in %lu runs; peer->host %lu bytes, %lu lost in %lu runs\n",
            up.bytes, up.lost, up.runs, down.bytes, down.lost, down.runs);
    return 0;
}
