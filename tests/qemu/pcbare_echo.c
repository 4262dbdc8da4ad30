/* SPDX-License-Identifier: MIT */
/* pcbare_echo.c - host side of the bare-metal test: boots the pc-bare image under
 * QEMU with COM1 on a pty, opens that pty with the project's own POSIX backend
 * (fbrl_uart over uart_posix, XON/XOFF on), pushes a pseudo-random payload through
 * the image's interrupt-driven echo and checks every byte that comes back.
 *
 * Usage: pcbare_echo QEMU IMAGE [BYTES [APPEND]]
 * APPEND is the image's command line (see ports/pc-bare/main.c: baud=, fifo=, stall=).
 * Exit 0 only when every byte came back transformed (a-z upper-cased), the image's
 * STATS line says PASS with the same byte sum, and QEMU ended with status 33
 * (isa-debug-exit 0x10); with stall= the image must also have sent XOFF and this
 * host must have obeyed it. Prints the figures on stdout.
 *
 * In-flight bound: QEMU's 16550 does not pace at the baud rate, and the pty buffers
 * kilobytes, so XON/XOFF alone cannot stop a host that has queued far ahead (the
 * XOFF arrives after the bytes). The POSIX backend bounds its kernel output queue only
 * on real ttys, not on ptys, so this program bounds what it has in flight itself:
 * it never has more than WINDOW bytes written but not yet echoed. WINDOW is also below
 * this side's XOFF mark (3/4 of the 4 KiB receive ring), so the host never has to stop
 * the image: without the bound, the stalling case deadlocks (measured: ~24 KB in
 * flight, both sides stopped), because the host's XON then waits behind data bytes
 * already queued toward an image that stopped reading. */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fbrl/clock.h"
#include "fbrl/uart.h"
#include "fbrl/uart_posix.h"

#define ENQ        0x05
#define EOT        0x04
#define ACK        0x06
#define WINDOW     2048u /* bytes written but not yet echoed back, at most */
#define CHUNK      256u
#define DEADLINE_S 100u /* the whole run; ctest allows 120 */

static pid_t qemu_pid = -1;

static void die(const char *what)
{
    fprintf(stderr, "pcbare_echo: FAIL: %s\n", what);
    if (qemu_pid > 0) {
        kill(qemu_pid, SIGKILL);
        waitpid(qemu_pid, NULL, 0);
    }
    exit(1);
}

static void die_st(const char *what, fbrl_status st)
{
    char msg[256];
    snprintf(msg, sizeof msg, "%s: %s (%s)", what, fbrl_status_name(st), fbrl_status_str(st));
    die(msg);
}

/* Start QEMU with its stdout on a pipe; return the pipe's read end. */
static int start_qemu(const char *qemu, const char *image, const char *append)
{
    int fds[2];
    if (pipe(fds) != 0)
        die("pipe");
    qemu_pid = fork();
    if (qemu_pid < 0)
        die("fork");
    if (qemu_pid == 0) {
        const char *argv[24];
        int n = 0;
        dup2(fds[1], STDOUT_FILENO);
        close(fds[0]);
        close(fds[1]);
        argv[n++] = qemu;
        argv[n++] = "-kernel";
        argv[n++] = image;
        if (append) {
            argv[n++] = "-append";
            argv[n++] = append;
        }
        argv[n++] = "-display";
        argv[n++] = "none";
        argv[n++] = "-no-reboot";
        argv[n++] = "-nic";
        argv[n++] = "none";
        argv[n++] = "-vga";
        argv[n++] = "none";
        argv[n++] = "-monitor";
        argv[n++] = "none";
        argv[n++] = "-serial";
        argv[n++] = "pty";
        argv[n++] = "-device";
        argv[n++] = "isa-debug-exit,iobase=0xf4,iosize=0x04";
        argv[n] = NULL;
        execv(qemu, (char *const *)argv);
        perror("exec qemu");
        _exit(127);
    }
    close(fds[1]);
    return fds[0];
}

/* QEMU prints "char device redirected to /dev/pts/N (label serial0)" on stdout. */
static void find_pty(int fd, char *path, size_t cap)
{
    char buf[1024];
    size_t len = 0;
    uint64_t end = fbrl_clock_now_us() + 20000000u;
    for (;;) {
        struct pollfd pfd = {fd, POLLIN, 0};
        char *p, *q;
        ssize_t n;
        if (fbrl_clock_now_us() > end)
            die("QEMU did not report its pty within 20 s");
        if (poll(&pfd, 1, 200) <= 0)
            continue;
        n = read(fd, buf + len, sizeof buf - 1 - len);
        if (n <= 0)
            die("QEMU exited before reporting its pty");
        len += (size_t)n;
        buf[len] = 0;
        p = strstr(buf, "/dev/pts/");
        if (p && (q = strpbrk(p, " \n")) != NULL) {
            if ((size_t)(q - p) >= cap)
                die("pty path too long");
            memcpy(path, p, (size_t)(q - p));
            path[q - p] = 0;
            return;
        }
        if (len == sizeof buf - 1)
            die("unexpected QEMU output");
    }
}

/* The payload: xorshift bytes, avoiding the protocol's control bytes and XON/XOFF. */
static uint8_t payload_byte(uint32_t *s)
{
    for (;;) {
        uint8_t c;
        *s ^= *s << 13;
        *s ^= *s >> 17;
        *s ^= *s << 5;
        c = (uint8_t)(*s >> 24);
        if (c != ENQ && c != EOT && c != FBRL_XON && c != FBRL_XOFF)
            return c;
    }
}

static uint8_t transform(uint8_t c) { return (c >= 'a' && c <= 'z') ? (uint8_t)(c - 'a' + 'A') : c; }

static fbrl_uart_posix port;
static fbrl_uart uart;
static uint8_t rx_mem[4096], tx_mem[4096];

/* Read into buf until it holds needle (or the deadline); returns bytes held. */
static size_t read_until(char *buf, size_t cap, size_t len, const char *needle, uint32_t timeout_ms)
{
    uint64_t end = fbrl_clock_now_us() + (uint64_t)timeout_ms * 1000u;
    while (fbrl_clock_now_us() < end) {
        size_t got = 0;
        fbrl_status st;
        buf[len] = 0;
        if (strstr(buf, needle))
            break;
        if (len + 1 >= cap)
            die("reply too long");
        st = fbrl_uart_read(&uart, buf + len, cap - 1 - len, &got, 200);
        if (st != FBRL_OK && st != FBRL_ETIMEOUT)
            die_st("read", st);
        /* NUL bytes would end the string search early; the replies have none. */
        len += got;
    }
    buf[len] = 0;
    return len;
}

int main(int argc, char **argv)
{
    const char *marker = "#BEGIN#";
    const size_t mlen = strlen(marker);
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    fbrl_uart_posix_options opt = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    fbrl_uart_counters c;
    fbrl_status st;
    char path[64], reply[512], *stats;
    uint8_t *expect, *send;
    size_t total, sent = 0, matched = 0, msync = 0, len;
    uint32_t seed = 0x2545F491u, sum = 0;
    uint64_t t0, t1, deadline;
    unsigned long guest_sum;
    int qout, status = 0, idle = 0;

    if (argc < 3 || argc > 5) {
        fprintf(stderr, "usage: %s QEMU IMAGE [BYTES [APPEND]]\n", argv[0]);
        return 2;
    }
    total = argc >= 4 ? (size_t)strtoul(argv[3], NULL, 0) : 65536u;
    if (total == 0)
        die("BYTES must be > 0");
    signal(SIGPIPE, SIG_IGN);
    deadline = fbrl_clock_now_us() + (uint64_t)DEADLINE_S * 1000000u;

    /* What goes out (marker first) and what must come back. */
    send = malloc(mlen + total);
    expect = malloc(mlen + total);
    if (!send || !expect)
        die("out of memory");
    memcpy(send, marker, mlen);
    for (len = 0; len < total; len++)
        send[mlen + len] = payload_byte(&seed);
    total += mlen;
    for (len = 0; len < total; len++) {
        expect[len] = transform(send[len]);
        sum += expect[len];
    }

    qout = start_qemu(argv[1], argv[2], argc == 5 ? argv[4] : NULL);
    find_pty(qout, path, sizeof path);

    cfg.baud = 115200;
    st = fbrl_uart_posix_open(&port, &uart, path, &cfg, rx_mem, sizeof rx_mem, tx_mem, sizeof tx_mem, &opt);
    if (st != FBRL_OK)
        die_st("open pty", st);

    /* Handshake: QEMU drops guest output until it notices the pty was opened (it
     * polls once a second), so ask with ENQ until READY comes back. Extra READYs
     * from repeated ENQs arrive before the marker's echo and are skipped. */
    len = 0;
    reply[0] = 0;
    while (!strstr(reply, "READY\n")) {
        uint8_t enq = ENQ;
        if (fbrl_clock_now_us() > deadline)
            die("no READY from the image");
        st = fbrl_uart_write(&uart, &enq, 1, NULL, 1000);
        if (st != FBRL_OK)
            die_st("write ENQ", st);
        len = read_until(reply, sizeof reply, len, "READY\n", 500);
        if (len > sizeof reply / 2)
            len = 0;
    }

    t0 = fbrl_clock_now_us();
    while (matched < total) {
        uint8_t in[4096];
        size_t got = 0, i, wrote = 0;
        if (fbrl_clock_now_us() > deadline) {
            fprintf(stderr, "sent %zu, matched %zu of %zu\n", sent, matched, total);
            die("transfer did not finish in time");
        }
        if (sent < total && sent - matched + CHUNK <= WINDOW) {
            size_t n = total - sent < CHUNK ? total - sent : CHUNK;
            st = fbrl_uart_write(&uart, send + sent, n, &wrote, 0);
            if (st != FBRL_OK && st != FBRL_ETIMEOUT)
                die_st("write", st);
            sent += wrote;
        }
        st = fbrl_uart_read(&uart, in, sizeof in, &got, (wrote || got) && !idle ? 0 : 20);
        if (st != FBRL_OK && st != FBRL_ETIMEOUT)
            die_st("read", st);
        idle = wrote == 0 && got == 0;
        for (i = 0; i < got; i++) {
            if (msync < mlen) { /* skip READY lines up to the marker's echo */
                msync = in[i] == (uint8_t)marker[msync] ? msync + 1 : (in[i] == (uint8_t)marker[0]);
                if (msync == mlen)
                    matched = mlen;
                continue;
            }
            if (matched >= total || in[i] != expect[matched]) {
                char msg[128];
                snprintf(msg, sizeof msg, "byte %zu: got 0x%02x, want 0x%02x", matched - mlen, in[i],
                         matched < total ? expect[matched] : 0);
                die(msg);
            }
            matched++;
        }
    }
    t1 = fbrl_clock_now_us();

    /* End: EOT -> the image's STATS line; ACK lets it exit. */
    {
        uint8_t eot = EOT;
        st = fbrl_uart_write(&uart, &eot, 1, NULL, 1000);
        if (st != FBRL_OK)
            die_st("write EOT", st);
    }
    len = read_until(reply, sizeof reply, 0, "\n", 10000);
    stats = strstr(reply, "STATS ");
    if (!stats || !strchr(stats, '\n'))
        die("no STATS line from the image");
    *strchr(stats, '\n') = 0;
    {
        uint8_t ack = ACK;
        st = fbrl_uart_write(&uart, &ack, 1, NULL, 1000);
        if (st != FBRL_OK)
            die_st("write ACK", st);
        (void)fbrl_uart_drain(&uart, 1000);
    }
    if (fbrl_uart_get_counters(&uart, &c) != FBRL_OK)
        die("counters");

    /* QEMU should now exit by itself through isa-debug-exit. */
    {
        uint64_t end = fbrl_clock_now_us() + 20000000u;
        pid_t w;
        while ((w = waitpid(qemu_pid, &status, WNOHANG)) == 0 && fbrl_clock_now_us() < end)
            fbrl_clock_sleep_us(10000);
        if (w != qemu_pid)
            die("QEMU did not exit");
        qemu_pid = -1;
    }
    (void)fbrl_uart_close(&uart);
    close(qout);

    printf("guest: %s\n", stats);
    printf("host: %zu bytes echoed in %.3f s (%.1f kB/s each way), window %u, xoff_sent=%llu "
           "xoff_recv=%llu held_off=%.3f s\n",
           total, (double)(t1 - t0) / 1e6, (double)total / ((double)(t1 - t0) / 1e6) / 1000.0, WINDOW,
           (unsigned long long)c.xoff_sent, (unsigned long long)c.xoff_received, (double)c.held_off_us / 1e6);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 33) {
        fprintf(stderr, "QEMU status %d\n", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        die("QEMU did not end with the image's PASS (status 33)");
    }
    if (!strstr(stats, " PASS"))
        die("the image reported FAIL");
    {
        const char *s = strstr(stats, " sum=");
        if (!s || sscanf(s, " sum=%lu", &guest_sum) != 1 || (uint32_t)guest_sum != sum)
            die("the image's byte sum differs from what was sent");
    }
    if (c.overruns != 0)
        die("host side lost bytes");
    /* A stalling image must have stopped this host with XOFF (and let it go again). */
    if (argc == 5 && strstr(argv[4], "stall=")) {
        if (c.xoff_received == 0)
            die("the stalling image never sent XOFF");
        if (!strstr(stats, "xoff_sent=") || strstr(stats, "xoff_sent=0 "))
            die("the image counted no XOFF sent");
    }
    printf("PASS\n");
    free(send);
    free(expect);
    return 0;
}
