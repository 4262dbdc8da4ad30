/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/fbrl.h"

/* The macros, the string and the running library agree with each other. */
static void macros_and_runtime_agree(void **state)
{
    char want[32];
    (void)state;
    snprintf(want, sizeof want, "%d.%d.%d", FBRL_VERSION_MAJOR, FBRL_VERSION_MINOR, FBRL_VERSION_PATCH);
    assert_string_equal(FBRL_VERSION_STRING, want);
    assert_string_equal(fbrl_version(), want);
    assert_int_equal(fbrl_version_number(),
                     FBRL_VERSION_MAJOR * 10000 + FBRL_VERSION_MINOR * 100 + FBRL_VERSION_PATCH);
}

/* The header's version is the one CMake's project() names (read from the top CMakeLists.txt). */
static void version_comes_from_the_project(void **state)
{
    char line[256], want[64];
    int found = 0;
    FILE *f = fopen(FBRL_TEST_SRCDIR "/CMakeLists.txt", "r");
    (void)state;
    assert_non_null(f);
    snprintf(want, sizeof want, "project(fbrl VERSION %s ", FBRL_VERSION_STRING);
    while (fgets(line, sizeof line, f) != NULL)
        if (strncmp(line, want, strlen(want)) == 0)
            found = 1;
    fclose(f);
    assert_true(found);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(macros_and_runtime_agree),
        cmocka_unit_test(version_comes_from_the_project),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
