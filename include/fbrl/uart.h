/* SPDX-License-Identifier: MIT */
/* uart.h - the serial driver core: two SPSC rings, XON/XOFF flow control, counters.
 *
 * A backend (POSIX termios, PC 8250/16550, libserialport) moves bytes between the
 * hardware and the core by calling the "interrupt" entry points fbrl_uart_isr_*();
 * the main line only calls fbrl_uart_write()/fbrl_uart_read(). The rings follow the
 * single-producer/single-consumer rule: the receive ring is filled only by the
 * interrupt side and drained only by the main line, the transmit ring the other way.
 * The core includes no OS header; time and waiting come from the backend's ops. */
#ifndef FBRL_UART_H
#define FBRL_UART_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/ring.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_XON  0x11
#define FBRL_XOFF 0x13

typedef enum fbrl_parity {
    FBRL_PARITY_NONE = 'N',
    FBRL_PARITY_EVEN = 'E',
    FBRL_PARITY_ODD = 'O'
} fbrl_parity;
typedef enum fbrl_flow { FBRL_FLOW_NONE = 0, FBRL_FLOW_XONXOFF = 1 } fbrl_flow;

typedef struct fbrl_uart_config {
    uint32_t baud;     /* bits per second, e.g. 9600 */
    uint8_t data_bits; /* 5..8 */
    fbrl_parity parity;
    uint8_t stop_bits; /* 1 or 2 */
    fbrl_flow flow;
} fbrl_uart_config;

/* 9600 8N1 with XON/XOFF: what the thesis used with the CRS controller. */
#define FBRL_UART_CONFIG_DEFAULT                           \
    {                                                      \
        9600u, 8u, FBRL_PARITY_NONE, 1u, FBRL_FLOW_XONXOFF \
    }

typedef struct fbrl_uart_counters {
    uint64_t rx_bytes, tx_bytes; /* data bytes moved (flow-control bytes excluded) */
    uint64_t overruns;           /* received bytes lost: ring full or hardware overrun */
    uint64_t framing_errors, parity_errors;
    uint64_t xoff_received, xoff_sent;
    uint64_t held_off_us; /* time the transmitter spent stopped by the peer's XOFF */
} fbrl_uart_counters;

/* Line-status flags a backend reports through fbrl_uart_isr_line_status(). */
#define FBRL_UART_LS_OVERRUN 0x1u
#define FBRL_UART_LS_PARITY  0x2u
#define FBRL_UART_LS_FRAMING 0x4u

/* What a backend provides. ctx is the backend's own state.
 *
 * Contract (the 8250, POSIX and libserialport backends all follow it):
 *  - configure, service and close are called by the main line only.
 *  - tx_kick and now_us may be called from both sides: the core calls tx_kick from
 *    fbrl_uart_isr_rx() when it must send XOFF, or restart output after the peer's
 *    XON, and now_us from the interrupt side to time XOFF holds. Both must be safe
 *    there (no blocking; on bare metal: no re-enabling interrupts).
 *  - The main line also calls tx_kick after it took bytes from a receive ring that
 *    was full: a backend that stopped receiving when fbrl_uart_rx_room() was 0
 *    (masked the receive interrupt, left bytes in the kernel) resumes then. A kick
 *    with nothing to send simply finds fbrl_uart_isr_tx() returning -1.
 *  - After tx_kick, the backend calls fbrl_uart_isr_tx() until it returns -1 (or its
 *    transmitter is full); it need not call it again until the next tx_kick.
 *  - The backend calls the fbrl_uart_isr_*() entry points from one context at a time
 *    (its interrupt handler, service thread, or service() itself), never from two. */
struct fbrl_uart;

typedef struct fbrl_uart_ops {
    /* Program the line (baud, bits, parity, stop bits). Unsupported settings: FBRL_EUNSUPPORTED. */
    fbrl_status (*configure)(void *ctx, const fbrl_uart_config *cfg);
    /* New data (or a flow-control byte) waits to go out: start the transmitter. */
    void (*tx_kick)(void *ctx);
    /* Make progress or wait: move bytes if the backend is polled, or sleep until the
     * interrupt side did something; return within timeout_us (0 = do not block).
     * FBRL_EDISCONNECTED when the peer is gone. */
    fbrl_status (*service)(void *ctx, uint32_t timeout_us);
    /* Monotonic microseconds, for timeouts and the held-off counter. */
    uint64_t (*now_us)(void *ctx);
    /* Release the port (restore previous settings). May be NULL. */
    fbrl_status (*close)(void *ctx);
    /* Polled backends: hand the bytes tx_kick announced to the OS or the hardware now,
     * without waiting (a full OS queue keeps them for the next service); FBRL_OK, or
     * the error that stopped it (FBRL_EDISCONNECTED). Called by the main line at the
     * end of fbrl_uart_write(), and after a read made an XON due, so that a written
     * byte never waits for the next read. NULL when the transmitter runs by itself
     * after tx_kick (an interrupt, a service thread). */
    fbrl_status (*flush)(void *ctx);
    /* Several ports of this backend at once (fbrl_uart_wait_any, which checks its
     * arguments): wait up to timeout_us until a port whose flags[k] has
     * FBRL_UART_WAIT_RX receives, then move the bytes of every port that is ready and
     * set FBRL_UART_WAIT_READY in flags[k] of each port that received or hit an error.
     * FBRL_EUNSUPPORTED when it cannot serve these ports together (the core then
     * services them one by one). Main line only. NULL = never. */
    fbrl_status (*wait_many)(struct fbrl_uart *const *ports, size_t n, uint32_t timeout_us,
                             unsigned char *flags);
} fbrl_uart_ops;

/* Counter slots kept by the interrupt side (private; see fbrl_uart_counters). */
#define FBRL_UART_NCOUNTERS 8

/* One serial port: caller-owned storage; every field is private. Sharing rules:
 * the interrupt side (fbrl_uart_isr_*) writes the rx ring, the flow-control state
 * and the raw counters; the main line writes the tx ring and the config. A reader
 * thread and a writer thread may use fbrl_uart_read() and fbrl_uart_write() at the
 * same time; every other main-line call belongs to one thread at a time. */
typedef struct fbrl_uart {
    fbrl_ring rx, tx;
    const fbrl_uart_ops *ops;
    void *ctx;
    fbrl_uart_config cfg;
    size_t open;            /* 1 between init and close */
    size_t flow;            /* 1 = XON/XOFF (copy of cfg.flow for the interrupt side) */
    size_t rx_high, rx_low; /* send XOFF at >= rx_high stored bytes, XON at <= rx_low */
    /* interrupt side */
    size_t peer_xoff;   /* 1 while the peer's XOFF is in force */
    size_t rx_stopped;  /* 1 from our XOFF until our XON */
    size_t ctl_pending; /* FBRL_XOFF waiting to jump the tx queue, or 0 */
    size_t held_since;  /* now_us (low bits) when the peer's XOFF began */
    size_t raw[FBRL_UART_NCOUNTERS];
    /* main line: 64-bit totals extended from raw (wrap-safe on 32-bit targets) */
    size_t seen[FBRL_UART_NCOUNTERS];
    uint64_t total[FBRL_UART_NCOUNTERS];
} fbrl_uart;

/* Open a port over a backend. rx_storage/tx_storage become the rings (any size >= 2;
 * the largest power of two that fits is used, see fbrl/ring.h); cfg is checked
 * (baud > 0, data bits 5..8, parity N/E/O, stop bits 1..2, flow NONE/XONXOFF:
 * otherwise FBRL_EINVAL) and passed to ops->configure. ops->configure, tx_kick,
 * service and now_us must be non-NULL. */
FBRL_API fbrl_status fbrl_uart_init(fbrl_uart *u, const fbrl_uart_ops *ops, void *ctx, void *rx_storage,
                                    size_t rx_size, void *tx_storage, size_t tx_size,
                                    const fbrl_uart_config *cfg);

/* Change the line settings (same checks as init). Pending bytes are not drained:
 * call fbrl_uart_drain() first if they must leave at the old settings. */
FBRL_API fbrl_status fbrl_uart_configure(fbrl_uart *u, const fbrl_uart_config *cfg);

/* Current settings. */
FBRL_API fbrl_status fbrl_uart_get_config(const fbrl_uart *u, fbrl_uart_config *cfg);

/* Queue len bytes for sending, waiting up to timeout_ms for room (0 = take what
 * fits now), and hand them to the backend's transmitter before returning (a polled
 * backend writes them to the OS within this call: ops->flush; an error it meets there,
 * such as FBRL_EDISCONNECTED, is returned). FBRL_OK when all were queued; FBRL_ETIMEOUT when the deadline passed
 * first; *written (may be NULL) tells how many were queued either way. With XON/XOFF
 * the bytes 0x11 and 0x13 cannot be sent as data (the peer would obey them). */
FBRL_API fbrl_status fbrl_uart_write(fbrl_uart *u, const void *data, size_t len, size_t *written,
                                     uint32_t timeout_ms);

/* Take up to len received bytes, waiting up to timeout_ms for the first one (0 = do
 * not wait). Returns as soon as at least one byte is there: FBRL_OK with *got >= 1
 * (len 0: FBRL_OK, *got 0), FBRL_ETIMEOUT with *got 0 when none came in time. Bytes
 * already received are returned before a backend error such as FBRL_EDISCONNECTED.
 * got must not be NULL. */
FBRL_API fbrl_status fbrl_uart_read(fbrl_uart *u, void *buf, size_t len, size_t *got, uint32_t timeout_ms);

/* Wait until every queued byte has been handed to the backend (the tx ring is empty),
 * at most timeout_ms. A peer's XOFF can hold this up: FBRL_ETIMEOUT then. */
FBRL_API fbrl_status fbrl_uart_drain(fbrl_uart *u, uint32_t timeout_ms);

/* Bytes waiting to be read / waiting to be sent (0 for a bad handle). */
FBRL_API size_t fbrl_uart_rx_available(const fbrl_uart *u);
FBRL_API size_t fbrl_uart_tx_pending(const fbrl_uart *u);

/* Interrupt side: how many more bytes the receive ring can take now (0 for a bad
 * handle). A backend that can leave bytes in a lower queue (the kernel's, a FIFO it
 * can mask) reads no more than this, so nothing is lost while the reader is slow. */
FBRL_API size_t fbrl_uart_rx_room(const fbrl_uart *u);

/* 1 while the peer's XOFF holds our transmitter, 0 otherwise (or bad handle). */
FBRL_API int fbrl_uart_peer_stopped(const fbrl_uart *u);

/* Snapshot of the counters since init. Call it from one main-line thread at a time;
 * on 32-bit targets call it at least once per 2^32 counted events or microseconds
 * held (71 minutes of continuous XOFF) so the 64-bit totals stay exact. */
FBRL_API fbrl_status fbrl_uart_get_counters(fbrl_uart *u, fbrl_uart_counters *out);

/* fbrl_uart_wait_any() flags, one byte per port. */
#define FBRL_UART_WAIT_RX    0x1u /* in: wake up when this port receives */
#define FBRL_UART_WAIT_READY 0x2u /* out: this port received bytes or hit an error */
/* Most ports one fbrl_uart_wait_any() call serves together through the backend. */
#define FBRL_UART_WAIT_MAX 256u

/* Wait for several ports at once, as one thread serving many robots needs: sleep up to
 * timeout_us until a port whose flags[k] has FBRL_UART_WAIT_RX receives, moving every
 * port's bytes (a port without the flag only gets its pending output written: a caller
 * that knows no reply can be complete yet leaves it out, and is not woken by it). On
 * return FBRL_UART_WAIT_READY is set in flags[k] of each port that received bytes or hit
 * an error (which that port's next read reports). Ports of one backend with wait_many
 * (POSIX, polled, at most FBRL_UART_WAIT_MAX) are served by one poll(); otherwise each
 * port is serviced in turn and the wait is cut into slices of at most 1 ms. FBRL_OK
 * (also when the time passed with nothing), FBRL_EINVAL (NULL, n 0, a closed port). */
FBRL_API fbrl_status fbrl_uart_wait_any(fbrl_uart *const *ports, size_t n, uint32_t timeout_us,
                                        unsigned char *flags);

/* Release the port through ops->close (if any); the handle is unusable afterwards. */
FBRL_API fbrl_status fbrl_uart_close(fbrl_uart *u);

/* ---- interrupt side: called by backends only ----
 * These never block and ignore a NULL or closed handle. */

/* One byte arrived from the line. With XON/XOFF, XON and XOFF are obeyed and not
 * stored; the rest go to the rx ring (a full ring counts an overrun and re-sends
 * XOFF). Reaching the high-water mark queues XOFF and calls ops->tx_kick. */
FBRL_API void fbrl_uart_isr_rx(fbrl_uart *u, uint8_t byte);

/* The transmitter has room for one byte: returns it (0..255), or -1 when there is
 * nothing to send now (queue empty, or held by the peer's XOFF). Flow-control bytes
 * come first: XOFF when queued, XON once the rx ring has drained to rx_low. */
FBRL_API int fbrl_uart_isr_tx(fbrl_uart *u);

/* The line reported errors: FBRL_UART_LS_* flags, each counted once per call. */
FBRL_API void fbrl_uart_isr_line_status(fbrl_uart *u, unsigned flags);

#ifdef __cplusplus
}
#endif
#endif
