/* SPDX-License-Identifier: MIT */
/* test_link_probe: the probe's bytes, its markers, and the parse of its echo, as the
 * controller of docs/rapl-commands.md 1 would answer it (src/link_probe.c). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "link_internal.h"

/* The controller's echo of a probe that found `held` characters on the line. */
static size_t echo_of(const uint8_t *probe, size_t n, size_t held, uint8_t *out)
{
    size_t k = 0, on_line = held;
    for (size_t i = 0; i < n; i++) {
        if (probe[i] == 0x11) /* XON: not echoed */
            continue;
        if (probe[i] == 0x18) { /* CAN: a triple per character on the line */
            for (; on_line > 0; on_line--)
                out[k++] = '\b', out[k++] = ' ', out[k++] = '\b';
            continue;
        }
        out[k++] = probe[i];
        on_line++;
    }
    return k;
}

static void probes_and_their_echoes(void **state)
{
    (void)state;
    fbrl_link_probe p;
    uint8_t probe[FBRLI_PROBE_MAX], echo[64];
    memset(&p, 0, sizeof p);
    assert_int_equal(fbrli_probe_make(&p, probe, 1), 8);
    assert_int_equal(probe[0], 0x11);
    assert_memory_equal(probe + 1, "?\x18?\x18", 4);
    /* the line held "HOME": the first CAN erases it and the '?' */
    size_t n = echo_of(probe, 8, 4, echo);
    for (size_t i = 0; i < n; i++) {
        assert_false(fbrli_probe_answered(&p));
        fbrli_probe_echo(&p, echo[i], 1);
    }
    assert_true(fbrli_probe_answered(&p));
    assert_true(fbrli_probe_ended(&p));
    assert_int_equal(fbrli_probe_erased(&p), 5);
    /* an empty line: its own '?' only; no XON */
    assert_int_equal(fbrli_probe_make(&p, probe, 0), 7);
    n = echo_of(probe, 7, 0, echo);
    for (size_t i = 0; i < n; i++)
        fbrli_probe_echo(&p, echo[i], 1);
    assert_int_equal(fbrli_probe_erased(&p), 1);
    /* a damaged echo: answered ends whole, but the parse is no evidence */
    fbrli_probe_make(&p, probe, 0);
    n = echo_of(probe, 7, 2, echo);
    echo[1] = '!';
    for (size_t i = 0; i < n; i++)
        fbrli_probe_echo(&p, echo[i], 1);
    assert_true(fbrli_probe_answered(&p));
    assert_int_equal(fbrli_probe_erased(&p), -1);
    /* not parsed (a later probe): no evidence either */
    fbrli_probe_make(&p, probe, 0);
    n = echo_of(probe, 7, 0, echo);
    for (size_t i = 0; i < n; i++)
        fbrli_probe_echo(&p, echo[i], 0);
    assert_true(fbrli_probe_answered(&p));
    assert_int_equal(fbrli_probe_erased(&p), -1);
}

/* 216 probes in a row end in markers no two alike, and any two markers differ in two bits
 * or more: an older probe's echo is never taken for the latest one's. */
static void markers_tell_probes_apart(void **state)
{
    (void)state;
    fbrl_link_probe p;
    uint8_t probe[FBRLI_PROBE_MAX];
    static char seen[216][3];
    memset(&p, 0, sizeof p);
    for (int k = 0; k < 216; k++) {
        fbrli_probe_make(&p, probe, 0);
        memcpy(seen[k], probe + 4, 3);
        for (int j = 0; j < k; j++)
            assert_false(memcmp(seen[j], seen[k], 3) == 0);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                unsigned x = (unsigned)(seen[k][i] ^ seen[0][j]);
                assert_true(x == 0 || (x & (x - 1)) != 0);
            }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(probes_and_their_echoes),
        cmocka_unit_test(markers_tell_probes_apart),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
