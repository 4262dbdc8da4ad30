/* mon_conn.h - fbrlmon's connection to a controller: a serial port, a pty or a
 * TCP serial server through the POSIX uart backend, or the built-in emulator
 * (fbrlsim's core on a pty, reached through the very same termios path), with the
 * RAPL link's start-up handshake proving that a controller answers. */
#ifndef FBRLMON_CONN_H
#define FBRLMON_CONN_H

#include <stddef.h>
#include <stdio.h>
#include "fbrl/link.h"
#include "fbrl/uart.h"
#include "fbrl/uart_posix.h"

#ifdef FBRLMON_HAVE_SIM
#include "fbrlsim.h"
#endif

typedef enum mon_conn_kind { MON_CONN_OFFLINE, MON_CONN_PORT, MON_CONN_SIM } mon_conn_kind;

typedef struct mon_conn_options {
    mon_conn_kind kind;
    const char *port;        /* MON_CONN_PORT: path or tcp:HOST:PORT */
    fbrl_uart_config line;   /* baud, data bits, parity, stop bits, flow */
    const char *sim_state;   /* MON_CONN_SIM: emulator's persistent memory, or NULL */
    const char *sim_inputs;  /* MON_CONN_SIM: fbrlsim --inputs file (timed "T IN n v"), or NULL */
} mon_conn_options;

/* Keep at a fixed address while open (the backend points into it). */
typedef struct mon_conn {
    mon_conn_kind kind;
    int open;
#ifdef FBRLMON_HAVE_SIM
    fbrl_sim *sim;
#endif
    fbrl_uart_posix port;
    fbrl_uart uart;
    unsigned char rx[4096], tx[1024];
    fbrl_link link;
    char path[256];
} mon_conn;

/* Connect as asked; on failure err says why (one line, no newline). */
fbrl_status mon_conn_open(mon_conn *c, const mon_conn_options *o, char *err, size_t errlen);
/* One-line description, e.g. "emulator on /dev/pts/4 (9600 8N1, XON/XOFF)". */
void mon_conn_describe(const mon_conn *c, char *buf, size_t cap);
void mon_conn_close(mon_conn *c);

/* --list-ports: print the serial ports the system knows, one per line.
 * FBRL_EUNSUPPORTED when fbrlmon was built without libserialport. */
fbrl_status mon_conn_list_ports(FILE *out);

#endif
