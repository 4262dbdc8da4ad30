/* SPDX-License-Identifier: MIT */
/* test_port.c - opening ports by name over real ptys and a real TCP listener, the
 * option text, "sim:" through a hook that makes a real pty, low-latency mode refused
 * cleanly by a pty, and the USB latency timer through a fake sysfs tree in a temporary
 * directory (the real files of an FTDI adapter have the same names and format). */
#define _XOPEN_SOURCE 700 /* posix_openpt, grantpt, unlockpt, ptsname, mkdtemp, symlink */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "fbrl/port.h"

static fbrl_port port; /* large: not on the stack */

static int make_pty(char *name, size_t n)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(m >= 0);
    assert_int_equal(grantpt(m), 0);
    assert_int_equal(unlockpt(m), 0);
    assert_true(strlen(ptsname(m)) < n);
    strcpy(name, ptsname(m));
    return m;
}

static void options_from_text(void **state)
{
    (void)state;
    fbrl_port_options o;
    fbrl_port_options_init(&o);
    assert_int_equal(o.line.baud, 9600);
    assert_int_equal(o.line.flow, FBRL_FLOW_XONXOFF);
    assert_int_equal(o.low_latency, 1);
    assert_int_equal(fbrl_port_set_option(&o, "baud", "38400"), FBRL_OK);
    assert_int_equal(fbrl_port_set_option(&o, "parity", "even"), FBRL_OK);
    assert_int_equal(o.line.parity, FBRL_PARITY_EVEN);
    assert_int_equal(fbrl_port_set_option(&o, "parity", "O"), FBRL_OK);
    assert_int_equal(o.line.parity, FBRL_PARITY_ODD);
    assert_int_equal(fbrl_port_set_option(&o, "data-bits", "7"), FBRL_OK);
    assert_int_equal(fbrl_port_set_option(&o, "stop-bits", "2"), FBRL_OK);
    assert_int_equal(fbrl_port_set_option(&o, "flow", "none"), FBRL_OK);
    assert_int_equal(fbrl_port_set_option(&o, "low-latency", "off"), FBRL_OK);
    assert_int_equal(fbrl_port_set_option(&o, "latency-timer", "4"), FBRL_OK);
    assert_int_equal(o.line.baud, 38400);
    assert_int_equal(o.line.data_bits, 7);
    assert_int_equal(o.line.stop_bits, 2);
    assert_int_equal(o.line.flow, FBRL_FLOW_NONE);
    assert_int_equal(o.low_latency, 0);
    assert_int_equal(o.latency_timer_ms, 4);
    /* bad text: an error, nothing changed */
    fbrl_port_options before = o;
    static const char *const bad[][2] = {
        {"baud", "0"},      {"baud", "96OO"},        {"baud", ""},
        {"baud", "-9600"},  {"data-bits", "9"},      {"stop-bits", "3"},
        {"parity", "mark"}, {"flow", "rtscts"},      {"latency-timer", "256"},
        {"speed", "9600"},  {"low-latency", "maybe"}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(fbrl_port_set_option(&o, bad[k][0], bad[k][1]), FBRL_EINVAL);
    assert_memory_equal(&o, &before, sizeof o);
    assert_int_equal(fbrl_port_set_option(NULL, "baud", "1"), FBRL_EINVAL);
    assert_int_equal(fbrl_port_set_option(&o, NULL, "1"), FBRL_EINVAL);
}

/* A pty by path, options in the name: the settings reach the uart, the port knows it is
 * a pty, and the low-latency request a pty cannot take is reported, not an error. */
static void pty_by_path_with_options(void **state)
{
    (void)state;
    char name[64], url[128], desc[256];
    int m = make_pty(name, sizeof name);
    snprintf(url, sizeof url, "%s?baud=19200&stop-bits=2&flow=none", name);
    assert_int_equal(fbrl_port_open(&port, url, NULL), FBRL_OK);
    fbrl_uart_config c;
    assert_int_equal(fbrl_uart_get_config(fbrl_port_uart(&port), &c), FBRL_OK);
    assert_int_equal(c.baud, 19200);
    assert_int_equal(c.stop_bits, 2);
    assert_int_equal(c.flow, FBRL_FLOW_NONE);
    assert_int_equal(port.kind, FBRL_PORT_PTY);
    assert_true(port.quirks & FBRL_PORT_Q_PTY);
    assert_int_equal(port.low_latency, FBRL_PORT_LL_UNSUPPORTED);
    assert_int_equal(port.latency_timer_ms, -1);
    assert_int_equal(fbrl_port_describe(&port, desc, sizeof desc), FBRL_OK);
    assert_non_null(strstr(desc, name));
    assert_non_null(strstr(desc, "19200 8N2, no flow control"));
    assert_non_null(strstr(desc, "pty, low latency: not supported"));
    /* bytes flow both ways through the port's uart */
    size_t n;
    assert_int_equal(fbrl_uart_write(fbrl_port_uart(&port), "W2\r", 3, &n, 100), FBRL_OK);
    char buf[8];
    assert_int_equal(read(m, buf, sizeof buf), 3);
    assert_memory_equal(buf, "W2\r", 3);
    assert_int_equal(fbrl_port_close(&port), FBRL_OK);
    assert_null(fbrl_port_uart(&port));
    /* with low latency off nothing is tried */
    fbrl_port_options o;
    fbrl_port_options_init(&o);
    o.low_latency = 0;
    assert_int_equal(fbrl_port_open(&port, name, &o), FBRL_OK);
    assert_int_equal(port.low_latency, FBRL_PORT_LL_OFF);
    assert_int_equal(fbrl_port_describe(&port, desc, sizeof desc), FBRL_OK);
    assert_non_null(strstr(desc, "low latency: off"));
    assert_int_equal(fbrl_port_describe(&port, desc, 8), FBRL_ENOSPC);
    fbrl_port_close(&port);
    close(m);
}

static void bad_names(void **state)
{
    (void)state;
    assert_int_equal(fbrl_port_open(&port, "", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(NULL, "/dev/null", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, "/no/such/tty", NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_port_open(&port, "/dev/null", NULL), FBRL_ENOTTY);
    assert_int_equal(fbrl_port_open(&port, "tcp:", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, "tcp:localhost:x1", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, "/dev/null?baud=fast", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, "/dev/null?baud", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, "?baud=9600", NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_open(&port, "sim:", NULL), FBRL_EUNSUPPORTED); /* no hook */
    assert_null(fbrl_port_uart(&port));
    char desc[32];
    assert_int_equal(fbrl_port_describe(&port, desc, sizeof desc), FBRL_ESTATE);
}

/* ---- sim: through a hook that makes a real pty (the emulator's side is the master) ---- */

typedef struct sim_hook {
    int master, starts, stops;
    char arg[64];
    fbrl_status fail;
} sim_hook;

static fbrl_status hook_start(void *ctx, const char *arg, char *path, size_t cap)
{
    sim_hook *h = ctx;
    h->starts++;
    snprintf(h->arg, sizeof h->arg, "%s", arg);
    if (h->fail != FBRL_OK)
        return h->fail;
    h->master = make_pty(path, cap);
    return FBRL_OK;
}

static void hook_stop(void *ctx)
{
    sim_hook *h = ctx;
    h->stops++;
    if (h->master >= 0)
        close(h->master);
    h->master = -1;
}

static void sim_through_the_hook(void **state)
{
    (void)state;
    sim_hook h = {-1, 0, 0, "", FBRL_OK};
    fbrl_port_options o;
    fbrl_port_options_init(&o);
    o.sim_start = hook_start;
    o.sim_stop = hook_stop;
    o.sim_ctx = &h;
    assert_int_equal(fbrl_port_open(&port, "sim:state.sim?baud=38400", &o), FBRL_OK);
    assert_string_equal(h.arg, "state.sim");
    assert_int_equal(port.kind, FBRL_PORT_SIM);
    fbrl_uart_config c;
    assert_int_equal(fbrl_uart_get_config(fbrl_port_uart(&port), &c), FBRL_OK);
    assert_int_equal(c.baud, 38400);
    size_t n;
    assert_int_equal(fbrl_uart_write(fbrl_port_uart(&port), "HOME\r", 5, &n, 100), FBRL_OK);
    char buf[8];
    assert_int_equal(read(h.master, buf, sizeof buf), 5);
    assert_int_equal(fbrl_port_close(&port), FBRL_OK);
    assert_int_equal(h.stops, 1);
    /* "sim" alone works too; a hook that fails is stopped again and its error returned */
    assert_int_equal(fbrl_port_open(&port, "sim", &o), FBRL_OK);
    assert_string_equal(h.arg, "");
    fbrl_port_close(&port);
    h.fail = FBRL_EIO;
    assert_int_equal(fbrl_port_open(&port, "sim:", &o), FBRL_EIO);
    assert_int_equal(h.starts, 3);
    assert_int_equal(h.stops, 3);
}

/* ---- TCP ---- */

static void tcp_server_by_name(void **state)
{
    (void)state;
    int ls = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a;
    socklen_t al = sizeof a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    assert_int_equal(bind(ls, (struct sockaddr *)&a, sizeof a), 0);
    assert_int_equal(listen(ls, 1), 0);
    assert_int_equal(getsockname(ls, (struct sockaddr *)&a, &al), 0);
    char url[64], desc[256];
    snprintf(url, sizeof url, "tcp:127.0.0.1:%u", (unsigned)ntohs(a.sin_port));
    assert_int_equal(fbrl_port_open(&port, url, NULL), FBRL_OK);
    int c = accept(ls, NULL, NULL);
    assert_true(c >= 0);
    assert_int_equal(port.kind, FBRL_PORT_TCP);
    assert_true(port.quirks & FBRL_PORT_Q_SOCKET);
    assert_int_equal(fbrl_port_describe(&port, desc, sizeof desc), FBRL_OK);
    assert_non_null(strstr(desc, "TCP serial server"));
    size_t n;
    assert_int_equal(fbrl_uart_write(fbrl_port_uart(&port), "STATUS\r", 7, &n, 100), FBRL_OK);
    char buf[16];
    assert_int_equal(read(c, buf, sizeof buf), 7);
    fbrl_port_close(&port);
    close(c);
    close(ls);
}

/* ---- the USB latency timer in a fake sysfs tree ---- */

static char root[64];

static void put_file(const char *rel, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void mkdirs(const char *rel)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    for (char *p = path + strlen(root) + 1; *p; p++) {
        if (*p == '/') {
            *p = '\0';
            mkdir(path, 0755);
            *p = '/';
        }
    }
    mkdir(path, 0755);
}

static void latency_timer_in_fake_sysfs(void **state)
{
    (void)state;
    snprintf(root, sizeof root, "/tmp/fbrl-sysfs-XXXXXX");
    assert_non_null(mkdtemp(root));
    /* an FTDI adapter: ttyUSB7, driver ftdi_sio, latency timer 16 ms (the default) */
    mkdirs("bus/usb-serial/devices/ttyUSB7");
    mkdirs("bus/usb-serial/drivers/ftdi_sio");
    mkdirs("class/tty/ttyUSB7/device");
    put_file("bus/usb-serial/devices/ttyUSB7/latency_timer", "16\n");
    char link[256], target[256];
    snprintf(link, sizeof link, "%s/class/tty/ttyUSB7/device/driver", root);
    snprintf(target, sizeof target, "%s/bus/usb-serial/drivers/ftdi_sio", root);
    assert_int_equal(symlink(target, link), 0);
    /* a CH340 without a latency timer: ttyUSB8, driver ch341 */
    mkdirs("bus/usb-serial/drivers/ch341");
    mkdirs("class/tty/ttyUSB8/device");
    snprintf(link, sizeof link, "%s/class/tty/ttyUSB8/device/driver", root);
    snprintf(target, sizeof target, "%s/bus/usb-serial/drivers/ch341", root);
    assert_int_equal(symlink(target, link), 0);

    fbrl_port_usb_info info;
    assert_int_equal(fbrl_port_usb_info_get(root, "/dev/ttyUSB7", &info), FBRL_OK);
    assert_string_equal(info.driver, "ftdi_sio");
    assert_true(info.quirks & FBRL_PORT_Q_LATENCY_TIMER);
    assert_true(info.quirks & FBRL_PORT_Q_USB);
    assert_int_equal(info.latency_timer_ms, 16);
    assert_int_equal(fbrl_port_usb_info_get(root, "ttyUSB8", &info), FBRL_OK);
    assert_string_equal(info.driver, "ch341");
    assert_true(info.quirks & FBRL_PORT_Q_COARSE_BAUD);
    assert_false(info.quirks & FBRL_PORT_Q_LATENCY_TIMER);
    assert_int_equal(info.latency_timer_ms, -1);
    assert_int_equal(fbrl_port_usb_info_get(root, "ttyS0", &info), FBRL_OK); /* unknown: nothing */
    assert_string_equal(info.driver, "");
    assert_int_equal(info.quirks, 0);

    int was = 0;
    assert_int_equal(fbrl_port_set_latency_timer(root, "ttyUSB7", 1, &was), FBRL_OK);
    assert_int_equal(was, 16);
    assert_int_equal(fbrl_port_usb_info_get(root, "ttyUSB7", &info), FBRL_OK);
    assert_int_equal(info.latency_timer_ms, 1);
    assert_int_equal(fbrl_port_set_latency_timer(root, "ttyUSB7", 1, &was), FBRL_OK); /* already */
    assert_int_equal(was, 1);
    assert_int_equal(fbrl_port_set_latency_timer(root, "ttyUSB8", 1, &was), FBRL_ENOENT);
    assert_int_equal(was, -1);
    assert_int_equal(fbrl_port_set_latency_timer(root, "ttyUSB7", 0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_set_latency_timer(root, "ttyUSB7", 256, NULL), FBRL_EINVAL);
    /* a timer the kernel keeps as it is (a read-only attribute, even for root): EIO */
    if (access("/sys/devices/system/cpu/kernel_max", R_OK) == 0) {
        mkdirs("bus/usb-serial/devices/ttyUSB9");
        snprintf(link, sizeof link, "%s/bus/usb-serial/devices/ttyUSB9/latency_timer", root);
        assert_int_equal(symlink("/sys/devices/system/cpu/kernel_max", link), 0);
        assert_int_equal(fbrl_port_set_latency_timer(root, "ttyUSB9", 1, &was), FBRL_EIO);
        assert_true(was > 1);
    }
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
    assert_int_equal(system(cmd), 0);
}

/* ---- the port list: USB details and /dev/serial/by-id names in fake sysfs and dev trees ---- */

static void symlink_in_root(const char *target_rel, const char *link_rel)
{
    char link[256], target[256];
    snprintf(link, sizeof link, "%s/%s", root, link_rel);
    snprintf(target, sizeof target, "%s/%s", root, target_rel);
    assert_int_equal(symlink(target, link), 0);
}

static void port_list_in_fake_trees(void **state)
{
    (void)state;
    char sys[128], dev[128];
    snprintf(root, sizeof root, "/tmp/fbrl-ports-XXXXXX");
    assert_non_null(mkdtemp(root));
    snprintf(sys, sizeof sys, "%s/sys", root);
    snprintf(dev, sizeof dev, "%s/dev", root);
    /* an FTDI adapter as Linux shows it: the tty's device is the usb-serial port under the
     * interface 1-1:1.0 of the USB device 1-1, which has the ids and strings */
    mkdirs("sys/devices/usb1/1-1/1-1:1.0/ttyUSB3");
    put_file("sys/devices/usb1/1-1/idVendor", "0403\n");
    put_file("sys/devices/usb1/1-1/idProduct", "6001\n");
    put_file("sys/devices/usb1/1-1/product", "FT232R USB UART\n");
    put_file("sys/devices/usb1/1-1/manufacturer", "FTDI\n");
    put_file("sys/devices/usb1/1-1/serial", "A12345\n");
    mkdirs("sys/class/tty/ttyUSB3");
    symlink_in_root("sys/devices/usb1/1-1/1-1:1.0/ttyUSB3", "sys/class/tty/ttyUSB3/device");
    /* a CDC-ACM device (an Arduino): the tty's device is the interface itself */
    mkdirs("sys/devices/usb1/1-2/1-2:1.0");
    put_file("sys/devices/usb1/1-2/idVendor", "2341\n");
    put_file("sys/devices/usb1/1-2/idProduct", "0043\n");
    put_file("sys/devices/usb1/1-2/serial", "7553\n");
    mkdirs("sys/class/tty/ttyACM0");
    symlink_in_root("sys/devices/usb1/1-2/1-2:1.0", "sys/class/tty/ttyACM0/device");
    /* 8250 UARTs: ttyS0 is there (type 4, a 16550A), ttyS1 is not (type 0); tty1 is a console */
    mkdirs("sys/devices/platform/serial8250/tty/ttyS0");
    mkdirs("sys/class/tty/ttyS0");
    mkdirs("sys/class/tty/ttyS1");
    mkdirs("sys/class/tty/tty1");
    put_file("sys/class/tty/ttyS0/type", "4\n");
    put_file("sys/class/tty/ttyS1/type", "0\n");
    symlink_in_root("sys/devices/platform/serial8250/tty/ttyS0", "sys/class/tty/ttyS0/device");
    symlink_in_root("sys/devices/platform/serial8250/tty/ttyS0", "sys/class/tty/ttyS1/device");
    /* /dev: the ttys, and udev's stable name for the FTDI adapter */
    mkdirs("dev/serial/by-id");
    put_file("dev/ttyUSB3", "");
    put_file("dev/ttyACM0", "");
    put_file("dev/ttyS0", "");
    symlink_in_root("dev/ttyUSB3", "dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A12345-if00-port0");

    fbrl_port_entry e[8];
    size_t n = 0;
    assert_int_equal(fbrl_port_list(sys, dev, e, 8, &n), FBRL_OK);
    assert_int_equal(n, 3); /* ttyACM0 ttyS0 ttyUSB3: not the absent UART, not the console */
    char want[256];
    snprintf(want, sizeof want, "%s/ttyACM0", dev);
    assert_string_equal(e[0].device, want);
    assert_true(e[0].usb);
    assert_int_equal(e[0].vid, 0x2341);
    assert_int_equal(e[0].pid, 0x0043);
    assert_string_equal(e[0].serial, "7553");
    assert_string_equal(e[0].by_id, "");
    snprintf(want, sizeof want, "%s/ttyS0", dev);
    assert_string_equal(e[1].device, want);
    assert_false(e[1].usb);
    snprintf(want, sizeof want, "%s/ttyUSB3", dev);
    assert_string_equal(e[2].device, want);
    assert_true(e[2].usb);
    assert_int_equal(e[2].vid, 0x0403);
    assert_int_equal(e[2].pid, 0x6001);
    assert_string_equal(e[2].description, "FT232R USB UART");
    assert_string_equal(e[2].manufacturer, "FTDI");
    assert_string_equal(e[2].serial, "A12345");
    snprintf(want, sizeof want, "%s/serial/by-id/usb-FTDI_FT232R_USB_UART_A12345-if00-port0", dev);
    assert_string_equal(e[2].by_id, want);
    /* a short array: the count still says how many there are */
    assert_int_equal(fbrl_port_list(sys, dev, e, 1, &n), FBRL_OK);
    assert_int_equal(n, 3);
    snprintf(want, sizeof want, "%s/ttyACM0", dev); /* the first in name order */
    assert_string_equal(e[0].device, want);
    assert_int_equal(fbrl_port_list(sys, dev, NULL, 0, &n), FBRL_OK);
    assert_int_equal(n, 3);
    assert_int_equal(fbrl_port_list(sys, dev, e, 8, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_port_list(dev, dev, e, 8, &n), FBRL_EUNSUPPORTED); /* no class/tty */
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(options_from_text),
        cmocka_unit_test(pty_by_path_with_options),
        cmocka_unit_test(bad_names),
        cmocka_unit_test(sim_through_the_hook),
        cmocka_unit_test(tcp_server_by_name),
        cmocka_unit_test(latency_timer_in_fake_sysfs),
        cmocka_unit_test(port_list_in_fake_trees),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
