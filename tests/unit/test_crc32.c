/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdint.h>

#include "fbrl/crc32.h"
#include "le.h"

static void crc32_matches_the_standard(void **state)
{
    (void)state;
    assert_int_equal(fbrl_crc32(0, "123456789", 9), 0xCBF43926u);
    assert_int_equal(fbrl_crc32(0, "", 0), 0);
    assert_int_equal(fbrl_crc32(0, "The quick brown fox jumps over the lazy dog", 43), 0x414FA339u);
    uint32_t part = fbrl_crc32(0, "1234", 4);
    assert_int_equal(fbrl_crc32(part, "56789", 5), 0xCBF43926u);
    assert_int_equal(fbrl_crc32(0x1234u, NULL, 10), 0x1234u);
}

/* Each single-bit change of a message changes its CRC (what the file formats rely on). */
static void crc32_sees_every_single_bit_flip(void **state)
{
    (void)state;
    unsigned char msg[64];
    for (unsigned i = 0; i < sizeof msg; i++)
        msg[i] = (unsigned char)(i * 37u + 11u);
    uint32_t good = fbrl_crc32(0, msg, sizeof msg);
    for (unsigned bit = 0; bit < 8 * sizeof msg; bit++) {
        msg[bit / 8] ^= (unsigned char)(1u << (bit % 8));
        assert_int_not_equal(fbrl_crc32(0, msg, sizeof msg), good);
        msg[bit / 8] ^= (unsigned char)(1u << (bit % 8));
    }
}

static void little_endian_fields(void **state)
{
    (void)state;
    unsigned char b[8];
    fbrl_le_put32(b, 0x11223344u);
    assert_int_equal(b[0], 0x44);
    assert_int_equal(b[3], 0x11);
    assert_int_equal(fbrl_le_get32(b), 0x11223344u);
    fbrl_le_put16(b, 0xBEEF);
    assert_int_equal(b[0], 0xEF);
    assert_int_equal(fbrl_le_get16(b), 0xBEEF);
    fbrl_le_put_double(b, 1.0); /* 0x3FF0000000000000 */
    assert_int_equal(b[7], 0x3F);
    assert_int_equal(b[6], 0xF0);
    assert_true(fbrl_le_get_double(b) == 1.0);
    fbrl_le_put64(b, 0x8000000000000001ull);
    assert_true(fbrl_le_get64(b) == 0x8000000000000001ull);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(crc32_matches_the_standard),
        cmocka_unit_test(crc32_sees_every_single_bit_flip),
        cmocka_unit_test(little_endian_fields),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
