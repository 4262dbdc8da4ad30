/* SPDX-License-Identifier: MIT */
/* port.h - open a controller port by its name, the same way in every program.
 *
 *   fbrl_port_open(&p, "/dev/ttyUSB0", &opt)            a serial device (or any tty/pty path)
 *   fbrl_port_open(&p, "tcp:192.168.1.20:4001", &opt)   a TCP serial server
 *   fbrl_port_open(&p, "sim:", &opt)                    an emulator the program starts (hook)
 *   fbrl_port_open(&p, "/dev/ttyS0?baud=19200&parity=even", &opt)   options in the name
 *
 * then fbrl_port_uart(&p) is the fbrl_uart the link runs on. Line settings come from
 * fbrl_port_options (fbrl_port_set_option() takes them as text, as command lines and
 * configuration files give them); after "?" in the name, key=value pairs joined by '&'
 * override them. The POSIX backend does the I/O (docs/serial.md 3); this module adds
 * what depends on the device: it recognises the kind of port (pty, USB adapter and its
 * kernel driver) and applies the quirk table (docs/serial.md 6), e.g. a USB-serial
 * adapter is put into low-latency mode (Linux ASYNC_LOW_LATENCY; an FTDI's latency
 * timer lowered to 1 ms through sysfs), and fbrl_port_describe() says what was done.
 *
 * "sim:" needs an emulator: the library never starts programs itself, so the caller
 * passes a hook that starts one (fbrlmon runs fbrlsim's core in a thread; a program may
 * fork fbrlsim) and names the pseudo-terminal to open; without a hook "sim:" gives
 * FBRL_EUNSUPPORTED. The header includes no OS header (the backend's state is opaque
 * storage here), so fbrl.h stays freestanding; src/port.c is built on POSIX hosts. */
#ifndef FBRL_PORT_H
#define FBRL_PORT_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/uart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Device quirks, as bits (the table in src/port.c, one row per kind of device). */
#define FBRL_PORT_Q_PTY \
    0x01u                     /* pseudo-terminal: no wire, no parity (CS8 forced), TIOCOUTQ always 0,
                                         * PARMRK would double each 0xFF, no TIOCSSERIAL, no error counts */
#define FBRL_PORT_Q_USB 0x02u /* USB adapter: input reaches the host in USB packets, not per byte */
#define FBRL_PORT_Q_LATENCY_TIMER \
    0x04u                             /* holds input until its latency timer runs out (FTDI: 16 ms by
                                         * default; a 9-byte command then costs 2.6x), settable in sysfs */
#define FBRL_PORT_Q_LOW_LATENCY 0x08u /* the driver takes ASYNC_LOW_LATENCY (TIOCSSERIAL) */
#define FBRL_PORT_Q_COARSE_BAUD \
    0x10u                        /* baud from a prescaler/divisor pair: some rates approximated,
                                         * some chips cannot send a real break (CH340/CH341) */
#define FBRL_PORT_Q_SOCKET 0x20u /* TCP: the settings are only recorded, the server owns the line */

typedef enum fbrl_port_kind {
    FBRL_PORT_TTY = 0, /* a serial device */
    FBRL_PORT_PTY,     /* a pseudo-terminal (an emulator) */
    FBRL_PORT_TCP,     /* a TCP serial server */
    FBRL_PORT_SIM      /* an emulator started through the hook (on a pty) */
} fbrl_port_kind;

/* What became of the low-latency request. */
typedef enum fbrl_port_low_latency {
    FBRL_PORT_LL_OFF = 0,     /* not asked for (options.low_latency = 0), or no tty */
    FBRL_PORT_LL_SET,         /* ASYNC_LOW_LATENCY is on (was, or was set now) */
    FBRL_PORT_LL_UNSUPPORTED, /* the driver has no TIOCSSERIAL (a pty, most USB drivers) */
    FBRL_PORT_LL_REFUSED      /* the driver refused the flag */
} fbrl_port_low_latency;

typedef struct fbrl_port_options {
    fbrl_uart_config line;       /* baud, data bits, parity, stop bits, flow (FBRL_UART_CONFIG_DEFAULT) */
    int service_thread;          /* 1: the POSIX backend's service thread (0) */
    uint32_t connect_timeout_ms; /* tcp: (5000) */
    int low_latency;             /* 1: low-latency mode where the driver supports it (1) */
    unsigned latency_timer_ms;   /* the FTDI latency timer to set, 1..255 (1) */
    const char *sysfs_root;      /* where sysfs is mounted (NULL: "/sys"); tests use a fake tree */
    /* "sim:ARG": start an emulator for ARG (the text after "sim:") and put the path of
     * the tty to open into path; stop it again (also when the open failed). */
    fbrl_status (*sim_start)(void *ctx, const char *arg, char *path, size_t cap);
    void (*sim_stop)(void *ctx);
    void *sim_ctx;
} fbrl_port_options;

FBRL_API void fbrl_port_options_init(fbrl_port_options *o);

/* Set one option from text: "baud" (1..4000000), "data-bits" (5..8), "parity" (none|even|odd
 * or N|E|O), "stop-bits" (1|2), "flow" (none|xonxoff), "low-latency" (on|off|1|0),
 * "latency-timer" (1..255 ms), "thread" (on|off). FBRL_EINVAL for an unknown key or a bad
 * value (o unchanged). */
FBRL_API fbrl_status fbrl_port_set_option(fbrl_port_options *o, const char *key, const char *value);

/* Room for the backend's state (fbrl_uart_posix), checked at compile time in port.c. */
#define FBRL_PORT_BACKEND_BYTES 8192
#define FBRL_PORT_NAME_MAX      256

/* An open port: caller-owned, every field private; keep it at a fixed address while open. */
typedef struct fbrl_port {
    union {
        unsigned char bytes[FBRL_PORT_BACKEND_BYTES];
        uint64_t align_u64;
        void *align_ptr;
        long double align_ld;
    } backend;
    fbrl_uart uart;
    unsigned char rx[4096], tx[1024];
    char name[FBRL_PORT_NAME_MAX]; /* what was opened (the device, tcp:..., the emulator's pty) */
    char driver[32];               /* kernel driver ("ftdi_sio", "ch341", "pty", ""), for messages */
    fbrl_port_kind kind;
    unsigned quirks; /* FBRL_PORT_Q_* */
    fbrl_port_low_latency low_latency;
    int latency_timer_ms;     /* the adapter's latency timer now, -1 when it has none */
    int latency_timer_was_ms; /* before the open changed it, -1 when unchanged or none */
    int open, sim_running;
    void (*sim_stop)(void *ctx);
    void *sim_ctx;
} fbrl_port;

/* Open url (see the top of this file) with opt (NULL: defaults). Errors: those of
 * fbrl_uart_posix_open (FBRL_ENOENT, FBRL_ENOTTY, FBRL_EBUSY, FBRL_EPERM, FBRL_EUNSUPPORTED,
 * FBRL_ETIMEOUT, FBRL_EIO), FBRL_EINVAL for a bad name or option text,
 * FBRL_EUNSUPPORTED for "sim:" without a hook, or what the hook returned. A low-latency
 * mode the driver lacks is no error: fbrl_port_describe() tells it. */
FBRL_API fbrl_status fbrl_port_open(fbrl_port *p, const char *url, const fbrl_port_options *opt);

/* The uart of an open port (NULL when p is not open). */
FBRL_API fbrl_uart *fbrl_port_uart(fbrl_port *p);

/* One line: "/dev/ttyUSB0 (9600 8N1, XON/XOFF; ftdi_sio, low latency: latency timer 1 ms
 * (was 16))", "/dev/pts/4 (9600 8N1, XON/XOFF; pty, low latency: not supported)". */
FBRL_API fbrl_status fbrl_port_describe(const fbrl_port *p, char *buf, size_t cap);

/* Close the uart and stop an emulator the hook started. */
FBRL_API fbrl_status fbrl_port_close(fbrl_port *p);

/* ---- USB-serial adapters by device name (also for port lists; nothing is opened) ---- */

typedef struct fbrl_port_usb_info {
    char driver[32];      /* kernel driver of the tty ("" if none is known) */
    unsigned quirks;      /* from the table, by driver */
    int latency_timer_ms; /* the latency timer, -1 when the device has none */
} fbrl_port_usb_info;

/* What sysfs (under sysfs_root, NULL = "/sys") says about the tty called name ("ttyUSB0"
 * or "/dev/ttyUSB0"). FBRL_OK (an unknown device gives driver "" and timer -1). */
FBRL_API fbrl_status fbrl_port_usb_info_get(const char *sysfs_root, const char *name,
                                            fbrl_port_usb_info *out);

/* ---- the serial ports this machine has (Linux sysfs; nothing is opened) ---- */

/* One port as fbrl_port_list() finds it. Every text is "" when unknown. */
typedef struct fbrl_port_entry {
    char device[128];      /* "/dev/ttyUSB0" */
    char by_id[256];       /* its stable name, "/dev/serial/by-id/usb-FTDI_..._A12345-if00-port0" */
    char description[128]; /* the USB product string ("FT232R USB UART") */
    char manufacturer[64]; /* the USB manufacturer string ("FTDI") */
    char serial[64];       /* the USB serial number ("A12345") */
    int usb;               /* 1 when the port is on USB: vid and pid are known */
    unsigned vid, pid;     /* USB vendor and product id */
    char driver[32];       /* kernel driver ("ftdi_sio", "cdc_acm", "serial8250") */
    int latency_timer_ms;  /* as fbrl_port_usb_info_get() says; -1 when none */
} fbrl_port_entry;

/* List the serial ports: every tty in SYSFS/class/tty with a device behind it (8250 UARTs
 * only when one is there: their "type" is not 0), sorted by device name, with the names
 * under DEV/serial/by-id that lead to each. sysfs_root NULL = "/sys", dev_root NULL =
 * "/dev". Fills out[0 .. max) and sets *count to the number found (which may exceed max).
 * FBRL_EUNSUPPORTED without SYSFS/class/tty (not Linux); FBRL_EINVAL for NULL count. */
FBRL_API fbrl_status fbrl_port_list(const char *sysfs_root, const char *dev_root, fbrl_port_entry *out,
                                    size_t max, size_t *count);

/* Set the latency timer of the tty called name to ms (1..255) through
 * SYSFS/bus/usb-serial/devices/NAME/latency_timer; *was = the value before (may be NULL).
 * FBRL_ENOENT when the device has no latency timer, FBRL_EIO when it cannot be written
 * (permissions: see docs/serial.md), FBRL_EINVAL for bad arguments. */
FBRL_API fbrl_status fbrl_port_set_latency_timer(const char *sysfs_root, const char *name, unsigned ms,
                                                 int *was);

#ifdef __cplusplus
}
#endif
#endif
