/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/status.h"

/* Every code in range has its own text and a name that matches its spelling. */
static void every_code_has_distinct_text(void **state)
{
    (void)state;
    for (int a = 0; a >= FBRL_STATUS_MIN; a--) {
        const char *ta = fbrl_status_str((fbrl_status)a);
        assert_non_null(ta);
        assert_string_not_equal(ta, "unknown status");
        assert_int_equal(strncmp(fbrl_status_name((fbrl_status)a), "FBRL_", 5), 0);
        for (int b = a - 1; b >= FBRL_STATUS_MIN; b--)
            assert_string_not_equal(ta, fbrl_status_str((fbrl_status)b));
    }
    assert_string_equal(fbrl_status_name(FBRL_EDEGENERATE), "FBRL_EDEGENERATE");
    assert_string_equal(fbrl_status_str(FBRL_OK), "ok");
}

static void unknown_codes_are_safe(void **state)
{
    (void)state;
    assert_string_equal(fbrl_status_str((fbrl_status)1), "unknown status");
    assert_string_equal(fbrl_status_str((fbrl_status)(FBRL_STATUS_MIN - 1)), "unknown status");
    assert_string_equal(fbrl_status_str((fbrl_status)-1000000), "unknown status");
    assert_string_equal(fbrl_status_name((fbrl_status)12345), "FBRL_E?");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_code_has_distinct_text),
        cmocka_unit_test(unknown_codes_are_safe),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
