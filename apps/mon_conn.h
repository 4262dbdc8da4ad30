/* SPDX-License-Identifier: MIT */
/* mon_conn.h - fbrlmon's connection to a controller: a serial port, a pty or a
 * TCP serial server, or the built-in emulator (fbrlsim's core on a pty), all opened
 * by name through the library's fbrl_port (so every program opens ports the same way),
 * with the RAPL link's start-up handshake proving that a controller answers. */
#ifndef FBRLMON_CONN_H
#define FBRLMON_CONN_H

#include <stddef.h>
#include <stdio.h>
#include "fbrl/arm.h"
#include "fbrl/link.h"
#include "fbrl/port.h"

#ifdef FBRLMON_HAVE_SIM
#include "fbrlsim.h"
#endif

typedef enum mon_conn_kind { MON_CONN_OFFLINE, MON_CONN_PORT, MON_CONN_SIM } mon_conn_kind;

typedef struct mon_conn_options {
    mon_conn_kind kind;
    const char *port;       /* MON_CONN_PORT: a name fbrl_port_open takes (path, tcp:HOST:PORT, ?options) */
    fbrl_port_options line; /* baud, data bits, parity, stop bits, flow, low latency */
    const char *sim_state;  /* MON_CONN_SIM: emulator's persistent memory, or NULL */
    const char *sim_inputs; /* MON_CONN_SIM: fbrlsim --inputs file (timed "T IN n v"), or NULL */
    const fbrl_arm *arm;    /* the arm (--arm); NULL: the emulator's own (its state file's), else
                             * the A255 */
    unsigned axes;          /* the axes in W2/STATUS; 0: the arm's */
    double (*sim_clock)(void *ctx); /* MON_CONN_SIM: the emulator's clock (the dry run's), or NULL */
    void (*sim_skip)(void *ctx, double s);
    void *sim_clock_ctx;
    /* every line the controller executed (fbrl_link_config.on_exec): the run log */
    void (*on_exec)(void *ctx, const char *line, size_t len, fbrl_status result);
    void *exec_ctx;
} mon_conn_options;

/* Keep at a fixed address while open (the backend points into it). */
typedef struct mon_conn {
    mon_conn_kind kind;
    int open;
#ifdef FBRLMON_HAVE_SIM
    fbrl_sim *sim;
#endif
    const char *sim_state, *sim_inputs;
    const fbrl_arm *arm; /* the arm the link checks positions of (and the emulator is) */
    double (*sim_clock)(void *ctx);
    void (*sim_skip)(void *ctx, double s);
    void *sim_clock_ctx;
    char sim_err[256];
    fbrl_port port;
    fbrl_link link;
    const char *url; /* what was opened, and how (for mon_conn_reopen) */
    fbrl_port_options opts;
    fbrl_link_config lcfg;
    fbrl_link_modes modes; /* the session's modes (lcfg.modes): kept across reconnects */
    /* what the user must know about the controller just connected ("" nothing): it works
     * in millimetres (the connect refused its units, docs/link.md 1) */
    char note[FBRL_PORT_NAME_MAX + 200];
} mon_conn;

/* Connect as asked; on failure err says why (one line, no newline). A controller that
 * works in millimetres is connected all the same, with c->note saying so and how to switch
 * it (the robot words refuse their commands meanwhile). *c must be all zero, as static
 * storage is (clear it again before a second try): clearing its 18 KB here would make
 * them resident. */
fbrl_status mon_conn_open(mon_conn *c, const mon_conn_options *o, char *err, size_t errlen);
/* One-line description, e.g. "emulator on /dev/pts/4 (9600 8N1, XON/XOFF; pty, low
 * latency: not supported)". */
void mon_conn_describe(const mon_conn *c, char *buf, size_t cap);
void mon_conn_close(mon_conn *c);
/* After the controller went away: open the port again by the same name and options (the
 * built-in emulator is not restarted) and run the connect handshake; on failure err says
 * why; c->note as for mon_conn_open. */
fbrl_status mon_conn_reopen(mon_conn *c, char *err, size_t errlen);
/* What to do about an open failure, as text to append to the message ("" if nothing
 * useful): for FBRL_EPERM, the dialout group. */
const char *mon_conn_hint(fbrl_status st);

/* --list-ports: print the serial ports the system has, one per line: the stable
 * /dev/serial/by-id name (when udev made one) and the device, the USB product, VID:PID and
 * serial number, the driver and latency timer (fbrl_port_list: Linux sysfs; elsewhere
 * libserialport's list). FBRL_EUNSUPPORTED with neither. The environment variables below
 * point it at other sysfs and /dev trees (the tests' fake ones). */
#define MON_SYSFS_ENV      "FBRLMON_SYSFS_ROOT"
#define MON_DEV_ENV        "FBRLMON_DEV_ROOT"
#define MON_LIST_PORTS_MAX 64
fbrl_status mon_conn_list_ports(FILE *out);

#endif
