/* SPDX-License-Identifier: MIT */
/* uart_serialport.c - enumeration and a polled UART backend over libserialport. */
#define _DEFAULT_SOURCE 1
#include <errno.h>
#include <string.h>
#include <libserialport.h>
#ifndef _WIN32
#include <sys/stat.h>
#endif
#include "fbrl/uart_serialport.h"
#include "fbrl/clock.h"
#include "atomic.h"

static void copy_text(char *dst, size_t n, const char *src)
{
    size_t len = src == NULL ? 0 : strlen(src);
    if (len >= n)
        len = n - 1;
    if (len > 0)
        memcpy(dst, src, len);
    dst[len] = '\0';
}

fbrl_status fbrl_uart_serialport_list(fbrl_serial_port_info *out, size_t max, size_t *count)
{
    struct sp_port **ports = NULL;
    if (count == NULL || (out == NULL && max > 0))
        return FBRL_EINVAL;
    *count = 0;
    if (sp_list_ports(&ports) != SP_OK)
        return FBRL_EIO;
    size_t n = 0;
    for (; ports[n] != NULL; n++) {
        if (n >= max)
            continue;
        fbrl_serial_port_info *i = &out[n];
        int vid = 0, pid = 0;
        memset(i, 0, sizeof *i);
        copy_text(i->name, sizeof i->name, sp_get_port_name(ports[n]));
        copy_text(i->description, sizeof i->description, sp_get_port_description(ports[n]));
        if (sp_get_port_transport(ports[n]) == SP_TRANSPORT_USB &&
            sp_get_port_usb_vid_pid(ports[n], &vid, &pid) == SP_OK) {
            i->usb = 1;
            i->vid = (uint16_t)vid;
            i->pid = (uint16_t)pid;
        }
    }
    sp_free_port_list(ports);
    *count = n;
    return FBRL_OK;
}

/* ---- backend ops ---- */

static fbrl_status sp_status(enum sp_return r)
{
    switch (r) {
    case SP_OK: return FBRL_OK;
    case SP_ERR_ARG:
    case SP_ERR_SUPP: return FBRL_EUNSUPPORTED;
    default: return FBRL_EIO;
    }
}

static fbrl_status sps_configure(void *ctx, const fbrl_uart_config *cfg)
{
    fbrl_uart_serialport *p = ctx;
    struct sp_port *port = p->port;
    enum sp_return r;
    enum sp_parity par = cfg->parity == FBRL_PARITY_EVEN  ? SP_PARITY_EVEN
                         : cfg->parity == FBRL_PARITY_ODD ? SP_PARITY_ODD
                                                          : SP_PARITY_NONE;
    if ((r = sp_set_baudrate(port, (int)cfg->baud)) != SP_OK ||
        (r = sp_set_bits(port, cfg->data_bits)) != SP_OK || (r = sp_set_parity(port, par)) != SP_OK ||
        (r = sp_set_stopbits(port, cfg->stop_bits)) != SP_OK ||
        (r = sp_set_flowcontrol(port, SP_FLOWCONTROL_NONE)) != SP_OK)
        return sp_status(r);
    p->outq_limit = cfg->baud / 1000u < 16u ? 16u : cfg->baud / 1000u; /* ~10 ms of line */
    return FBRL_OK;
}

static void sps_kick(void *ctx) { fbrl_store_rel(&((fbrl_uart_serialport *)ctx)->kick, 1); }

/* Transmit: refill the stage from isr_tx while the OS queue is short, and write it. */
static fbrl_status sps_send(fbrl_uart_serialport *p, size_t *moved)
{
    struct sp_port *port = p->port;
    if (p->stage_off == p->stage_len && fbrl_load_acq(&p->kick)) {
        int waiting = sp_output_waiting(port);
        size_t limit = waiting < 0 || (size_t)waiting >= p->outq_limit ? 0 : p->outq_limit - (size_t)waiting;
        int c = 0;
        if (limit > sizeof p->stage)
            limit = sizeof p->stage;
        p->stage_off = p->stage_len = 0;
        while (p->stage_len < limit && (c = fbrl_uart_isr_tx(p->u)) >= 0)
            p->stage[p->stage_len++] = (uint8_t)c;
        if (c < 0)
            fbrl_store_rel(&p->kick, 0);
        *moved += p->stage_len;
    }
    if (p->stage_off < p->stage_len) {
        int n = sp_nonblocking_write(port, p->stage + p->stage_off, p->stage_len - p->stage_off);
        if (n < 0)
            return FBRL_EDISCONNECTED;
        p->stage_off += (size_t)n;
    }
    return FBRL_OK;
}

/* The bytes just queued leave within fbrl_uart_write (docs/serial.md 4). */
static fbrl_status sps_flush(void *ctx)
{
    size_t moved = 0;
    return sps_send(ctx, &moved);
}

static fbrl_status sps_service(void *ctx, uint32_t timeout_us)
{
    fbrl_uart_serialport *p = ctx;
    struct sp_port *port = p->port;
    size_t moved = 0;
    uint8_t buf[1024];
    /* Receive: never more than the ring takes; the rest waits in the OS. */
    size_t room = fbrl_uart_rx_room(p->u);
    if (room > 0) {
        int n = sp_nonblocking_read(port, buf, room < sizeof buf ? room : sizeof buf);
        if (n < 0)
            return FBRL_EDISCONNECTED;
        for (int i = 0; i < n; i++)
            fbrl_uart_isr_rx(p->u, buf[i]);
        moved += (size_t)n;
    }
    fbrl_status st = sps_send(p, &moved);
    if (st != FBRL_OK)
        return st;
    if (moved > 0 || timeout_us == 0)
        return moved > 0 ? FBRL_OK : FBRL_ETIMEOUT;
    /* Nothing happened: wait for the port, in short slices while output is pending
     * (the OS queue drains without an event we can wait on everywhere). */
    unsigned ms = timeout_us / 1000u + (timeout_us % 1000u != 0);
    if ((p->stage_off < p->stage_len || fbrl_load_acq(&p->kick)) && ms > 2)
        ms = 2;
    if (sp_wait(p->events, ms) != SP_OK)
        return FBRL_EIO;
    return FBRL_ETIMEOUT;
}

static uint64_t sps_now(void *ctx)
{
    (void)ctx;
    return fbrl_clock_now_us();
}

static void release(fbrl_uart_serialport *p)
{
    if (p->events != NULL)
        sp_free_event_set(p->events);
    if (p->port != NULL) {
        sp_close(p->port);
        sp_free_port(p->port);
    }
    p->events = p->port = NULL;
}

static fbrl_status sps_close(void *ctx)
{
    release(ctx);
    return FBRL_OK;
}

static const fbrl_uart_ops serialport_ops = {sps_configure, sps_kick, sps_service, sps_now, sps_close,
                                             sps_flush,     0};

fbrl_status fbrl_uart_serialport_open(fbrl_uart_serialport *p, fbrl_uart *u, const char *name,
                                      const fbrl_uart_config *cfg, void *rx, size_t rx_size, void *tx,
                                      size_t tx_size)
{
    struct sp_port *port = NULL;
    struct sp_event_set *ev = NULL;
    if (p == NULL || u == NULL || name == NULL || name[0] == '\0')
        return FBRL_EINVAL;
    memset(p, 0, sizeof *p);
    if (sp_get_port_by_name(name, &port) != SP_OK) {
#ifndef _WIN32
        struct stat sb;
        if (stat(name, &sb) == 0) /* it exists, libserialport just cannot drive it (a pty) */
            return FBRL_EUNSUPPORTED;
#endif
        return FBRL_ENOENT;
    }
    p->port = port;
    if (sp_open(port, SP_MODE_READ_WRITE) != SP_OK) {
        int e = sp_last_error_code();
        sp_free_port(port);
        p->port = NULL;
        return e == EBUSY ? FBRL_EBUSY : e == ENOENT ? FBRL_ENOENT : FBRL_EIO;
    }
    if (sp_new_event_set(&ev) != SP_OK ||
        sp_add_port_events(ev, port, SP_EVENT_RX_READY | SP_EVENT_ERROR) != SP_OK) {
        if (ev != NULL)
            sp_free_event_set(ev);
        release(p);
        return FBRL_EIO;
    }
    p->events = ev;
    p->u = u;
    fbrl_status st = fbrl_uart_init(u, &serialport_ops, p, rx, rx_size, tx, tx_size, cfg);
    if (st != FBRL_OK)
        release(p);
    return st;
}
