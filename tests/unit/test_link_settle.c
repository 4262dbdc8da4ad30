/* SPDX-License-Identifier: MIT */
/* test_link_settle: the rule that settles a damaged reply by STATUS's LAST ERROR, and the
 * command kept while STATUS is read for it (src/link_settle.c; docs/link.md 3.5). The
 * reading itself is test_link's (a scripted controller). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "link_internal.h"

static void the_verdict(void **state)
{
    (void)state;
    fbrl_link_settle s;
    memset(&s, 0x55, sizeof s);
    fbrli_settle_begin(&s, "HOME", 4, FBRL_LINK_REPLY_NONE, 2, 0);
    assert_int_equal(fbrli_settle_verdict(&s, -1, 11), FBRL_OK);          /* NONE: nothing ever failed */
    assert_int_equal(fbrli_settle_verdict(&s, 29, 11), FBRL_ECONTROLLER); /* a new error: its refusal */
    assert_int_equal(fbrli_settle_verdict(&s, 11, 11), FBRL_EMAYBE);      /* the same: cannot tell */
    assert_int_equal(fbrli_settle_verdict(&s, 11, FBRLI_ERR_UNKNOWN), FBRL_EMAYBE); /* nothing to compare */
    fbrli_settle_begin(&s, "MOVE X", 6, FBRL_LINK_REPLY_NONE, 1, 1); /* an error line's shape */
    assert_int_equal(fbrli_settle_verdict(&s, 11, 11), FBRL_ECONTROLLER);
    assert_int_equal(fbrli_settle_verdict(&s, -1, 11), FBRL_EMAYBE);
}

static void the_command_is_kept(void **state)
{
    (void)state;
    fbrl_link_settle s;
    char line[FBRL_LINK_LINE_MAX + 1] = "STATUS";
    size_t len = 6;
    fbrl_link_reply kind = FBRL_LINK_REPLY_STATUS;
    unsigned attempts = 0;
    fbrli_settle_begin(&s, "V1=2", 4, FBRL_LINK_REPLY_NONE, 3, 0);
    fbrli_settle_ran(&s, FBRL_EPROTOCOL);
    fbrli_settle_ran(&s, FBRL_OK);
    fbrli_settle_ran(&s, FBRL_EMAYBE);
    fbrli_settle_ran(&s, FBRL_OK);
    assert_int_equal(s.ok, 2);
    assert_int_equal(s.bad, 1);
    assert_int_equal(s.maybe, 1);
    fbrli_settle_end(&s, line, &len, &kind, &attempts);
    assert_string_equal(line, "V1=2");
    assert_int_equal(len, 4);
    assert_int_equal(kind, FBRL_LINK_REPLY_NONE);
    assert_int_equal(attempts, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_verdict),
        cmocka_unit_test(the_command_is_kept),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
