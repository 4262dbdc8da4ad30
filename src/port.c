/* SPDX-License-Identifier: MIT */
/* port.c - a controller port opened by its name, with the device's quirks (fbrl/port.h).
 *
 * The name decides the backend (tcp:, sim:, a path), the device decides the quirks:
 * the tty's kernel driver (sysfs) selects a row of the quirk table, as Linux's 8250
 * driver keeps its per-UART quirk bits, and the rows say what to do at open (low
 * latency) and what to tell the user. */
#define _DEFAULT_SOURCE 1 /* realpath, readlink */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <dirent.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#ifdef __linux__
#include <linux/serial.h>
#endif
#include "fbrl/port.h"
#include "fbrl/uart_posix.h"

typedef char backend_fits[sizeof(fbrl_uart_posix) <= FBRL_PORT_BACKEND_BYTES ? 1 : -1];

#define DEFAULT_SYSFS        "/sys"
#define LATENCY_TIMER_MAX_MS 255u
#define PATH_BYTES           512

/* The quirk table: one row per kernel driver (the name sysfs gives the tty's driver). */
static const struct {
    const char *driver;
    unsigned quirks;
} quirk_table[] = {
    {"pty", FBRL_PORT_Q_PTY},
    {"ftdi_sio", FBRL_PORT_Q_USB | FBRL_PORT_Q_LATENCY_TIMER | FBRL_PORT_Q_LOW_LATENCY},
    {"ch341", FBRL_PORT_Q_USB | FBRL_PORT_Q_COARSE_BAUD},
    {"cp210x", FBRL_PORT_Q_USB},
    {"pl2303", FBRL_PORT_Q_USB},
    {"cdc_acm", FBRL_PORT_Q_USB},
    {"serial8250", FBRL_PORT_Q_LOW_LATENCY},
    {"port", FBRL_PORT_Q_LOW_LATENCY}, /* Linux 6.x: serial core ports (8250 ...) */
};

static unsigned quirks_of(const char *driver)
{
    for (size_t k = 0; k < sizeof quirk_table / sizeof quirk_table[0]; k++)
        if (strcmp(quirk_table[k].driver, driver) == 0)
            return quirk_table[k].quirks;
    return 0;
}

/* ---- options ---- */

void fbrl_port_options_init(fbrl_port_options *o)
{
    static const fbrl_uart_config line = FBRL_UART_CONFIG_DEFAULT;
    if (o == NULL)
        return;
    memset(o, 0, sizeof *o);
    o->line = line;
    o->connect_timeout_ms = 5000u;
    o->low_latency = 1;
    o->latency_timer_ms = 1u;
}

static int parse_ulong(const char *s, unsigned long lo, unsigned long hi, unsigned long *out)
{
    unsigned long v = 0;
    if (s == NULL || *s == '\0')
        return -1;
    for (; *s; s++) {
        if (*s < '0' || *s > '9' || v > (ULONG_MAX - 9u) / 10u)
            return -1;
        v = v * 10u + (unsigned long)(*s - '0');
    }
    if (v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

/* value is one of the '|'-separated words of list: its index, or -1. */
static int word_index(const char *value, const char *list)
{
    size_t n = strlen(value);
    for (int k = 0; *list; k++) {
        const char *end = strchr(list, '|');
        size_t len = end ? (size_t)(end - list) : strlen(list);
        if (len == n && strncmp(list, value, n) == 0)
            return k;
        if (!end)
            break;
        list = end + 1;
    }
    return -1;
}

fbrl_status fbrl_port_set_option(fbrl_port_options *o, const char *key, const char *value)
{
    unsigned long n;
    int w;
    if (o == NULL || key == NULL || value == NULL)
        return FBRL_EINVAL;
    if (strcmp(key, "baud") == 0) {
        if (parse_ulong(value, 1, 4000000ul, &n) != 0)
            return FBRL_EINVAL;
        o->line.baud = (uint32_t)n;
    } else if (strcmp(key, "data-bits") == 0) {
        if (parse_ulong(value, 5, 8, &n) != 0)
            return FBRL_EINVAL;
        o->line.data_bits = (uint8_t)n;
    } else if (strcmp(key, "stop-bits") == 0) {
        if (parse_ulong(value, 1, 2, &n) != 0)
            return FBRL_EINVAL;
        o->line.stop_bits = (uint8_t)n;
    } else if (strcmp(key, "parity") == 0) {
        static const fbrl_parity par[] = {FBRL_PARITY_NONE, FBRL_PARITY_EVEN, FBRL_PARITY_ODD};
        if ((w = word_index(value, "none|even|odd|N|E|O|n|e|o")) < 0)
            return FBRL_EINVAL;
        o->line.parity = par[w % 3];
    } else if (strcmp(key, "flow") == 0) {
        if ((w = word_index(value, "none|xonxoff")) < 0)
            return FBRL_EINVAL;
        o->line.flow = w ? FBRL_FLOW_XONXOFF : FBRL_FLOW_NONE;
    } else if (strcmp(key, "low-latency") == 0 || strcmp(key, "thread") == 0) {
        if ((w = word_index(value, "off|on|0|1")) < 0)
            return FBRL_EINVAL;
        *(key[0] == 'l' ? &o->low_latency : &o->service_thread) = w % 2;
    } else if (strcmp(key, "latency-timer") == 0) {
        if (parse_ulong(value, 1, LATENCY_TIMER_MAX_MS, &n) != 0)
            return FBRL_EINVAL;
        o->latency_timer_ms = (unsigned)n;
    } else {
        return FBRL_EINVAL;
    }
    return FBRL_OK;
}

/* "key=value&key=value" into o (all or nothing). */
static fbrl_status apply_query(fbrl_port_options *o, char *q)
{
    fbrl_port_options tmp = *o;
    while (q && *q) {
        char *amp = strchr(q, '&'), *eq;
        if (amp)
            *amp = '\0';
        if ((eq = strchr(q, '=')) == NULL)
            return FBRL_EINVAL;
        *eq = '\0';
        fbrl_status st = fbrl_port_set_option(&tmp, q, eq + 1);
        if (st != FBRL_OK)
            return st;
        q = amp ? amp + 1 : NULL;
    }
    *o = tmp;
    return FBRL_OK;
}

/* ---- sysfs ---- */

/* src into dst, cut to fit. */
static void copy_text(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

/* The tty's name without "/dev/" and directories (after following symlinks such as
 * /dev/serial/by-id/...). */
static void tty_name(const char *path, char *out, size_t cap)
{
    char real[PATH_MAX];
    const char *p = realpath(path, real) ? real : path;
    const char *slash = strrchr(p, '/');
    copy_text(out, cap, slash ? slash + 1 : p);
}

static int read_small(const char *path, char *buf, size_t cap)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return -1;
    ssize_t n = read(fd, buf, cap - 1);
    close(fd);
    if (n < 0)
        return -1;
    buf[n] = '\0';
    return 0;
}

/* A latency timer file's value in ms, or -1. */
static int read_ms(const char *path)
{
    char buf[32];
    unsigned long v;
    if (read_small(path, buf, sizeof buf) != 0)
        return -1;
    buf[strcspn(buf, " \n")] = '\0';
    return parse_ulong(buf, 0, 100000ul, &v) == 0 ? (int)v : -1;
}

static void latency_path(const char *root, const char *name, char *out, size_t cap)
{
    char tn[64];
    tty_name(name, tn, sizeof tn);
    snprintf(out, cap, "%s/bus/usb-serial/devices/%s/latency_timer", root ? root : DEFAULT_SYSFS, tn);
}

fbrl_status fbrl_port_usb_info_get(const char *sysfs_root, const char *name, fbrl_port_usb_info *out)
{
    char tn[64], path[PATH_BYTES], link[PATH_BYTES];
    if (name == NULL || out == NULL || name[0] == '\0')
        return FBRL_EINVAL;
    memset(out, 0, sizeof *out);
    tty_name(name, tn, sizeof tn);
    snprintf(path, sizeof path, "%s/class/tty/%s/device/driver", sysfs_root ? sysfs_root : DEFAULT_SYSFS, tn);
    ssize_t n = readlink(path, link, sizeof link - 1);
    if (n > 0) {
        link[n] = '\0';
        const char *slash = strrchr(link, '/');
        copy_text(out->driver, sizeof out->driver, slash ? slash + 1 : link);
    }
    out->quirks = quirks_of(out->driver);
    latency_path(sysfs_root, name, path, sizeof path);
    out->latency_timer_ms = read_ms(path);
    if (out->latency_timer_ms >= 0)
        out->quirks |= FBRL_PORT_Q_USB | FBRL_PORT_Q_LATENCY_TIMER;
    return FBRL_OK;
}

fbrl_status fbrl_port_set_latency_timer(const char *sysfs_root, const char *name, unsigned ms, int *was)
{
    char path[PATH_BYTES], text[16];
    if (name == NULL || name[0] == '\0' || ms < 1 || ms > LATENCY_TIMER_MAX_MS)
        return FBRL_EINVAL;
    latency_path(sysfs_root, name, path, sizeof path);
    int old = read_ms(path);
    if (was)
        *was = old;
    if (old < 0)
        return FBRL_ENOENT;
    if ((unsigned)old == ms)
        return FBRL_OK;
    int fd = open(path, O_WRONLY | O_TRUNC | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return errno == ENOENT ? FBRL_ENOENT : FBRL_EIO;
    int len = snprintf(text, sizeof text, "%u\n", ms);
    ssize_t n = write(fd, text, (size_t)len);
    close(fd);
    /* read back: a file the kernel keeps as it was (a read-only attribute) is no success */
    return n == len && read_ms(path) == (int)ms ? FBRL_OK : FBRL_EIO;
}

/* ---- low latency on the open tty ---- */

static fbrl_port_low_latency set_low_latency(int fd)
{
#if defined(__linux__) && defined(TIOCGSERIAL) && defined(ASYNC_LOW_LATENCY)
    struct serial_struct ss;
    if (ioctl(fd, TIOCGSERIAL, &ss) != 0)
        return FBRL_PORT_LL_UNSUPPORTED;
    if (ss.flags & ASYNC_LOW_LATENCY)
        return FBRL_PORT_LL_SET;
    ss.flags |= ASYNC_LOW_LATENCY;
    if (ioctl(fd, TIOCSSERIAL, &ss) != 0)
        return errno == ENOTTY || errno == EINVAL || errno == ENOSYS ? FBRL_PORT_LL_UNSUPPORTED
                                                                     : FBRL_PORT_LL_REFUSED;
    if (ioctl(fd, TIOCGSERIAL, &ss) != 0 || !(ss.flags & ASYNC_LOW_LATENCY))
        return FBRL_PORT_LL_REFUSED;
    return FBRL_PORT_LL_SET;
#else
    (void)fd;
    return FBRL_PORT_LL_UNSUPPORTED;
#endif
}

/* After the open: learn the device, and put a tty into low-latency mode. */
static void tune(fbrl_port *p, const fbrl_port_options *o)
{
    const fbrl_uart_posix *px = (const fbrl_uart_posix *)(const void *)p->backend.bytes;
    p->latency_timer_ms = p->latency_timer_was_ms = -1;
    if (px->is_socket) {
        p->kind = FBRL_PORT_TCP;
        p->quirks = FBRL_PORT_Q_SOCKET;
        return;
    }
    if (px->is_pty) {
        copy_text(p->driver, sizeof p->driver, "pty");
        p->quirks = quirks_of("pty");
        if (p->kind != FBRL_PORT_SIM)
            p->kind = FBRL_PORT_PTY;
    } else {
        fbrl_port_usb_info info;
        fbrl_port_usb_info_get(o->sysfs_root, p->name, &info);
        copy_text(p->driver, sizeof p->driver, info.driver);
        p->quirks = info.quirks;
        p->latency_timer_ms = info.latency_timer_ms;
    }
    if (!o->low_latency)
        return;
    p->low_latency = set_low_latency(px->fd);
    if (p->quirks & FBRL_PORT_Q_LATENCY_TIMER) {
        int was = -1;
        if (fbrl_port_set_latency_timer(o->sysfs_root, p->name, o->latency_timer_ms, &was) == FBRL_OK &&
            was != (int)o->latency_timer_ms)
            p->latency_timer_was_ms = was;
        fbrl_port_usb_info info;
        fbrl_port_usb_info_get(o->sysfs_root, p->name, &info);
        p->latency_timer_ms = info.latency_timer_ms;
    }
}

/* ---- open, describe, close ---- */

#define SIM_PREFIX "sim:"
#define TCP_PREFIX "tcp:"

fbrl_status fbrl_port_open(fbrl_port *p, const char *url, const fbrl_port_options *opt)
{
    fbrl_port_options o;
    char spec[FBRL_PORT_NAME_MAX + 256];
    if (p == NULL || url == NULL || url[0] == '\0' || strlen(url) >= sizeof spec)
        return FBRL_EINVAL;
    if (opt)
        o = *opt;
    else
        fbrl_port_options_init(&o);
    memset(p, 0, sizeof *p);
    copy_text(spec, sizeof spec, url);
    char *q = strchr(spec, '?');
    if (q) {
        *q++ = '\0';
        fbrl_status st = apply_query(&o, q);
        if (st != FBRL_OK)
            return st;
    }
    if (spec[0] == '\0' || strlen(spec) >= sizeof p->name)
        return FBRL_EINVAL;
    const char *path = spec;
    if (strncmp(spec, SIM_PREFIX, strlen(SIM_PREFIX)) == 0 || strcmp(spec, "sim") == 0) {
        if (o.sim_start == NULL)
            return FBRL_EUNSUPPORTED;
        const char *arg = spec[3] == ':' ? spec + strlen(SIM_PREFIX) : "";
        fbrl_status st = o.sim_start(o.sim_ctx, arg, p->name, sizeof p->name);
        if (st != FBRL_OK) {
            if (o.sim_stop)
                o.sim_stop(o.sim_ctx);
            return st;
        }
        p->kind = FBRL_PORT_SIM;
        p->sim_running = 1;
        p->sim_stop = o.sim_stop;
        p->sim_ctx = o.sim_ctx;
        path = p->name;
    } else {
        copy_text(p->name, sizeof p->name, spec);
    }
    fbrl_uart_posix_options po = FBRL_UART_POSIX_OPTIONS_DEFAULT;
    po.service_thread = o.service_thread;
    po.connect_timeout_ms = o.connect_timeout_ms;
    fbrl_status st = fbrl_uart_posix_open((fbrl_uart_posix *)(void *)p->backend.bytes, &p->uart, path,
                                          &o.line, p->rx, sizeof p->rx, p->tx, sizeof p->tx, &po);
    if (st != FBRL_OK) {
        fbrl_port_close(p);
        return st;
    }
    p->open = 1;
    tune(p, &o);
    return FBRL_OK;
}

fbrl_uart *fbrl_port_uart(fbrl_port *p) { return p != NULL && p->open ? &p->uart : NULL; }

static const char *low_latency_text(const fbrl_port *p, char *buf, size_t cap)
{
    if (p->latency_timer_ms >= 0) {
        if (p->latency_timer_was_ms >= 0)
            snprintf(buf, cap, "latency timer %d ms (was %d)", p->latency_timer_ms, p->latency_timer_was_ms);
        else
            snprintf(buf, cap, "latency timer %d ms%s", p->latency_timer_ms,
                     p->latency_timer_ms > 1 ? " (not writable: see docs/serial.md)" : "");
        return buf;
    }
    switch (p->low_latency) {
    case FBRL_PORT_LL_SET: return "on";
    case FBRL_PORT_LL_UNSUPPORTED: return "not supported";
    case FBRL_PORT_LL_REFUSED: return "refused by the driver";
    default: return "off";
    }
}

fbrl_status fbrl_port_describe(const fbrl_port *p, char *buf, size_t cap)
{
    fbrl_uart_config l;
    char ll[96];
    if (p == NULL || buf == NULL || cap == 0)
        return FBRL_EINVAL;
    if (!p->open || fbrl_uart_get_config(&p->uart, &l) != FBRL_OK) {
        snprintf(buf, cap, "not open");
        return FBRL_ESTATE;
    }
    int n = snprintf(buf, cap, "%s (%lu %u%c%u, %s", p->name, (unsigned long)l.baud, (unsigned)l.data_bits,
                     (char)l.parity, (unsigned)l.stop_bits,
                     l.flow == FBRL_FLOW_XONXOFF ? "XON/XOFF" : "no flow control");
    if (n < 0 || (size_t)n >= cap)
        return FBRL_ENOSPC;
    if (p->kind == FBRL_PORT_TCP)
        n += snprintf(buf + n, cap - (size_t)n, "; TCP serial server)");
    else
        n += snprintf(buf + n, cap - (size_t)n, "; %s, low latency: %s)", p->driver[0] ? p->driver : "tty",
                      low_latency_text(p, ll, sizeof ll));
    return (size_t)n < cap ? FBRL_OK : FBRL_ENOSPC;
}

fbrl_status fbrl_port_close(fbrl_port *p)
{
    fbrl_status st = FBRL_OK;
    if (p == NULL)
        return FBRL_EINVAL;
    if (p->open)
        st = fbrl_uart_close(&p->uart);
    p->open = 0;
    if (p->sim_running && p->sim_stop)
        p->sim_stop(p->sim_ctx);
    p->sim_running = 0;
    return st;
}

/* ---- the serial ports this machine has ---- */

#define DEFAULT_DEV       "/dev"
#define USB_DEVICE_LEVELS 4 /* a tty's device dir to its USB device: port, interface, device */

/* a "/" b into out; -1 (out "") when it does not fit. */
static int path_join(char *out, size_t cap, const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    out[0] = '\0';
    if (na + 1 + nb + 1 > cap)
        return -1;
    memcpy(out, a, na);
    out[na] = '/';
    memcpy(out + na + 1, b, nb + 1);
    return 0;
}

/* The first line of DIR/NAME into out ("" if there is none). */
static void read_attr(const char *dir, const char *name, char *out, size_t cap)
{
    char path[PATH_BYTES];
    out[0] = '\0';
    if (cap > 1 && path_join(path, sizeof path, dir, name) == 0 && read_small(path, out, cap) == 0)
        out[strcspn(out, "\r\n")] = '\0';
}

/* The USB device above a tty's device directory: the nearest parent with an idVendor. */
static void usb_details(const char *devdir, fbrl_port_entry *e)
{
    char dir[PATH_MAX], text[16];
    if (realpath(devdir, dir) == NULL)
        return;
    for (int level = 0; level < USB_DEVICE_LEVELS; level++) {
        unsigned long vid, pid;
        read_attr(dir, "idVendor", text, sizeof text);
        if (text[0]) {
            char ptext[16];
            read_attr(dir, "idProduct", ptext, sizeof ptext);
            char *end1, *end2;
            vid = strtoul(text, &end1, 16);
            pid = strtoul(ptext, &end2, 16);
            if (*end1 == '\0' && *end2 == '\0' && ptext[0]) {
                e->usb = 1;
                e->vid = (unsigned)vid;
                e->pid = (unsigned)pid;
            }
            read_attr(dir, "product", e->description, sizeof e->description);
            read_attr(dir, "manufacturer", e->manufacturer, sizeof e->manufacturer);
            read_attr(dir, "serial", e->serial, sizeof e->serial);
            return;
        }
        char *slash = strrchr(dir, '/');
        if (slash == NULL || slash == dir)
            return;
        *slash = '\0';
    }
}

/* A tty of class/tty that is a serial port: it has a device, and an 8250 UART is there. */
static int is_serial_port(const char *ttydir)
{
    char path[PATH_BYTES], type[16];
    struct stat sb;
    if (path_join(path, sizeof path, ttydir, "device") != 0 || stat(path, &sb) != 0)
        return 0;
    read_attr(ttydir, "type", type, sizeof type); /* 8250: 0 = no UART at this address */
    return strcmp(type, "0") != 0;
}

/* The DEV/serial/by-id name that leads to device (the first in name order), or "".
 * readdir, not scandir: the library never allocates. */
static void by_id_name(const char *dev_root, const char *device, char *out, size_t cap)
{
    char dir[PATH_BYTES], path[PATH_BYTES], real[PATH_MAX];
    struct dirent *d;
    out[0] = '\0';
    if (path_join(dir, sizeof dir, dev_root, "serial/by-id") != 0)
        return;
    DIR *dp = opendir(dir);
    if (dp == NULL)
        return;
    while ((d = readdir(dp)) != NULL) {
        if (d->d_name[0] == '.' || path_join(path, sizeof path, dir, d->d_name) != 0 ||
            realpath(path, real) == NULL || strcmp(strrchr(real, '/') + 1, device) != 0)
            continue;
        if (!out[0] || strcmp(path, out) < 0)
            copy_text(out, cap, path);
    }
    closedir(dp);
}

/* Puts the entry for tty into out[0 .. *n) in device-name order, keeping the first max. */
static void insert_sorted(fbrl_port_entry *out, size_t max, size_t *n, const char *tty, const char *ttydir,
                          const char *sysfs_root, const char *dev_root)
{
    fbrl_port_entry e;
    fbrl_port_usb_info info;
    char devdir[PATH_BYTES];
    size_t at;
    memset(&e, 0, sizeof e);
    if (path_join(e.device, sizeof e.device, dev_root, tty) != 0)
        return;
    for (at = *n; at > 0 && strcmp(out[at - 1].device, e.device) > 0; at--)
        ;
    if (at >= max)
        return;
    if (path_join(devdir, sizeof devdir, ttydir, "device") == 0)
        usb_details(devdir, &e);
    by_id_name(dev_root, tty, e.by_id, sizeof e.by_id);
    fbrl_port_usb_info_get(sysfs_root, tty, &info);
    copy_text(e.driver, sizeof e.driver, info.driver);
    e.latency_timer_ms = info.latency_timer_ms;
    if (*n == max)
        (*n)--; /* the last one drops out */
    memmove(&out[at + 1], &out[at], (*n - at) * sizeof *out);
    out[at] = e;
    (*n)++;
}

fbrl_status fbrl_port_list(const char *sysfs_root, const char *dev_root, fbrl_port_entry *out, size_t max,
                           size_t *count)
{
    char dir[PATH_BYTES], ttydir[PATH_BYTES];
    struct dirent *d;
    size_t found = 0, kept = 0;
    if (count == NULL || (out == NULL && max > 0))
        return FBRL_EINVAL;
    *count = 0;
    if (path_join(dir, sizeof dir, sysfs_root ? sysfs_root : DEFAULT_SYSFS, "class/tty") != 0)
        return FBRL_EINVAL;
    DIR *dp = opendir(dir);
    if (dp == NULL)
        return FBRL_EUNSUPPORTED;
    while ((d = readdir(dp)) != NULL) {
        if (d->d_name[0] == '.' || path_join(ttydir, sizeof ttydir, dir, d->d_name) != 0 ||
            !is_serial_port(ttydir))
            continue;
        found++;
        insert_sorted(out, max, &kept, d->d_name, ttydir, sysfs_root, dev_root ? dev_root : DEFAULT_DEV);
    }
    closedir(dp);
    *count = found;
    return FBRL_OK;
}
