/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/fbrl.h"
#include "fbrl/cell_words.h"
#include "fbrl/workspace.h"

/* alignment probes, one struct per type (C99 has no alignof) */
#define PROBE(code, type) \
    struct probe_##code { \
        char c;           \
        type t;           \
    };
FBRL_ABI_TYPES(PROBE)
#undef PROBE

/* What the library answers is what this compiler lays out from the same headers. */
static void sizes_and_alignments_match_the_headers(void **state)
{
    (void)state;
#define CHECK(code, type)                                                                \
    assert_int_equal(fbrl_abi_size(FBRL_ABI_##code), sizeof(type));                      \
    assert_int_equal(fbrl_abi_align(FBRL_ABI_##code), offsetof(struct probe_##code, t)); \
    assert_string_equal(fbrl_abi_name(FBRL_ABI_##code), #type);
    FBRL_ABI_TYPES(CHECK)
#undef CHECK
}

/* Sizes a binding relies on: nonzero, a multiple of the alignment, a power-of-two alignment. */
static void every_type_is_sane(void **state)
{
    (void)state;
    for (int t = 0; t < FBRL_ABI_TYPE_COUNT; t++) {
        size_t s = fbrl_abi_size((fbrl_abi_type)t), a = fbrl_abi_align((fbrl_abi_type)t);
        assert_true(s > 0);
        assert_true(a > 0 && (a & (a - 1)) == 0);
        assert_int_equal(s % a, 0);
        assert_int_equal(strncmp(fbrl_abi_name((fbrl_abi_type)t), "fbrl_", 5), 0);
    }
}

static void unknown_codes_answer_zero(void **state)
{
    (void)state;
    assert_int_equal(fbrl_abi_size(FBRL_ABI_TYPE_COUNT), 0);
    assert_int_equal(fbrl_abi_align((fbrl_abi_type)-1), 0);
    assert_null(fbrl_abi_name((fbrl_abi_type)1000));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sizes_and_alignments_match_the_headers),
        cmocka_unit_test(every_type_is_sane),
        cmocka_unit_test(unknown_codes_answer_zero),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
