/* SPDX-License-Identifier: MIT */
/* uart_posix.h - POSIX backend for the UART core: termios ttys and ptys, and TCP.
 *
 * Open any tty or pty path ("/dev/ttyUSB0", "/dev/pts/3") or a serial server as
 * "tcp:HOST:PORT"; the port is then used through fbrl/uart.h (fbrl_uart_write,
 * fbrl_uart_read, fbrl_uart_drain, fbrl_uart_close ...).
 *
 *  - Raw mode (no echo, no line editing, no CR/LF mapping, no kernel XON/XOFF:
 *    the core does flow control itself). Every fbrl_uart_config setting maps to
 *    termios; a baud rate termios lacks gives FBRL_EUNSUPPORTED.
 *  - Exclusive use: TIOCEXCL plus flock(LOCK_EX), so a second open of a port in use,
 *    by this or another program, gives FBRL_EBUSY. The previous termios settings are
 *    restored on close.
 *  - The service loop plays the interrupt: poll() on the fd, bytes read go to
 *    fbrl_uart_isr_rx() (never more than the receive ring can take; the rest waits
 *    in the kernel), bytes from fbrl_uart_isr_tx() are written while the fd is
 *    writable, at most tx_chunk at a time and, on a real tty, only while the
 *    kernel's output queue holds less than about 10 ms of line time, so that a
 *    peer's XOFF stops the output quickly.
 *  - Parity E or O on a tty: INPCK|PARMRK; a byte received with a parity error is
 *    counted (fbrl_uart_counters.parity_errors, through fbrl_uart_isr_line_status)
 *    and dropped; it never reaches the receive ring. On a pty PARMRK stays off and
 *    the peer is expected to write that format (fbrlsim --parity does).
 *  - Without a service thread the loop runs inside fbrl_uart_read/write/drain (one
 *    thread may use the port). With service_thread = 1 a background thread runs it,
 *    answering flow control while the application computes; read/write/drain then
 *    wait on a condition variable the thread signals whenever it moved bytes, and
 *    one reader thread plus one writer thread may use the port at the same time.
 *
 * Errors at open: no such path -> FBRL_ENOENT, not a terminal -> FBRL_ENOTTY, in use
 * -> FBRL_EBUSY, no permission (EACCES, EPERM) -> FBRL_EPERM, bad "tcp:" text ->
 * FBRL_EINVAL, unknown host -> FBRL_ENOENT, no answer within connect_timeout_ms ->
 * FBRL_ETIMEOUT, refused -> FBRL_EIO. Later, a
 * peer that went away (pty master closed, TCP reset or EOF) gives FBRL_EDISCONNECTED
 * from read/write/drain. Over TCP the line settings are only recorded: the serial
 * server owns the real line. */
#ifndef FBRL_UART_POSIX_H
#define FBRL_UART_POSIX_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include <pthread.h>
#include <termios.h>
#include "fbrl/status.h"
#include "fbrl/uart.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fbrl_uart_posix_options {
    int service_thread;          /* 1: run the service loop in a background thread */
    uint32_t connect_timeout_ms; /* tcp: how long connect may take (0: 5000) */
    size_t tx_chunk;             /* most bytes handed to write() at once (0: 256, max 4096) */
} fbrl_uart_posix_options;

#define FBRL_UART_POSIX_OPTIONS_DEFAULT \
    {                                   \
        0, 5000u, 0                     \
    }

#define FBRL_UART_POSIX_STAGE 4096

/* Backend state: caller-owned storage, fields private. Keep it at a fixed address
 * while the port is open (the core and the service thread point at it). */
typedef struct fbrl_uart_posix {
    fbrl_uart *u;
    int fd, wake[2]; /* wake: self-pipe that tx_kick writes in thread mode */
    int is_tty, is_pty, is_socket, locked, saved_valid;
    int icount_ok; /* the driver reports error counts (TIOCGICOUNT) */
    uint32_t ic_frame, ic_parity, ic_overrun;
    size_t marked;  /* parity on (tty): received bytes come in PARMRK format */
    int mark_state; /* service side: 0, 1 after 0xFF, 2 after 0xFF 0x00 */
    struct termios saved, raw;
    uint32_t baud;
    size_t chunk, outq_limit;
    size_t kick;                          /* tx_kick happened (polled mode) */
    uint8_t stage[FBRL_UART_POSIX_STAGE]; /* bytes taken from isr_tx, not yet written */
    size_t stage_len, stage_off;
    /* thread mode */
    int threaded, thread_started;
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    uint64_t seq, seen;        /* thread's progress count / last seen by service() */
    fbrl_status thread_status; /* first error the thread hit (e.g. EDISCONNECTED) */
    int stop;
} fbrl_uart_posix;

/* Open path (tty/pty device or "tcp:HOST:PORT") as u, using rx/tx storage for the
 * core's rings and cfg for the line (see fbrl_uart_init). opt may be NULL (defaults). */
FBRL_API fbrl_status fbrl_uart_posix_open(fbrl_uart_posix *p, fbrl_uart *u, const char *path,
                                          const fbrl_uart_config *cfg, void *rx, size_t rx_size, void *tx,
                                          size_t tx_size, const fbrl_uart_posix_options *opt);

/* The same over an fd the caller already opened (a pty master from posix_openpt, a
 * connected socket, a tty); the port takes ownership and closes it on close. No
 * exclusivity is claimed. FBRL_EINVAL for fd < 0. */
FBRL_API fbrl_status fbrl_uart_posix_open_fd(fbrl_uart_posix *p, fbrl_uart *u, int fd,
                                             const fbrl_uart_config *cfg, void *rx, size_t rx_size, void *tx,
                                             size_t tx_size, const fbrl_uart_posix_options *opt);

/* The fd in use (e.g. to tcgetattr it), or -1. */
FBRL_API int fbrl_uart_posix_fd(const fbrl_uart_posix *p);

/* The termios speed constant for a baud rate (e.g. 9600 -> B9600); FBRL_EUNSUPPORTED
 * when this system has none. */
FBRL_API fbrl_status fbrl_uart_posix_speed(uint32_t baud, speed_t *speed);

#ifdef __cplusplus
}
#endif
#endif
