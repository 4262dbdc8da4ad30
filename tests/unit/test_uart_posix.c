/* SPDX-License-Identifier: MIT */
/* test_uart_posix.c - the POSIX backend over real pseudo-terminals (posix_openpt)
 * and a real loopback TCP listener: settings read back with tcgetattr, exclusive
 * use, restore on close, 16 MiB both ways under XON/XOFF with a slow reader, the
 * service thread answering flow control, timeouts, and every error case. */
/* ctest-labels: threads */
#define _XOPEN_SOURCE 700 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <unistd.h>
#include <termios.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <cmocka.h>

#include "fbrl/uart_posix.h"
#include "fbrl/clock.h"

/* A pty pair: returns the master fd, the slave's path in name. */
static int make_pty(char *name, size_t n)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(m >= 0);
    assert_int_equal(grantpt(m), 0);
    assert_int_equal(unlockpt(m), 0);
    const char *s = ptsname(m);
    assert_non_null(s);
    assert_true(strlen(s) < n);
    strcpy(name, s);
    return m;
}

static uint8_t rxa[4096], txa[4096], rxb[4096], txb[4096];

/* A pty and the port on its slave end with rings of ring bytes, polled or with the
 * service thread; the master's fd. */
static int open_on_pty(fbrl_uart_posix *p, fbrl_uart *u, const fbrl_uart_config *cfg, size_t ring,
                       int threaded)
{
    char name[64];
    int m = make_pty(name, sizeof name);
    fbrl_uart_posix_options opt = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    opt.service_thread = threaded;
    assert_int_equal(fbrl_uart_posix_open(p, u, name, cfg, rxa, ring, txa, ring, &opt), FBRL_OK);
    return m;
}

static void open_errors(void **state)
{
    (void)state;
    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    char name[64], file[] = "/tmp/fbrl_not_a_ttyXXXXXX";

    assert_int_equal(fbrl_uart_posix_open(&p, &u, "/dev/fbrl-no-such-port", &cfg, rxa, 64, txa, 64, NULL),
                     FBRL_ENOENT);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, "/no/such/dir/tty", &cfg, rxa, 64, txa, 64, NULL),
                     FBRL_ENOENT);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, "/dev/null", &cfg, rxa, 64, txa, 64, NULL), FBRL_ENOTTY);
    int fd = mkstemp(file);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, file, &cfg, rxa, 64, txa, 64, NULL), FBRL_ENOTTY);
    unlink(file);
    assert_int_equal(fbrl_uart_posix_open(NULL, &u, "/dev/null", &cfg, rxa, 64, txa, 64, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_posix_open(&p, NULL, "/dev/null", &cfg, rxa, 64, txa, 64, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, NULL, &cfg, rxa, 64, txa, 64, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, "", &cfg, rxa, 64, txa, 64, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_posix_open_fd(&p, &u, -1, &cfg, rxa, 64, txa, 64, NULL), FBRL_EINVAL);
    const char *bad_tcp[] = {"tcp:", "tcp:hostonly", "tcp::4000", "tcp:127.0.0.1:", "tcp:127.0.0.1:40x0"};
    for (size_t i = 0; i < sizeof bad_tcp / sizeof bad_tcp[0]; i++)
        assert_int_equal(fbrl_uart_posix_open(&p, &u, bad_tcp[i], &cfg, rxa, 64, txa, 64, NULL), FBRL_EINVAL);

    int m = make_pty(name, sizeof name);
    /* Bad ring storage or config: refused, and the port is left free. */
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 1, txa, 64, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, NULL, rxa, 64, txa, 64, NULL), FBRL_EINVAL);
    cfg.baud = 12345;
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL), FBRL_EUNSUPPORTED);
    cfg.baud = 9600;
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL), FBRL_OK);
    cfg.baud = 7;
    assert_int_equal(fbrl_uart_configure(&u, &cfg), FBRL_EUNSUPPORTED);
    struct termios t;
    assert_int_equal(tcgetattr(fbrl_uart_posix_fd(&p), &t), 0);
    assert_int_equal(cfgetospeed(&t), B9600); /* the refused rate left the line alone */

    /* Exclusive use: a second open of the same port, in the same process, is busy. */
    fbrl_uart_posix p2;
    fbrl_uart u2;
    cfg.baud = 9600;
    assert_int_equal(fbrl_uart_posix_open(&p2, &u2, name, &cfg, rxb, 64, txb, 64, NULL), FBRL_EBUSY);
    assert_int_equal(fbrl_uart_close(&u), FBRL_OK);
    assert_int_equal(fbrl_uart_posix_open(&p2, &u2, name, &cfg, rxb, 64, txb, 64, NULL), FBRL_OK);
    assert_int_equal(fbrl_uart_close(&u2), FBRL_OK);
    close(m);

    speed_t sp;
    assert_int_equal(fbrl_uart_posix_speed(9600, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_posix_speed(0, &sp), FBRL_EUNSUPPORTED);
    assert_int_equal(fbrl_uart_posix_speed(4000001, &sp), FBRL_EUNSUPPORTED);
    assert_int_equal(fbrl_uart_posix_fd(NULL), -1);
}

/* Another process holding the port also makes it busy (flock is per open file). */
static void busy_across_processes(void **state)
{
    (void)state;
    char name[64];
    int m = make_pty(name, sizeof name), ready[2], done[2];
    assert_int_equal(pipe(ready), 0);
    assert_int_equal(pipe(done), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        fbrl_uart_posix p;
        fbrl_uart u;
        fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
        char c = fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL) == FBRL_OK ? 'y' : 'n';
        if (write(ready[1], &c, 1) != 1 || read(done[0], &c, 1) != 1)
            _exit(1);
        _exit(0);
    }
    char c = 0;
    assert_int_equal(read(ready[0], &c, 1), 1);
    assert_int_equal(c, 'y');
    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL), FBRL_EBUSY);
    assert_int_equal(write(done[1], "x", 1), 1);
    int status;
    waitpid(pid, &status, 0);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL), FBRL_OK);
    fbrl_uart_close(&u);
    close(m);
    close(ready[0]), close(ready[1]), close(done[0]), close(done[1]);
}

/* Every rate, size, parity and stop setting is accepted and shows in tcgetattr. A
 * Linux pty keeps the speed, CSTOPB and PARODD but forces CS8 and clears PARENB
 * (it has no wire to frame): the test checks exactly what the kernel keeps. */
static void every_setting_is_applied(void **state)
{
    (void)state;
    static const uint32_t rates[] = {50,      75,      110,     134,     150,     200,    300,     600,
                                     1200,    1800,    2400,    4800,    9600,    19200,  38400,   57600,
                                     115200,  230400,  460800,  500000,  576000,  921600, 1000000, 1152000,
                                     1500000, 2000000, 2500000, 3000000, 3500000, 4000000};
    char name[64];
    int m = make_pty(name, sizeof name);
    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    struct termios t;
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL), FBRL_OK);
    int fd = fbrl_uart_posix_fd(&p);
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; i++) {
        speed_t sp;
        cfg.baud = rates[i];
        assert_int_equal(fbrl_uart_posix_speed(rates[i], &sp), FBRL_OK);
        assert_int_equal(fbrl_uart_configure(&u, &cfg), FBRL_OK);
        assert_int_equal(tcgetattr(fd, &t), 0);
        assert_int_equal(cfgetospeed(&t), sp);
        assert_int_equal(cfgetispeed(&t), sp);
    }
    cfg.baud = 9600;
    for (uint8_t bits = 5; bits <= 8; bits++) {
        for (int par = 0; par < 3; par++) {
            for (uint8_t stop = 1; stop <= 2; stop++) {
                fbrl_uart_config got;
                cfg.data_bits = bits;
                cfg.parity = par == 0 ? FBRL_PARITY_NONE : par == 1 ? FBRL_PARITY_EVEN : FBRL_PARITY_ODD;
                cfg.stop_bits = stop;
                assert_int_equal(fbrl_uart_configure(&u, &cfg), FBRL_OK);
                assert_int_equal(fbrl_uart_get_config(&u, &got), FBRL_OK);
                assert_memory_equal(&got, &cfg, sizeof cfg);
                assert_int_equal(tcgetattr(fd, &t), 0);
                assert_int_equal(!!(t.c_cflag & CSTOPB), stop == 2);
                if (par != 0)
                    assert_int_equal(!!(t.c_cflag & PARODD), par == 2);
                assert_int_equal(t.c_cflag & CSIZE, CS8); /* the pty's own rule */
                assert_int_equal(t.c_cflag & PARENB, 0);
                /* raw mode, whatever the framing */
                assert_int_equal(t.c_lflag & (ICANON | ECHO | ISIG | IEXTEN), 0);
                assert_int_equal(t.c_iflag & (IXON | IXOFF | ICRNL | ISTRIP), 0);
                assert_int_equal(t.c_oflag & OPOST, 0);
                assert_true((t.c_cflag & (CREAD | CLOCAL)) == (CREAD | CLOCAL));
                assert_int_equal(t.c_cc[VMIN], 1);
            }
        }
    }
    fbrl_uart_close(&u);
    close(m);
}

/* The settings the port had before are back after close. */
static void settings_restored_on_close(void **state)
{
    (void)state;
    char name[64];
    int m = make_pty(name, sizeof name);
    int fd = open(name, O_RDWR | O_NOCTTY); /* keeps the slave's termios alive across closes */
    struct termios before, after;
    assert_int_equal(tcgetattr(fd, &before), 0);
    before.c_lflag |= ICANON | ECHO;
    before.c_iflag |= ICRNL | IXON;
    cfsetospeed(&before, B1200);
    cfsetispeed(&before, B1200);
    assert_int_equal(tcsetattr(fd, TCSANOW, &before), 0);
    assert_int_equal(tcgetattr(fd, &before), 0);

    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = {115200, 8, FBRL_PARITY_ODD, 2, FBRL_FLOW_XONXOFF};
    assert_int_equal(fbrl_uart_posix_open(&p, &u, name, &cfg, rxa, 64, txa, 64, NULL), FBRL_OK);
    assert_int_equal(tcgetattr(fd, &after), 0);
    assert_int_equal(after.c_lflag & ICANON, 0);
    assert_int_equal(cfgetospeed(&after), B115200);
    assert_int_equal(fbrl_uart_close(&u), FBRL_OK);
    assert_int_equal(tcgetattr(fd, &after), 0);
    assert_int_equal(after.c_lflag, before.c_lflag);
    assert_int_equal(after.c_iflag, before.c_iflag);
    assert_int_equal(after.c_oflag, before.c_oflag);
    assert_int_equal(after.c_cflag, before.c_cflag);
    assert_int_equal(cfgetospeed(&after), B1200);
    close(fd);
    close(m);
}

/* ---- 16 MiB both ways ---- */

static uint8_t pat(uint64_t i, unsigned seed)
{
    uint32_t x = (uint32_t)(i * 2654435761u) ^ (uint32_t)(i >> 13) ^ seed;
    uint8_t b = (uint8_t)(x ^ (x >> 8) ^ (x >> 16));
    return (b == 0x11 || b == 0x13) ? (uint8_t)(b + 0x40) : b; /* XON/XOFF are not data */
}

struct flow {
    fbrl_uart *u;
    uint64_t total;
    unsigned seed;
    int slow; /* reader: pause 2 ms after every 'slow' KiB */
    uint64_t done;
    uint64_t bad_at; /* first wrong byte, UINT64_MAX if none */
    fbrl_status err;
};

static void *writer(void *arg)
{
    struct flow *f = arg;
    uint8_t buf[3000];
    while (f->done < f->total) {
        size_t len = sizeof buf, n = 0;
        if (len > f->total - f->done)
            len = (size_t)(f->total - f->done);
        for (size_t i = 0; i < len; i++)
            buf[i] = pat(f->done + i, f->seed);
        fbrl_status st = fbrl_uart_write(f->u, buf, len, &n, 10000);
        f->done += n;
        if (st != FBRL_OK) {
            f->err = st;
            break;
        }
    }
    return NULL;
}

static void *reader(void *arg)
{
    struct flow *f = arg;
    uint8_t buf[4096];
    uint64_t since_pause = 0;
    while (f->done < f->total) {
        size_t n = 0;
        fbrl_status st = fbrl_uart_read(f->u, buf, sizeof buf, &n, 10000);
        if (st != FBRL_OK) {
            f->err = st;
            break;
        }
        for (size_t i = 0; i < n; i++) {
            if (buf[i] != pat(f->done + i, f->seed) && f->bad_at == UINT64_MAX)
                f->bad_at = f->done + i;
        }
        f->done += n;
        since_pause += n;
        if (f->slow && since_pause >= (uint64_t)f->slow * 1024u) {
            since_pause = 0;
            fbrl_clock_sleep_us(2000);
        }
    }
    return NULL;
}

/* 16 MiB each way (about 4 s here). ThreadSanitizer makes every byte's atomics
 * some 10x dearer (16 MiB took 38 s), so a TSan build moves 2 MiB each way by
 * default: the race check needs the interleavings, not the volume.
 * FBRL_PTY_FLOW_MIB overrides both. */
#if defined(__SANITIZE_THREAD__)
#define FLOW_MIB_DEFAULT 2u
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define FLOW_MIB_DEFAULT 2u
#endif
#endif
#ifndef FLOW_MIB_DEFAULT
#define FLOW_MIB_DEFAULT 16u
#endif

static uint64_t flow_bytes(void)
{
    const char *e = getenv("FBRL_PTY_FLOW_MIB");
    return (e != NULL && atoi(e) > 0 ? (uint64_t)atoi(e) : FLOW_MIB_DEFAULT) << 20;
}

/* Both ends are ours: the slave by path, the master fd adopted; each with a service
 * thread. Both directions run at once; both readers are slow. */
static void sixteen_mib_both_ways_with_xonxoff(void **state)
{
    (void)state;
    char name[64];
    int m = make_pty(name, sizeof name);
    fbrl_uart_posix pa, pb;
    fbrl_uart ua, ub;
    fbrl_uart_config cfg = {115200, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_XONXOFF};
    fbrl_uart_posix_options opt = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    opt.service_thread = 1;
    assert_int_equal(fbrl_uart_posix_open(&pa, &ua, name, &cfg, rxa, sizeof rxa, txa, sizeof txa, &opt),
                     FBRL_OK);
    assert_int_equal(fbrl_uart_posix_open_fd(&pb, &ub, m, &cfg, rxb, sizeof rxb, txb, sizeof txb, &opt),
                     FBRL_OK);

    uint64_t total = flow_bytes();
    struct flow wa = {&ua, total, 1, 0, 0, UINT64_MAX, FBRL_OK},
                rb = {&ub, total, 1, 64, 0, UINT64_MAX, FBRL_OK};
    struct flow wb = {&ub, total, 2, 0, 0, UINT64_MAX, FBRL_OK},
                ra = {&ua, total, 2, 64, 0, UINT64_MAX, FBRL_OK};
    pthread_t t[4];
    uint64_t t0 = fbrl_clock_now_us();
    pthread_create(&t[0], NULL, writer, &wa);
    pthread_create(&t[1], NULL, reader, &rb);
    pthread_create(&t[2], NULL, writer, &wb);
    pthread_create(&t[3], NULL, reader, &ra);
    for (int i = 0; i < 4; i++)
        pthread_join(t[i], NULL);
    double secs = (double)(fbrl_clock_now_us() - t0) / 1e6;

    assert_int_equal(wa.err, FBRL_OK);
    assert_int_equal(wb.err, FBRL_OK);
    assert_int_equal(ra.err, FBRL_OK);
    assert_int_equal(rb.err, FBRL_OK);
    assert_true(rb.done == total && ra.done == total);
    if (rb.bad_at != UINT64_MAX || ra.bad_at != UINT64_MAX)
        fail_msg("data wrong at byte %llu (a->b) / %llu (b->a)", (unsigned long long)rb.bad_at,
                 (unsigned long long)ra.bad_at);
    fbrl_uart_counters ca, cb;
    fbrl_uart_get_counters(&ua, &ca);
    fbrl_uart_get_counters(&ub, &cb);
    printf("# %llu bytes each way in %.2f s; a: xoff sent %llu recv %llu held %llu us; "
           "b: xoff sent %llu recv %llu held %llu us\n",
           (unsigned long long)total, secs, (unsigned long long)ca.xoff_sent,
           (unsigned long long)ca.xoff_received, (unsigned long long)ca.held_off_us,
           (unsigned long long)cb.xoff_sent, (unsigned long long)cb.xoff_received,
           (unsigned long long)cb.held_off_us);
    assert_int_equal(ca.rx_bytes, total);
    assert_int_equal(cb.rx_bytes, total);
    assert_int_equal(ca.tx_bytes, total);
    assert_int_equal(ca.overruns + cb.overruns, 0);
    /* The slow readers made their ends send XOFF, and the writers held off. */
    assert_true(ca.xoff_sent > 0 && cb.xoff_sent > 0);
    assert_true(ca.xoff_received > 0 && cb.xoff_received > 0);
    assert_true(ca.held_off_us > 0 && cb.held_off_us > 0);
    assert_int_equal(fbrl_uart_close(&ua), FBRL_OK);
    assert_int_equal(fbrl_uart_close(&ub), FBRL_OK);
}

/* No thread: one thread alternates non-blocking writes and reads on both ends; the
 * service loop runs inside those calls. */
static void polled_mode_moves_data(void **state)
{
    (void)state;
    enum { TOTAL = 1 << 20 };
    char name[64];
    int m = make_pty(name, sizeof name);
    fbrl_uart_posix pa, pb;
    fbrl_uart ua, ub;
    fbrl_uart_config cfg = {9600, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_XONXOFF};
    assert_int_equal(fbrl_uart_posix_open(&pa, &ua, name, &cfg, rxa, 1024, txa, 1024, NULL), FBRL_OK);
    assert_int_equal(fbrl_uart_posix_open_fd(&pb, &ub, m, &cfg, rxb, 1024, txb, 1024, NULL), FBRL_OK);
    uint64_t sent = 0, got = 0;
    uint8_t buf[700];
    for (int rounds = 0; got < TOTAL && rounds < 1000000; rounds++) {
        size_t n = 0;
        if (sent < TOTAL) {
            size_t len = TOTAL - sent < 500 ? (size_t)(TOTAL - sent) : 500;
            for (size_t i = 0; i < len; i++)
                buf[i] = pat(sent + i, 7);
            fbrl_uart_write(&ua, buf, len, &n, 0);
            sent += n;
        }
        /* a slow reader now and then: only every third round */
        if (rounds % 3 == 0 && fbrl_uart_read(&ub, buf, sizeof buf, &n, 1) == FBRL_OK) {
            for (size_t i = 0; i < n; i++)
                if (buf[i] != pat(got + i, 7))
                    fail_msg("byte %llu wrong", (unsigned long long)(got + i));
            got += n;
        }
        fbrl_uart_read(&ua, buf, 0, &n, 0); /* lets a's loop see b's XON/XOFF */
        fbrl_uart_drain(&ua, 0);
    }
    assert_int_equal(got, TOTAL);
    fbrl_uart_counters c;
    fbrl_uart_get_counters(&ub, &c);
    assert_int_equal(c.overruns, 0);
    fbrl_uart_close(&ua);
    fbrl_uart_close(&ub);
}

/* Polled mode: the bytes of a write are in the kernel when the write returns, so an
 * event-driven host that next waits for the fd to become readable is never waiting for
 * its own CR still sitting in the ring (the peer sees the bytes with no further call). */
static void polled_write_reaches_the_peer_within_the_call(void **state)
{
    (void)state;
    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = {9600, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_XONXOFF};
    int m = open_on_pty(&p, &u, &cfg, 256, 0);
    const char msg[] = "SPEED 50\r";
    for (int round = 0; round < 3; round++) {
        size_t n = 0;
        assert_int_equal(fbrl_uart_write(&u, msg, sizeof msg - 1, &n, 0), FBRL_OK);
        assert_int_equal(fbrl_uart_tx_pending(&u), 0);
        struct pollfd f = {m, POLLIN, 0};
        assert_int_equal(poll(&f, 1, 0), 1); /* already there: no wait, no further call */
        char buf[64];
        size_t have = 0;
        while (have < sizeof msg - 1) {
            ssize_t r = read(m, buf + have, sizeof buf - have);
            assert_true(r > 0);
            have += (size_t)r;
        }
        assert_int_equal(have, sizeof msg - 1);
        assert_memory_equal(buf, msg, have);
    }
    fbrl_uart_close(&u);
    close(m);
}

/* The service thread answers flow control while the application is busy: the peer
 * floods, our application does not call anything on its port, yet our end sends
 * XOFF in time and loses nothing. */
static void thread_answers_flow_control_while_app_computes(void **state)
{
    (void)state;
    char name[64];
    int m = make_pty(name, sizeof name);
    fbrl_uart_posix pa, pb;
    fbrl_uart ua, ub;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    fbrl_uart_posix_options threaded = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    threaded.service_thread = 1;
    assert_int_equal(fbrl_uart_posix_open(&pa, &ua, name, &cfg, rxa, 256, txa, 256, &threaded), FBRL_OK);
    assert_int_equal(fbrl_uart_posix_open_fd(&pb, &ub, m, &cfg, rxb, 4096, txb, 4096, &threaded), FBRL_OK);
    enum { FLOOD = 300000 }; /* well beyond what the pty's kernel buffers hold (~26 KB) */
    struct flow wb = {&ub, FLOOD, 5, 0, 0, UINT64_MAX, FBRL_OK};
    pthread_t t;
    pthread_create(&t, NULL, writer, &wb);
    /* "Computing": no call on ua at all, for 300 ms and then (on a loaded machine)
     * until the flood has met the XOFF, at most 10 s. */
    fbrl_uart_counters ca, cb;
    fbrl_clock_sleep_us(300000);
    for (int i = 0; i < 1000; i++) {
        fbrl_uart_get_counters(&ua, &ca);
        if (ca.xoff_sent >= 1 && fbrl_uart_peer_stopped(&ub))
            break;
        fbrl_clock_sleep_us(10000);
    }
    fbrl_uart_get_counters(&ub, &cb);
    assert_true(ca.xoff_sent >= 1);
    assert_int_equal(ca.overruns, 0);
    assert_true(fbrl_uart_rx_available(&ua) <= 256);
    assert_int_equal(fbrl_uart_peer_stopped(&ub), 1);
    assert_true(cb.tx_bytes < FLOOD);
    struct flow ra = {&ua, FLOOD, 5, 0, 0, UINT64_MAX, FBRL_OK};
    reader(&ra);
    pthread_join(t, NULL);
    assert_int_equal(ra.err, FBRL_OK);
    assert_int_equal(ra.done, FLOOD);
    assert_true(ra.bad_at == UINT64_MAX);
    fbrl_uart_close(&ua);
    fbrl_uart_close(&ub);
}

/* Timeouts hold in both modes: an idle read returns FBRL_ETIMEOUT no earlier than
 * asked and (generously) not much later. */
static void idle_read_times_out(void **state)
{
    (void)state;
    for (int threaded = 0; threaded < 2; threaded++) {
        fbrl_uart_posix p;
        fbrl_uart u;
        fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
        int m = open_on_pty(&p, &u, &cfg, 64, threaded);
        uint8_t b;
        size_t n;
        uint64_t t0 = fbrl_clock_now_us();
        assert_int_equal(fbrl_uart_read(&u, &b, 1, &n, 0), FBRL_ETIMEOUT);
        assert_int_equal(fbrl_uart_read(&u, &b, 1, &n, 150), FBRL_ETIMEOUT);
        uint64_t dt = fbrl_clock_now_us() - t0;
        assert_true(dt >= 150000u);
        assert_true(dt < 3000000u);
        /* A byte from the far end ends the wait early. */
        assert_int_equal(write(m, "Z", 1), 1);
        assert_int_equal(fbrl_uart_read(&u, &b, 1, &n, 5000), FBRL_OK);
        assert_int_equal(b, 'Z');
        fbrl_uart_close(&u);
        close(m);
    }
}

/* Read what the peer wrote until `want` bytes came (or 2 s). */
static size_t read_all(fbrl_uart *u, uint8_t *buf, size_t cap, size_t want)
{
    size_t got = 0;
    uint64_t end = fbrl_clock_now_us() + 2000000u;
    while (got < want && got < cap && fbrl_clock_now_us() < end) {
        size_t n = 0;
        fbrl_uart_read(u, buf + got, cap - got, &n, 50);
        got += n;
    }
    return got;
}

/* With parity, bytes come in the PARMRK format (on a pty the peer writes it, as
 * fbrlsim --parity does): 0xFF 0x00 X is a parity error, counted, X dropped; 0xFF 0xFF
 * is one data byte 0xFF; a mark split across writes (and reads) is still one mark.
 * Without parity every byte is data. Polled and thread mode. */
static void parity_marks_are_parsed(void **state)
{
    (void)state;
    for (int threaded = 0; threaded < 2; threaded++) {
        fbrl_uart_posix p;
        fbrl_uart u;
        fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
        cfg.flow = FBRL_FLOW_NONE;
        cfg.parity = threaded ? FBRL_PARITY_ODD : FBRL_PARITY_EVEN;
        int m = open_on_pty(&p, &u, &cfg, 256, threaded);
        struct termios t;
        assert_int_equal(tcgetattr(fbrl_uart_posix_fd(&p), &t), 0);
        assert_true(t.c_iflag & INPCK);
        assert_int_equal(t.c_iflag & (PARMRK | IGNPAR), 0); /* a pty would double 0xFF */
        static const uint8_t in[] = {'A', 0xFF, 0x00, 'Q', 'B', 0xFF, 0xFF, 'C', 0xFF, 0x00, 0xFF, 'D'};
        static const uint8_t want[] = {'A', 'B', 0xFF, 'C', 'D'};
        assert_int_equal(write(m, in, sizeof in), (ssize_t)sizeof in);
        uint8_t buf[64];
        size_t got = read_all(&u, buf, sizeof buf, sizeof want);
        assert_int_equal(got, sizeof want);
        assert_memory_equal(buf, want, sizeof want);
        /* split marks: 0xFF | 0x00 | X, and 0xFF | 0xFF, each written separately */
        static const uint8_t parts[][2] = {{'E', 0xFF}, {0x00, 0}, {'R', 'F'}, {0xFF, 0}, {0xFF, 'G'}};
        static const size_t plen[] = {2, 1, 2, 1, 2};
        got = 0;
        for (size_t k = 0; k < 5; k++) {
            assert_int_equal(write(m, parts[k], plen[k]), (ssize_t)plen[k]);
            usleep(20000);
            size_t n = 0;
            fbrl_uart_read(&u, buf + got, sizeof buf - got, &n, 20); /* each part read on its own */
            got += n;
        }
        static const uint8_t want2[] = {'E', 'F', 0xFF, 'G'};
        got += read_all(&u, buf + got, sizeof buf - got, sizeof want2 - got);
        assert_int_equal(got, sizeof want2);
        assert_memory_equal(buf, want2, sizeof want2);
        fbrl_uart_counters c;
        assert_int_equal(fbrl_uart_get_counters(&u, &c), FBRL_OK);
        assert_int_equal(c.parity_errors, 3);
        /* parity off: 0xFF and 0x00 are data */
        cfg.parity = FBRL_PARITY_NONE;
        assert_int_equal(fbrl_uart_configure(&u, &cfg), FBRL_OK);
        assert_int_equal(write(m, in, 4), 4);
        got = read_all(&u, buf, sizeof buf, 4);
        assert_int_equal(got, 4);
        assert_memory_equal(buf, in, 4);
        assert_int_equal(fbrl_uart_get_counters(&u, &c), FBRL_OK);
        assert_int_equal(c.parity_errors, 3);
        fbrl_uart_close(&u);
        close(m);
    }
}

/* The master side goes away: reads and writes on the slave end report
 * FBRL_EDISCONNECTED (after any bytes that came first), within their timeouts. */
static void peer_gone_is_disconnected(void **state)
{
    (void)state;
    for (int threaded = 0; threaded < 2; threaded++) {
        fbrl_uart_posix p;
        fbrl_uart u;
        fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
        int m = open_on_pty(&p, &u, &cfg, 64, threaded);
        assert_int_equal(write(m, "bye", 3), 3);
        uint8_t buf[8];
        size_t n = 0, got = 0;
        while (got < 3 && fbrl_uart_read(&u, buf + got, sizeof buf - got, &n, 2000) == FBRL_OK)
            got += n;
        assert_int_equal(got, 3);
        assert_memory_equal(buf, "bye", 3);
        close(m);
        uint64_t t0 = fbrl_clock_now_us();
        assert_int_equal(fbrl_uart_read(&u, buf, sizeof buf, &n, 2000), FBRL_EDISCONNECTED);
        assert_true(fbrl_clock_now_us() - t0 < 2000000u);
        /* Polled, the write hands its byte to the kernel at once and reports; with the
         * thread, a write that fits is only queued and the drain that waits for it
         * reports. */
        if (threaded) {
            assert_int_equal(fbrl_uart_write(&u, "x", 1, &n, 100), FBRL_OK);
            assert_int_equal(fbrl_uart_drain(&u, 500), FBRL_EDISCONNECTED);
        } else {
            assert_int_equal(fbrl_uart_write(&u, "x", 1, &n, 100), FBRL_EDISCONNECTED);
        }
        assert_int_equal(fbrl_uart_close(&u), FBRL_OK);
    }
    /* And the other way: the slave closes under an adopted master. */
    char name[64];
    int m = make_pty(name, sizeof name);
    int s = open(name, O_RDWR | O_NOCTTY);
    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    assert_int_equal(fbrl_uart_posix_open_fd(&p, &u, m, &cfg, rxa, 64, txa, 64, NULL), FBRL_OK);
    close(s);
    uint8_t b;
    size_t n;
    assert_int_equal(fbrl_uart_read(&u, &b, 1, &n, 2000), FBRL_EDISCONNECTED);
    fbrl_uart_close(&u);
}

/* ---- TCP against a listener on 127.0.0.1 made here ---- */

static int listener(uint16_t *port)
{
    int l = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a;
    socklen_t al = sizeof a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    assert_int_equal(bind(l, (struct sockaddr *)&a, sizeof a), 0);
    assert_int_equal(listen(l, 1), 0);
    assert_int_equal(getsockname(l, (struct sockaddr *)&a, &al), 0);
    *port = ntohs(a.sin_port);
    return l;
}

static void tcp_serial_server(void **state)
{
    (void)state;
    uint16_t port;
    int l = listener(&port);
    char path[64];
    snprintf(path, sizeof path, "tcp:127.0.0.1:%u", (unsigned)port);
    fbrl_uart_posix p;
    fbrl_uart u;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    assert_int_equal(fbrl_uart_posix_open(&p, &u, path, &cfg, rxa, sizeof rxa, txa, sizeof txa, NULL),
                     FBRL_OK);
    int s = accept(l, NULL, NULL);
    assert_true(s >= 0);

    size_t n;
    assert_int_equal(fbrl_uart_write(&u, "W2\r", 3, &n, 1000), FBRL_OK);
    assert_int_equal(fbrl_uart_drain(&u, 1000), FBRL_OK);
    char buf[16];
    size_t got = 0;
    while (got < 3) {
        ssize_t r = recv(s, buf + got, sizeof buf - got, 0);
        assert_true(r > 0);
        got += (size_t)r;
    }
    assert_memory_equal(buf, "W2\r", 3);
    assert_int_equal(send(s, "\r\n>>", 4, 0), 4);
    got = 0;
    while (got < 4 && fbrl_uart_read(&u, buf + got, sizeof buf - got, &n, 2000) == FBRL_OK)
        got += n;
    assert_memory_equal(buf, "\r\n>>", 4);
    /* XON/XOFF work over TCP too: the server's XOFF holds our output. */
    assert_int_equal(send(s, "\x13", 1, 0), 1);
    for (int i = 0; i < 200 && !fbrl_uart_peer_stopped(&u); i++)
        fbrl_uart_read(&u, buf, sizeof buf, &n, 5);
    assert_int_equal(fbrl_uart_peer_stopped(&u), 1);
    assert_int_equal(fbrl_uart_write(&u, "HOLD", 4, &n, 0), FBRL_OK);
    assert_int_equal(fbrl_uart_drain(&u, 100), FBRL_ETIMEOUT);
    assert_int_equal(send(s, "\x11", 1, 0), 1);
    assert_int_equal(fbrl_uart_drain(&u, 2000), FBRL_OK);

    /* The server resets the connection: FBRL_EDISCONNECTED. */
    struct linger lg = {1, 0};
    setsockopt(s, SOL_SOCKET, SO_LINGER, &lg, sizeof lg);
    close(s);
    fbrl_status st = FBRL_OK;
    for (int i = 0; i < 100 && st == FBRL_OK; i++)
        st = fbrl_uart_read(&u, buf, sizeof buf, &n, 50);
    assert_int_equal(st, FBRL_EDISCONNECTED);
    fbrl_uart_close(&u);

    /* Nobody listening: refused. */
    close(l);
    assert_int_equal(fbrl_uart_posix_open(&p, &u, path, &cfg, rxa, 64, txa, 64, NULL), FBRL_EIO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(open_errors),
        cmocka_unit_test(busy_across_processes),
        cmocka_unit_test(every_setting_is_applied),
        cmocka_unit_test(settings_restored_on_close),
        cmocka_unit_test(sixteen_mib_both_ways_with_xonxoff),
        cmocka_unit_test(polled_mode_moves_data),
        cmocka_unit_test(polled_write_reaches_the_peer_within_the_call),
        cmocka_unit_test(thread_answers_flow_control_while_app_computes),
        cmocka_unit_test(idle_read_times_out),
        cmocka_unit_test(peer_gone_is_disconnected),
        cmocka_unit_test(parity_marks_are_parsed),
        cmocka_unit_test(tcp_serial_server),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
