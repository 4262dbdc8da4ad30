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

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/ring.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_XON  0x11
#define FBRL_XOFF 0x13

typedef enum fbrl_parity { FBRL_PARITY_NONE = 'N', FBRL_PARITY_EVEN = 'E', FBRL_PARITY_ODD = 'O' } fbrl_parity;
typedef enum fbrl_flow { FBRL_FLOW_NONE = 0, FBRL_FLOW_XONXOFF = 1 } fbrl_flow;

typedef struct fbrl_uart_config {
    uint32_t baud;      /* bits per second, e.g. 9600 */
    uint8_t data_bits;  /* 5..8 */
    fbrl_parity parity;
    uint8_t stop_bits;  /* 1 or 2 */
    fbrl_flow flow;
} fbrl_uart_config;

/* 9600 8N1 with XON/XOFF: what the thesis used with the CRS controller. */
#define FBRL_UART_CONFIG_DEFAULT { 9600u, 8u, FBRL_PARITY_NONE, 1u, FBRL_FLOW_XONXOFF }

typedef struct fbrl_uart_counters {
    uint64_t rx_bytes, tx_bytes;   /* data bytes moved (flow-control bytes excluded) */
    uint64_t overruns;             /* received bytes lost: ring full or hardware overrun */
    uint64_t framing_errors, parity_errors;
    uint64_t xoff_received, xoff_sent;
    uint64_t held_off_us;          /* time the transmitter spent stopped by the peer's XOFF */
} fbrl_uart_counters;

/* Line-status flags a backend reports through fbrl_uart_isr_line_status(). */
#define FBRL_UART_LS_OVERRUN 0x1u
#define FBRL_UART_LS_PARITY  0x2u
#define FBRL_UART_LS_FRAMING 0x4u

/* What a backend provides. ctx is the backend's own state. */
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
} fbrl_uart_ops;

/* struct fbrl_uart (caller-owned, fields private), fbrl_uart_init(), read/write/drain,
 * counters and the fbrl_uart_isr_*() entry points are declared below by the uart module. */

#ifdef __cplusplus
}
#endif
#endif
