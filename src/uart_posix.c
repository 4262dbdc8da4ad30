/* SPDX-License-Identifier: MIT */
/* uart_posix.c - POSIX termios/pty/TCP backend for the UART core (fbrl/uart_posix.h).
 *
 * One "round" of the service loop does what the thesis's COM interrupt routine did:
 * wait for the line (poll), hand received bytes to fbrl_uart_isr_rx(), and feed the
 * transmitter from fbrl_uart_isr_tx(). The round runs inside the core's waits
 * (polled mode) or in a background thread (thread mode). */
#define _DEFAULT_SOURCE 1 /* B57600.. speeds, flock, TIOCEXCL, major() */
#ifdef __linux__
#define _GNU_SOURCE 1 /* ppoll: waits in microseconds */
#endif
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <netdb.h>
#include <poll.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#ifdef __linux__
#include <linux/serial.h>
#endif
#include "fbrl/uart_posix.h"
#include "fbrl/clock.h"
#include "atomic.h"

#define SPEED(n)   \
    {              \
        n##u, B##n \
    }
static const struct {
    uint32_t baud;
    speed_t speed;
} speeds[] = {
    SPEED(50),      SPEED(75),   SPEED(110),  SPEED(134),   SPEED(150),
    SPEED(200),     SPEED(300),  SPEED(600),  SPEED(1200),  SPEED(1800),
    SPEED(2400),    SPEED(4800), SPEED(9600), SPEED(19200), SPEED(38400),
#ifdef B57600
    SPEED(57600),
#endif
#ifdef B115200
    SPEED(115200),
#endif
#ifdef B230400
    SPEED(230400),
#endif
#ifdef B460800
    SPEED(460800),
#endif
#ifdef B500000
    SPEED(500000),
#endif
#ifdef B576000
    SPEED(576000),
#endif
#ifdef B921600
    SPEED(921600),
#endif
#ifdef B1000000
    SPEED(1000000),
#endif
#ifdef B1152000
    SPEED(1152000),
#endif
#ifdef B1500000
    SPEED(1500000),
#endif
#ifdef B2000000
    SPEED(2000000),
#endif
#ifdef B2500000
    SPEED(2500000),
#endif
#ifdef B3000000
    SPEED(3000000),
#endif
#ifdef B3500000
    SPEED(3500000),
#endif
#ifdef B4000000
    SPEED(4000000),
#endif
};

fbrl_status fbrl_uart_posix_speed(uint32_t baud, speed_t *speed)
{
    if (speed == NULL)
        return FBRL_EINVAL;
    for (size_t i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
        if (speeds[i].baud == baud) {
            *speed = speeds[i].speed;
            return FBRL_OK;
        }
    }
    return FBRL_EUNSUPPORTED;
}

int fbrl_uart_posix_fd(const fbrl_uart_posix *p) { return p == NULL ? -1 : p->fd; }

/* ---- the line: termios ---- */

/* Raw mode with cfg's framing: no echo, no editing, no CR/LF mapping, no kernel
 * XON/XOFF (the core runs flow control), reads return as soon as one byte is there.
 * With parity, INPCK|PARMRK: the driver delivers a byte received with an error as
 * 0xFF 0x00 byte and a data byte 0xFF as 0xFF 0xFF (parse_marked() reads that). On a
 * pty (no wire, no parity) PARMRK is left off, because the pty's line discipline
 * would double every 0xFF its peer writes: there the peer (fbrlsim --parity) writes
 * the marked format itself, exactly as a real port's driver would deliver it. */
static void make_raw(struct termios *t, const fbrl_uart_config *cfg, int is_pty)
{
    t->c_iflag &= ~(tcflag_t)(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON | IXOFF |
                              IXANY | INPCK | IGNPAR);
    if (cfg->parity != FBRL_PARITY_NONE)
        t->c_iflag |= INPCK | (is_pty ? 0 : PARMRK);
    t->c_oflag &= ~(tcflag_t)OPOST;
    t->c_lflag &= ~(tcflag_t)(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    t->c_cflag &= ~(tcflag_t)(CSIZE | PARENB | PARODD | CSTOPB);
#ifdef CRTSCTS
    t->c_cflag &= ~(tcflag_t)CRTSCTS;
#endif
    t->c_cflag |= CLOCAL | CREAD;
    static const tcflag_t sizes[] = {CS5, CS6, CS7, CS8};
    t->c_cflag |= sizes[cfg->data_bits - 5];
    if (cfg->parity != FBRL_PARITY_NONE)
        t->c_cflag |= PARENB | (cfg->parity == FBRL_PARITY_ODD ? PARODD : 0);
    if (cfg->stop_bits == 2)
        t->c_cflag |= CSTOPB;
    t->c_cc[VMIN] = 1; /* with O_NONBLOCK: no data gives EAGAIN, and 0 means hang-up */
    t->c_cc[VTIME] = 0;
}

static fbrl_status px_configure(void *ctx, const fbrl_uart_config *cfg)
{
    fbrl_uart_posix *p = ctx;
    speed_t sp;
    if (!p->is_tty) { /* TCP: the serial server owns the line; record the rate */
        p->baud = cfg->baud;
        return FBRL_OK;
    }
    fbrl_status st = fbrl_uart_posix_speed(cfg->baud, &sp);
    if (st != FBRL_OK)
        return st;
    struct termios t = p->raw, r;
    make_raw(&t, cfg, p->is_pty);
    if (cfsetispeed(&t, sp) != 0 || cfsetospeed(&t, sp) != 0)
        return FBRL_EUNSUPPORTED;
    if (tcsetattr(p->fd, TCSANOW, &t) != 0)
        return errno == EINVAL ? FBRL_EUNSUPPORTED : FBRL_EIO;
    /* tcsetattr succeeds if any part was applied: read back and compare. A Linux pty
     * always forces CS8 and no parity (it has no wire), so those two are not held
     * against a pty. */
    if (tcgetattr(p->fd, &r) != 0)
        return FBRL_EIO;
    tcflag_t must = CSTOPB | (cfg->parity != FBRL_PARITY_NONE ? PARODD : 0);
    if (!p->is_pty)
        must |= CSIZE | PARENB;
    if (cfgetospeed(&r) != sp || cfgetispeed(&r) != sp || (r.c_cflag & must) != (t.c_cflag & must)) {
        tcsetattr(p->fd, TCSANOW, &p->raw); /* back to the last good settings */
        return FBRL_EUNSUPPORTED;
    }
    p->raw = t;
    p->baud = cfg->baud;
    /* read by the service thread; the parse state is its own */
    fbrl_store_rel(&p->marked, cfg->parity != FBRL_PARITY_NONE && p->is_tty);
    /* About 10 ms of line time may wait in the kernel: enough to keep the line busy,
     * little enough that the peer's XOFF takes effect at once. */
    p->outq_limit = cfg->baud / 1000u < 16u ? 16u : cfg->baud / 1000u;
    return FBRL_OK;
}

/* ---- the service round ---- */

static void px_kick(void *ctx)
{
    fbrl_uart_posix *p = ctx;
    fbrl_store_rel(&p->kick, 1);
    if (p->threaded) {
        char c = 1;
        ssize_t n = write(p->wake[1], &c, 1); /* a full pipe already wakes the thread */
        (void)n;
    }
}

static fbrl_status io_error(int e)
{
    switch (e) {
    case EIO:
    case EPIPE:
    case ECONNRESET:
    case ENXIO:
    case ENOTCONN:
    case ESHUTDOWN:
    case ETIMEDOUT: return FBRL_EDISCONNECTED;
    default: return FBRL_EIO;
    }
}

/* Line errors counted by a real serial driver, passed on as line-status calls. */
static void poll_line_errors(fbrl_uart_posix *p)
{
#if defined(__linux__) && defined(TIOCGICOUNT)
    struct serial_icounter_struct ic;
    if (!p->icount_ok || ioctl(p->fd, TIOCGICOUNT, &ic) != 0)
        return;
    for (; p->ic_frame != (uint32_t)ic.frame; p->ic_frame++)
        fbrl_uart_isr_line_status(p->u, FBRL_UART_LS_FRAMING);
    /* with marks, each mark is the report (Linux marks framing and parity errors alike) */
    if (fbrl_load_acq(&p->marked)) {
        p->ic_frame = (uint32_t)ic.frame;
        p->ic_parity = (uint32_t)ic.parity;
    }
    for (; p->ic_parity != (uint32_t)ic.parity; p->ic_parity++)
        fbrl_uart_isr_line_status(p->u, FBRL_UART_LS_PARITY);
    uint32_t over = (uint32_t)ic.overrun + (uint32_t)ic.buf_overrun;
    for (; p->ic_overrun != over; p->ic_overrun++)
        fbrl_uart_isr_line_status(p->u, FBRL_UART_LS_OVERRUN);
#else
    (void)p;
#endif
}

/* The PARMRK format: 0xFF 0x00 X = X arrived with a parity (or framing) error: it is
 * reported and dropped, as a UART's firmware drops it; 0xFF 0xFF = a data byte 0xFF.
 * The state carries over between reads (a mark may be split). */
static void parse_marked(fbrl_uart_posix *p, uint8_t b)
{
    switch (p->mark_state) {
    case 1:
        p->mark_state = b == 0x00 ? 2 : 0;
        if (b == 0x00)
            return;
        fbrl_uart_isr_rx(p->u, 0xFF);
        if (b != 0xFF)
            fbrl_uart_isr_rx(p->u, b); /* not a mark (a driver never sends this): keep both */
        return;
    case 2:
        p->mark_state = 0;
        fbrl_uart_isr_line_status(p->u, FBRL_UART_LS_PARITY);
        return;
    default:
        if (b == 0xFF)
            p->mark_state = 1;
        else
            fbrl_uart_isr_rx(p->u, b);
        return;
    }
}

static fbrl_status do_read(fbrl_uart_posix *p, short revents, size_t *moved)
{
    uint8_t buf[4096];
    size_t room = fbrl_uart_rx_room(p->u);
    if (room == 0) /* the reader is slow: leave the bytes in the kernel */
        return (revents & POLLIN) ? FBRL_OK : FBRL_EDISCONNECTED;
    ssize_t n = p->is_socket ? recv(p->fd, buf, room < sizeof buf ? room : sizeof buf, 0)
                             : read(p->fd, buf, room < sizeof buf ? room : sizeof buf);
    if (n > 0) {
        size_t marked = fbrl_load_acq(&p->marked);
        if (!marked)
            p->mark_state = 0;
        for (ssize_t i = 0; i < n; i++) {
            if (marked)
                parse_marked(p, buf[i]);
            else
                fbrl_uart_isr_rx(p->u, buf[i]);
        }
        *moved += (size_t)n;
        poll_line_errors(p);
        return FBRL_OK;
    }
    if (n == 0)
        return FBRL_EDISCONNECTED; /* EOF: socket closed, or tty hung up */
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
        /* POLLHUP with nothing to read: a pty master whose slave side is closed */
        return (revents & (POLLHUP | POLLERR)) && !(revents & POLLIN) ? FBRL_EDISCONNECTED : FBRL_OK;
    return io_error(errno);
}

/* Bytes the kernel may still take without passing the XOFF-latency bound. */
static size_t kernel_room(fbrl_uart_posix *p)
{
    int q = 0;
    if (!p->is_tty || p->outq_limit == 0)
        return p->chunk;
    if (p->is_pty) /* its TIOCOUTQ is always 0: the bound alone, without a syscall per write */
        return p->outq_limit;
    if (ioctl(p->fd, TIOCOUTQ, &q) != 0 || q < 0)
        return p->chunk;
    return (size_t)q >= p->outq_limit ? 0 : p->outq_limit - (size_t)q;
}

/* Feed the transmitter: take bytes from isr_tx into the stage (our "FIFO") and write
 * them; at most four chunks per round so incoming XOFF is looked at often. */
static fbrl_status do_write(fbrl_uart_posix *p, size_t *moved)
{
    for (int chunks = 0; chunks < 4; chunks++) {
        if (p->stage_off == p->stage_len && chunks > 0 && !fbrl_load_acq(&p->kick))
            return FBRL_OK; /* all written, nothing more announced: no second look at the queue */
        if (p->stage_off == p->stage_len) {
            size_t limit = kernel_room(p);
            int c = 0;
            p->stage_off = p->stage_len = 0;
            if (limit > p->chunk)
                limit = p->chunk;
            while (p->stage_len < limit && (c = fbrl_uart_isr_tx(p->u)) >= 0)
                p->stage[p->stage_len++] = (uint8_t)c;
            if (c < 0)
                fbrl_store_rel(&p->kick, 0); /* nothing more until the next kick */
            *moved += p->stage_len;
            if (p->stage_len == 0)
                return FBRL_OK;
        }
        size_t len = p->stage_len - p->stage_off;
        ssize_t n = p->is_socket ? send(p->fd, p->stage + p->stage_off, len, MSG_NOSIGNAL)
                                 : write(p->fd, p->stage + p->stage_off, len);
        if (n < 0)
            return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? FBRL_OK : io_error(errno);
        p->stage_off += (size_t)n;
        if (p->stage_off < p->stage_len)
            return FBRL_OK; /* the kernel is full: wait for POLLOUT */
    }
    return FBRL_OK;
}

/* One round: wait up to timeout_ms (-1: no limit) for the line, then move bytes.
 * *moved counts bytes handed to or taken from the core. */
static fbrl_status service_round(fbrl_uart_posix *p, int timeout_ms, size_t *moved)
{
    struct pollfd f[2];
    nfds_t nf = 1;
    *moved = 0;
    bool room = fbrl_uart_rx_room(p->u) > 0;
    bool out = p->stage_off < p->stage_len || fbrl_load_acq(&p->kick);
    bool deferred = out && p->stage_off == p->stage_len && kernel_room(p) == 0;
    f[0].fd = p->fd;
    f[0].events = (short)((room ? POLLIN : 0) | (out && !deferred ? POLLOUT : 0));
    f[0].revents = 0;
    if (p->threaded) {
        f[1].fd = p->wake[0];
        f[1].events = POLLIN;
        f[1].revents = 0;
        nf = 2;
    }
    /* A full ring or kernel queue frees up without an fd event: look again soon. */
    if ((!room || deferred) && (timeout_ms < 0 || timeout_ms > 2))
        timeout_ms = 2;
    int rc = poll(f, nf, timeout_ms);
    if (rc < 0)
        return errno == EINTR ? FBRL_OK : FBRL_EIO;
    if (nf == 2 && (f[1].revents & POLLIN)) {
        char junk[64];
        while (read(p->wake[0], junk, sizeof junk) > 0)
            ;
        fbrl_store_rel(&p->kick, 1);
    }
    fbrl_status st = FBRL_OK;
    if (f[0].revents & (POLLIN | POLLHUP | POLLERR))
        st = do_read(p, f[0].revents, moved);
    /* Write after reading: an XOFF that just came in holds the data back. */
    if (st == FBRL_OK && (p->stage_off < p->stage_len || fbrl_load_acq(&p->kick)) &&
        (f[0].revents & POLLOUT || (rc > 0 && !deferred)))
        st = do_write(p, moved);
    return st;
}

/* poll() with a microsecond timeout where the system has one (ppoll), else rounded up to
 * milliseconds. */
static int poll_us(struct pollfd *f, nfds_t nf, uint32_t timeout_us)
{
#ifdef __linux__
    struct timespec ts = {(time_t)(timeout_us / 1000000u), (long)(timeout_us % 1000000u) * 1000L};
    return ppoll(f, nf, &ts, NULL);
#else
    uint32_t ms = timeout_us / 1000u + (timeout_us % 1000u != 0);
    return poll(f, nf, ms > INT_MAX ? INT_MAX : (int)ms);
#endif
}

/* Many polled ports in one poll(): what service_round does for one, for each that is
 * ready. A port with a service thread belongs to its thread: FBRL_EUNSUPPORTED. */
static fbrl_status px_wait_many(fbrl_uart *const *ports, size_t n, uint32_t timeout_us, unsigned char *flags)
{
    struct pollfd f[FBRL_UART_WAIT_MAX];
    for (size_t k = 0; k < n; k++) {
        fbrl_uart_posix *p = ports[k]->ctx;
        if (p->threaded)
            return FBRL_EUNSUPPORTED;
        bool room = fbrl_uart_rx_room(p->u) > 0;
        bool out = p->stage_off < p->stage_len || fbrl_load_acq(&p->kick);
        bool deferred = out && p->stage_off == p->stage_len && kernel_room(p) == 0;
        f[k].events =
            (short)((room && (flags[k] & FBRL_UART_WAIT_RX) ? POLLIN : 0) | (out && !deferred ? POLLOUT : 0));
        f[k].fd = f[k].events ? p->fd : -1; /* poll() skips it: a port not watched costs nothing */
        f[k].revents = 0;
        /* a full ring or kernel queue frees up without an fd event: look again soon */
        if ((!room || deferred) && timeout_us > 2000u)
            timeout_us = 2000u;
    }
    int rc = poll_us(f, (nfds_t)n, timeout_us);
    if (rc < 0)
        return errno == EINTR ? FBRL_OK : FBRL_EIO;
    for (size_t k = 0; k < n && rc > 0; k++) {
        fbrl_uart_posix *p = ports[k]->ctx;
        size_t moved = 0;
        fbrl_status st = FBRL_OK;
        if (f[k].revents == 0)
            continue;
        if (f[k].revents & (POLLIN | POLLHUP | POLLERR | POLLNVAL))
            st = do_read(p, f[k].revents, &moved);
        if (st == FBRL_OK && (f[k].revents & POLLOUT))
            st = do_write(p, &moved);
        if (st != FBRL_OK || fbrl_uart_rx_available(p->u) > 0)
            flags[k] |= FBRL_UART_WAIT_READY;
    }
    return FBRL_OK;
}

static void *service_thread(void *arg)
{
    fbrl_uart_posix *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        int stop = p->stop;
        pthread_mutex_unlock(&p->mu);
        if (stop)
            break;
        size_t moved = 0;
        fbrl_status st = service_round(p, 1000, &moved);
        if (st != FBRL_OK || moved > 0) {
            pthread_mutex_lock(&p->mu);
            p->seq++;
            if (st != FBRL_OK && p->thread_status == FBRL_OK)
                p->thread_status = st;
            pthread_cond_broadcast(&p->cv);
            pthread_mutex_unlock(&p->mu);
        }
        if (st != FBRL_OK)
            break;
    }
    return NULL;
}

static fbrl_status px_service(void *ctx, uint32_t timeout_us)
{
    fbrl_uart_posix *p = ctx;
    if (!p->threaded) {
        size_t moved = 0;
        uint32_t ms = timeout_us / 1000u + (timeout_us % 1000u != 0);
        fbrl_status st = service_round(p, ms > INT_MAX ? INT_MAX : (int)ms, &moved);
        if (st != FBRL_OK)
            return st;
        return moved > 0 ? FBRL_OK : FBRL_ETIMEOUT;
    }
    /* Thread mode: wait until the thread made progress since the last look. The
     * wait is cut into 10 ms slices so that a reader and a writer thread sharing
     * 'seen' can never sleep through each other's wake-up for long. */
    pthread_mutex_lock(&p->mu);
    if (p->seq == p->seen && p->thread_status == FBRL_OK && timeout_us > 0) {
        uint32_t slice = timeout_us < 10000u ? timeout_us : 10000u;
        struct timespec until;
        clock_gettime(CLOCK_MONOTONIC, &until);
        long ns = until.tv_nsec + (long)slice * 1000L;
        until.tv_sec += ns / 1000000000L;
        until.tv_nsec = ns % 1000000000L;
        while (p->seq == p->seen && p->thread_status == FBRL_OK)
            if (pthread_cond_timedwait(&p->cv, &p->mu, &until) == ETIMEDOUT)
                break;
    }
    bool changed = p->seq != p->seen;
    p->seen = p->seq;
    fbrl_status st = p->thread_status;
    pthread_mutex_unlock(&p->mu);
    return st != FBRL_OK ? st : changed ? FBRL_OK : FBRL_ETIMEOUT;
}

static uint64_t px_now(void *ctx)
{
    (void)ctx;
    return fbrl_clock_now_us();
}

/* Undo what open did, in reverse order; safe on a partly opened port. */
static void release(fbrl_uart_posix *p)
{
    if (p->thread_started) {
        pthread_mutex_lock(&p->mu);
        p->stop = 1;
        pthread_mutex_unlock(&p->mu);
        px_kick(p);
        pthread_join(p->thread, NULL);
        p->thread_started = 0;
    }
    /* Bytes already taken from the core get up to 100 ms to leave. */
    for (int tries = 0; tries < 50 && p->stage_off < p->stage_len; tries++) {
        struct pollfd f = {p->fd, POLLOUT, 0};
        if (poll(&f, 1, 2) < 0 || (f.revents & (POLLERR | POLLHUP)))
            break;
        ssize_t n = p->is_socket
                        ? send(p->fd, p->stage + p->stage_off, p->stage_len - p->stage_off, MSG_NOSIGNAL)
                        : write(p->fd, p->stage + p->stage_off, p->stage_len - p->stage_off);
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
            break;
        if (n > 0)
            p->stage_off += (size_t)n;
    }
    if (p->saved_valid)
        tcsetattr(p->fd, TCSANOW, &p->saved);
    if (p->locked) {
        ioctl(p->fd, TIOCNXCL);
        flock(p->fd, LOCK_UN);
    }
    if (p->fd >= 0)
        close(p->fd);
    p->fd = -1;
    if (p->threaded) {
        close(p->wake[0]);
        close(p->wake[1]);
        pthread_cond_destroy(&p->cv);
        pthread_mutex_destroy(&p->mu);
        p->threaded = 0;
    }
}

static fbrl_status px_close(void *ctx)
{
    release(ctx);
    return FBRL_OK;
}

/* Polled mode: the bytes just queued go to the kernel inside fbrl_uart_write, so a
 * host that waits for the fd to become readable (an event loop) never waits for a CR
 * still in our ring. Thread mode: the thread writes them once tx_kick woke it. */
static fbrl_status px_flush(void *ctx)
{
    fbrl_uart_posix *p = ctx;
    size_t moved = 0;
    if (!p->threaded && (p->stage_off < p->stage_len || fbrl_load_acq(&p->kick)))
        return do_write(p, &moved);
    return FBRL_OK;
}

static const fbrl_uart_ops posix_ops = {px_configure, px_kick,  px_service,  px_now,
                                        px_close,     px_flush, px_wait_many};

/* ---- opening ---- */

static fbrl_status set_nonblock(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) < 0)
        return FBRL_EIO;
    fcntl(fd, F_SETFD, FD_CLOEXEC);
    return FBRL_OK;
}

static fbrl_status init_thread_sync(fbrl_uart_posix *p)
{
    pthread_condattr_t ca;
    if (pipe(p->wake) != 0)
        return FBRL_EIO;
    if (set_nonblock(p->wake[0]) != FBRL_OK || set_nonblock(p->wake[1]) != FBRL_OK) {
        close(p->wake[0]);
        close(p->wake[1]);
        return FBRL_EIO;
    }
    pthread_mutex_init(&p->mu, NULL);
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC); /* timeouts immune to clock changes */
    pthread_cond_init(&p->cv, &ca);
    pthread_condattr_destroy(&ca);
    p->threaded = 1;
    return FBRL_OK;
}

/* Common part of both opens: fd is ours (closed on failure); locked says whether
 * flock/TIOCEXCL were taken. */
static fbrl_status start(fbrl_uart_posix *p, fbrl_uart *u, int fd, int locked, const fbrl_uart_config *cfg,
                         void *rx, size_t rx_size, void *tx, size_t tx_size,
                         const fbrl_uart_posix_options *opt)
{
    static const fbrl_uart_posix_options defaults = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    struct stat sb;
    if (opt == NULL)
        opt = &defaults;
    memset(p, 0, sizeof *p);
    p->u = u;
    p->fd = fd;
    p->wake[0] = p->wake[1] = -1;
    p->locked = locked;
    p->chunk = opt->tx_chunk == 0                      ? 256
               : opt->tx_chunk > FBRL_UART_POSIX_STAGE ? FBRL_UART_POSIX_STAGE
                                                       : opt->tx_chunk;
    fbrl_status st = FBRL_OK;
    if (fstat(fd, &sb) != 0) {
        st = FBRL_EIO;
    } else if (S_ISSOCK(sb.st_mode)) {
        int one = 1;
        p->is_socket = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one); /* fails harmlessly on AF_UNIX */
    } else if (isatty(fd) && tcgetattr(fd, &p->saved) == 0) {
        p->is_tty = 1;
        p->saved_valid = 1;
        p->raw = p->saved;
        /* Unix98 pty slaves are majors 136-143; /dev/ptmx masters are 5:2. */
        unsigned maj = major(sb.st_rdev), min = minor(sb.st_rdev);
        p->is_pty = (maj >= 136 && maj <= 143) || (maj == 5 && min == 2);
#if defined(__linux__) && defined(TIOCGICOUNT)
        struct serial_icounter_struct ic;
        if (ioctl(fd, TIOCGICOUNT, &ic) == 0) {
            p->icount_ok = 1;
            p->ic_frame = (uint32_t)ic.frame;
            p->ic_parity = (uint32_t)ic.parity;
            p->ic_overrun = (uint32_t)ic.overrun + (uint32_t)ic.buf_overrun;
        }
#endif
    } else {
        st = FBRL_ENOTTY;
    }
    if (st == FBRL_OK)
        st = set_nonblock(fd);
    if (st == FBRL_OK && opt->service_thread)
        st = init_thread_sync(p);
    if (st == FBRL_OK)
        st = fbrl_uart_init(u, &posix_ops, p, rx, rx_size, tx, tx_size, cfg);
    if (st != FBRL_OK) {
        release(p);
        return st;
    }
    if (p->threaded) {
        if (pthread_create(&p->thread, NULL, service_thread, p) != 0) {
            fbrl_uart_close(u);
            return FBRL_EIO;
        }
        p->thread_started = 1;
    }
    return FBRL_OK;
}

fbrl_status fbrl_uart_posix_open_fd(fbrl_uart_posix *p, fbrl_uart *u, int fd, const fbrl_uart_config *cfg,
                                    void *rx, size_t rx_size, void *tx, size_t tx_size,
                                    const fbrl_uart_posix_options *opt)
{
    if (p == NULL || u == NULL || fd < 0)
        return FBRL_EINVAL;
    return start(p, u, fd, 0, cfg, rx, rx_size, tx, tx_size, opt);
}

/* Connect to "HOST:PORT" (HOST may be "[v6addr]") within timeout_ms. */
static fbrl_status tcp_connect(const char *spec, uint32_t timeout_ms, int *out)
{
    char host[256], port[16];
    const char *colon = strrchr(spec, ':');
    if (colon == NULL || colon == spec || colon[1] == '\0' || strlen(colon + 1) >= sizeof port ||
        (size_t)(colon - spec) >= sizeof host)
        return FBRL_EINVAL;
    size_t hl = (size_t)(colon - spec);
    if (spec[0] == '[' && hl >= 2 && spec[hl - 1] == ']') { /* [::1]:4000 */
        spec++;
        hl -= 2;
    }
    memcpy(host, spec, hl);
    host[hl] = '\0';
    strcpy(port, colon + 1);
    for (const char *c = port; *c; c++)
        if (*c < '0' || *c > '9')
            return FBRL_EINVAL;

    struct addrinfo hints, *res = NULL;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    if (getaddrinfo(host, port, &hints, &res) != 0)
        return FBRL_ENOENT;
    uint64_t deadline = fbrl_clock_now_us() + (uint64_t)(timeout_ms ? timeout_ms : 5000u) * 1000u;
    fbrl_status st = FBRL_EIO;
    for (struct addrinfo *ai = res; ai != NULL; ai = ai->ai_next) {
        int fd = socket(ai->ai_family, ai->ai_socktype, ai->ai_protocol);
        if (fd < 0 || set_nonblock(fd) != FBRL_OK) {
            if (fd >= 0)
                close(fd);
            continue;
        }
        int rc = connect(fd, ai->ai_addr, ai->ai_addrlen);
        if (rc != 0 && errno == EINPROGRESS) {
            uint64_t now = fbrl_clock_now_us();
            int ms = now >= deadline ? 0 : (int)((deadline - now + 999) / 1000);
            struct pollfd f = {fd, POLLOUT, 0};
            int err = 0;
            socklen_t el = sizeof err;
            rc = poll(&f, 1, ms);
            if (rc == 0) {
                st = FBRL_ETIMEOUT;
                close(fd);
                continue;
            }
            rc = (rc > 0 && getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &el) == 0 && err == 0) ? 0 : -1;
        }
        if (rc == 0) {
            freeaddrinfo(res);
            *out = fd;
            return FBRL_OK;
        }
        close(fd);
    }
    freeaddrinfo(res);
    return st;
}

fbrl_status fbrl_uart_posix_open(fbrl_uart_posix *p, fbrl_uart *u, const char *path,
                                 const fbrl_uart_config *cfg, void *rx, size_t rx_size, void *tx,
                                 size_t tx_size, const fbrl_uart_posix_options *opt)
{
    if (p == NULL || u == NULL || path == NULL || path[0] == '\0')
        return FBRL_EINVAL;
    int fd;
    if (strncmp(path, "tcp:", 4) == 0) {
        fbrl_status st = tcp_connect(path + 4, opt != NULL ? opt->connect_timeout_ms : 0, &fd);
        if (st != FBRL_OK)
            return st;
        return start(p, u, fd, 0, cfg, rx, rx_size, tx, tx_size, opt);
    }
    fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return errno == ENOENT || errno == ENOTDIR ? FBRL_ENOENT
               : errno == EBUSY                    ? FBRL_EBUSY
               : errno == EACCES || errno == EPERM ? FBRL_EPERM
                                                   : FBRL_EIO;
    if (!isatty(fd)) {
        close(fd);
        return FBRL_ENOTTY;
    }
    /* flock guards against everyone, root included (TIOCEXCL does not stop root). */
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        close(fd);
        return e == EWOULDBLOCK ? FBRL_EBUSY : FBRL_EIO;
    }
    ioctl(fd, TIOCEXCL);
    return start(p, u, fd, 1, cfg, rx, rx_size, tx, tx_size, opt);
}
