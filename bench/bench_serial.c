/* SPDX-License-Identifier: MIT */
/* bench_serial.c - throughput of the UART core + POSIX backend through a pty pair,
 * with and without XON/XOFF, and the driver's CPU time per byte.
 *
 * One direction: our port on the pty slave sends, our port on the master (adopted
 * fd) receives and checks every byte. Two service modes: a background service
 * thread per port (an app writer and an app reader thread on top), and polled (one
 * thread alternates non-blocking writes and short reads). CPU time is the whole
 * process's user+system time (getrusage) divided by the bytes moved: both ends'
 * drivers and the kernel's pty work, i.e. what a byte costs on this machine.
 * Usage: bench_serial [MiB per case, default 32] */
#define _XOPEN_SOURCE 700
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/resource.h>
#include <sys/time.h>
#include "fbrl/uart_posix.h"
#include "fbrl/clock.h"

static uint8_t rxa[4096], txa[4096], rxb[4096], txb[4096];

static uint8_t pat(uint64_t i, int flow)
{
    uint8_t b = (uint8_t)(i * 131u + (i >> 9));
    return flow && (b == 0x11 || b == 0x13) ? (uint8_t)(b + 1) : b;
}

struct side {
    fbrl_uart *u;
    uint64_t total, done, bad;
    int flow;
};

static void *writer(void *arg)
{
    struct side *s = arg;
    uint8_t buf[4096];
    while (s->done < s->total) {
        size_t len = s->total - s->done < sizeof buf ? (size_t)(s->total - s->done) : sizeof buf, n = 0;
        for (size_t i = 0; i < len; i++)
            buf[i] = pat(s->done + i, s->flow);
        if (fbrl_uart_write(s->u, buf, len, &n, 5000) != FBRL_OK && n == 0)
            break;
        s->done += n;
    }
    return NULL;
}

static void *reader(void *arg)
{
    struct side *s = arg;
    uint8_t buf[4096];
    while (s->done < s->total) {
        size_t n = 0;
        if (fbrl_uart_read(s->u, buf, sizeof buf, &n, 5000) != FBRL_OK)
            break;
        for (size_t i = 0; i < n; i++)
            s->bad += buf[i] != pat(s->done + i, s->flow);
        s->done += n;
    }
    return NULL;
}

static double cpu_s(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 + (double)ru.ru_stime.tv_sec +
           (double)ru.ru_stime.tv_usec * 1e-6;
}

static int run(int flow, int threaded, uint64_t total)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    if (m < 0 || grantpt(m) != 0 || unlockpt(m) != 0)
        return -1;
    char name[64];
    snprintf(name, sizeof name, "%s", ptsname(m));
    fbrl_uart_posix pa, pb;
    fbrl_uart ua, ub;
    fbrl_uart_config cfg = {115200, 8, FBRL_PARITY_NONE, 1, flow ? FBRL_FLOW_XONXOFF : FBRL_FLOW_NONE};
    fbrl_uart_posix_options opt = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    opt.service_thread = threaded;
    if (fbrl_uart_posix_open(&pa, &ua, name, &cfg, rxa, sizeof rxa, txa, sizeof txa, &opt) != FBRL_OK ||
        fbrl_uart_posix_open_fd(&pb, &ub, m, &cfg, rxb, sizeof rxb, txb, sizeof txb, &opt) != FBRL_OK)
        return -1;
    struct side w = {&ua, total, 0, 0, flow}, r = {&ub, total, 0, 0, flow};
    double c0 = cpu_s();
    uint64_t t0 = fbrl_clock_now_us();
    if (threaded) {
        pthread_t tw, tr;
        pthread_create(&tw, NULL, writer, &w);
        pthread_create(&tr, NULL, reader, &r);
        pthread_join(tw, NULL);
        pthread_join(tr, NULL);
    } else {
        uint8_t buf[4096];
        while (r.done < total) {
            size_t n = 0;
            if (w.done < total) {
                size_t len = total - w.done < sizeof buf ? (size_t)(total - w.done) : sizeof buf;
                for (size_t i = 0; i < len; i++)
                    buf[i] = pat(w.done + i, flow);
                fbrl_uart_write(&ua, buf, len, &n, 0);
                w.done += n;
            }
            fbrl_uart_read(&ua, buf, 0, &n, 0); /* a's loop reads b's XON/XOFF */
            fbrl_uart_drain(&ua, 0);
            if (fbrl_uart_read(&ub, buf, sizeof buf, &n, 1) == FBRL_OK) {
                for (size_t i = 0; i < n; i++)
                    r.bad += buf[i] != pat(r.done + i, flow);
                r.done += n;
            }
        }
    }
    double wall = (double)(fbrl_clock_now_us() - t0) / 1e6, cpu = cpu_s() - c0;
    fbrl_uart_counters ca, cb;
    fbrl_uart_get_counters(&ua, &ca);
    fbrl_uart_get_counters(&ub, &cb);
    printf("%-9s %-8s %10.1f MB/s %8.1f ns/byte CPU  xoff %6llu  held %7.1f ms  %s\n",
           flow ? "XON/XOFF" : "none", threaded ? "thread" : "polled", (double)r.done / wall / 1e6,
           cpu / (double)r.done * 1e9, (unsigned long long)ca.xoff_received, (double)ca.held_off_us / 1e3,
           r.done == total && r.bad == 0 ? "all bytes intact" : "DATA LOST OR WRONG");
    fbrl_uart_close(&ua);
    fbrl_uart_close(&ub);
    return 0;
}

int main(int argc, char **argv)
{
    uint64_t total = (uint64_t)(argc > 1 && atoi(argv[1]) > 0 ? atoi(argv[1]) : 32) << 20;
    printf("pty pair, %llu bytes one way per case (MB = 1e6 B); CPU = process user+sys per byte\n",
           (unsigned long long)total);
    for (int flow = 0; flow < 2; flow++)
        for (int threaded = 1; threaded >= 0; threaded--)
            if (run(flow, threaded, total) != 0)
                fprintf(stderr, "could not open a pty pair\n");
    return 0;
}
