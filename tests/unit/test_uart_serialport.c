/* SPDX-License-Identifier: MIT */
/* test_uart_serialport.c - the libserialport part: enumeration answers (possibly with
 * zero ports: CI machines have none), and names it cannot open give clear errors.
 * libserialport cannot drive a Linux pty, so data tests live in test_uart_posix.c. */
#define _XOPEN_SOURCE 700
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>
#include <cmocka.h>

#ifdef FBRL_HAVE_SERIALPORT
#include "fbrl/uart_serialport.h"

static void enumeration_answers(void **state)
{
    (void)state;
    fbrl_serial_port_info ports[32];
    size_t count = 12345, again = 0;
    assert_int_equal(fbrl_uart_serialport_list(ports, 32, &count), FBRL_OK);
    assert_true(count < 12345);
    for (size_t i = 0; i < count && i < 32; i++) {
        printf("# port %s (%s)", ports[i].name, ports[i].description);
        if (ports[i].usb)
            printf(" USB %04x:%04x", ports[i].vid, ports[i].pid);
        printf("\n");
        assert_true(ports[i].name[0] != '\0');
        assert_true(strlen(ports[i].name) < sizeof ports[i].name);
    }
    /* Counting only, and argument checks. */
    assert_int_equal(fbrl_uart_serialport_list(NULL, 0, &again), FBRL_OK);
    assert_int_equal(again, count);
    assert_int_equal(fbrl_uart_serialport_list(ports, 32, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_serialport_list(NULL, 3, &again), FBRL_EINVAL);
}

static void unopenable_names_give_errors(void **state)
{
    (void)state;
    static uint8_t rx[64], tx[64];
    fbrl_uart_serialport p;
    fbrl_uart u;
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(m >= 0);
    assert_int_equal(grantpt(m), 0);
    assert_int_equal(unlockpt(m), 0);
    /* A real pty: libserialport has no sysfs entry for it. */
    assert_int_equal(fbrl_uart_serialport_open(&p, &u, ptsname(m), &cfg, rx, 64, tx, 64), FBRL_EUNSUPPORTED);
    close(m);
    assert_int_equal(fbrl_uart_serialport_open(&p, &u, "/dev/fbrl-no-such-port", &cfg, rx, 64, tx, 64),
                     FBRL_ENOENT);
    assert_int_equal(fbrl_uart_serialport_open(&p, &u, "", &cfg, rx, 64, tx, 64), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_serialport_open(NULL, &u, "/dev/ttyS0", &cfg, rx, 64, tx, 64), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_serialport_open(&p, NULL, "/dev/ttyS0", &cfg, rx, 64, tx, 64), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_serialport_open(&p, &u, NULL, &cfg, rx, 64, tx, 64), FBRL_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(enumeration_answers),
        cmocka_unit_test(unopenable_names_give_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#else
/* Built without libserialport: nothing to test; report a skip. */
static void skipped(void **state)
{
    (void)state;
    skip();
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(skipped)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#endif
