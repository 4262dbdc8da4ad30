/* SPDX-License-Identifier: MIT */
/* uart_serialport.h - serial port enumeration and a UART backend over libserialport.
 *
 * Built only when libserialport was found (then FBRL_HAVE_SERIALPORT is defined).
 * Use it for the list of ports (fbrlmon --list-ports) and on Windows and macOS; on
 * Linux and BSD the POSIX backend (fbrl/uart_posix.h) does more (ptys, TCP, a
 * service thread). libserialport cannot open Linux pseudo-terminals (it needs a
 * sysfs entry and modem-control ioctls ptys lack): such a name gives
 * FBRL_EUNSUPPORTED, a name that does not exist FBRL_ENOENT.
 *
 * The backend is polled: its service loop (sp_wait on the port's events, then
 * non-blocking reads into fbrl_uart_isr_rx and writes from fbrl_uart_isr_tx) runs
 * inside fbrl_uart_read/write/drain, so one thread uses the port. Flow control is
 * the core's XON/XOFF; libserialport's own flow control is switched off. */
#ifndef FBRL_UART_SERIALPORT_H
#define FBRL_UART_SERIALPORT_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/uart.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fbrl_serial_port_info {
    char name[128];        /* what to open: "/dev/ttyUSB0", "COM3" */
    char description[128]; /* e.g. "FT232R USB UART - FT232R USB UART" ("" if none) */
    int usb;               /* 1 when the port is on USB and vid/pid are known */
    uint16_t vid, pid;
} fbrl_serial_port_info;

/* Fill up to max entries; *count = how many ports exist (may be more than max, or
 * 0). Names and descriptions longer than the fields are cut. FBRL_EIO when the
 * system cannot be asked. out may be NULL when max is 0 (just count). */
FBRL_API fbrl_status fbrl_uart_serialport_list(fbrl_serial_port_info *out, size_t max, size_t *count);

#define FBRL_UART_SERIALPORT_STAGE 256

/* Backend state: caller-owned, fields private, fixed address while open. */
typedef struct fbrl_uart_serialport {
    fbrl_uart *u;
    void *port, *events; /* struct sp_port *, struct sp_event_set * */
    uint8_t stage[FBRL_UART_SERIALPORT_STAGE];
    size_t stage_len, stage_off, kick, outq_limit;
} fbrl_uart_serialport;

/* Open the port called name with cfg (see fbrl_uart_init for rx/tx storage). Errors:
 * FBRL_ENOENT (no such port), FBRL_EUNSUPPORTED (exists but libserialport cannot
 * drive it, e.g. a pty; or a setting it refuses), FBRL_EBUSY (in use), FBRL_EIO. */
FBRL_API fbrl_status fbrl_uart_serialport_open(fbrl_uart_serialport *p, fbrl_uart *u, const char *name,
                                               const fbrl_uart_config *cfg, void *rx, size_t rx_size,
                                               void *tx, size_t tx_size);

#ifdef __cplusplus
}
#endif
#endif
