/* SPDX-License-Identifier: MIT */
/* test_link_modes: the modes a session set, noted as the lines ran and listed in the order
 * a reconnect sends them again (src/link_modes.c; docs/link.md 1, "Modes"). The link's
 * part, noting what ran and sending it again, is tested against fbrlsim by mon_safe. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "link_internal.h"

static fbrl_link_modes m;

static int setup(void **state)
{
    (void)state;
    memset(&m, 0x55, sizeof m); /* init must not rely on zeroed storage */
    fbrl_link_modes_init(&m);
    return 0;
}

static void ran(const char *line) { fbrli_link_modes_note(&m, line, FBRL_LINK_UNITS_INCH); }

/* The lines, joined by '|'. */
static const char *listed(void)
{
    static char out[2048];
    const char *line;
    out[0] = '\0';
    for (size_t i = 0; (line = fbrl_link_modes_line(&m, i)) != NULL; i++) {
        if (i)
            strcat(out, "|");
        strcat(out, line);
    }
    return out;
}

static void nothing_set_nothing_listed(void **state)
{
    (void)state;
    assert_null(fbrl_link_modes_line(&m, 0));
    assert_null(fbrl_link_modes_line(NULL, 0));
    ran("MOVE P1");
    ran("LIMP");
    ran("OUTPUT 3");
    ran("LOCK 2");
    ran("V1=SPEED");
    ran("SPEEDY 5");
    ran("HERE H1");
    assert_string_equal(listed(), "");
}

/* The last of each wins; the units come first, whatever order they ran in. */
static void last_wins_units_first(void **state)
{
    (void)state;
    ran("SPEED 5");
    ran("FLASH 2");
    ran("METRIC");
    ran("SPEED 20");
    ran("NOFLASH");
    ran("NOMETRIC");
    assert_string_equal(listed(), "NOMETRIC|SPEED 20|NOFLASH");
    ran("/016 30"); /* a token line is the same command */
    assert_string_equal(listed(), "NOMETRIC|/016 30|NOFLASH");
}

/* TOOL copies its location: the POINT that defined it goes along, in the units it was
 * typed in; a later POINT of the same name (a scratch point reused for a move) does not
 * change the tool's. */
static void tool_takes_its_point(void **state)
{
    (void)state;
    ran("POINT FBRLT1,0,0,2.5,0,0,0");
    fbrli_link_modes_note(&m, "TOOL FBRLT1", FBRL_LINK_UNITS_INCH);
    ran("POINT FBRLT1,12,3,8,0,-90,0");
    ran("SPEED 5");
    assert_string_equal(listed(), "POINT FBRLT1,0,0,2.5,0,0,0|TOOL FBRLT1|SPEED 5");
    assert_int_equal(fbrli_link_modes_units(&m, 0), FBRL_LINK_UNITS_INCH);
    assert_int_equal(fbrli_link_modes_units(&m, 1), FBRLI_NO_LENGTHS);
    assert_int_equal(fbrli_link_modes_units(&m, 2), FBRLI_NO_LENGTHS);
    assert_int_equal(fbrli_link_modes_units(&m, 3), FBRLI_NO_LENGTHS);
    /* typed in millimetres: the units are kept with it */
    fbrli_link_modes_note(&m, "POINT TL,0,0,50,0,0,0", FBRL_LINK_UNITS_MM);
    ran("TOOL TL");
    assert_string_equal(listed(), "POINT TL,0,0,50,0,0,0|TOOL TL|SPEED 5");
    assert_int_equal(fbrli_link_modes_units(&m, 0), FBRL_LINK_UNITS_MM);
    /* a location the session did not define last: the TOOL alone */
    ran("POINT FBRLT2,1,2,3,0,0,0");
    ran("TOOL FBRLT1");
    assert_string_equal(listed(), "TOOL FBRLT1|SPEED 5");
    ran("POINT TLONG,0,0,1,0,0,0");
    ran("TOOL TL"); /* TL is not TLONG */
    assert_string_equal(listed(), "TOOL TL|SPEED 5");
    ran("TOOL"); /* the null tool */
    assert_string_equal(listed(), "TOOL|SPEED 5");
}

/* GAIN n,v sets motor n; GAIN 0,v every motor (the earlier ones are void); GAIN n alone
 * only prints. */
static void gains_by_motor(void **state)
{
    (void)state;
    ran("GAIN 3,0.5");
    ran("GAIN 1,2");
    ran("GAIN 3,0.75");
    ran("GAIN 2");
    assert_string_equal(listed(), "GAIN 1,2|GAIN 3,0.75");
    ran("GAIN 0,1");
    assert_string_equal(listed(), "GAIN 0,1");
    ran("GAIN 4, 3");
    ran("GAIN 9,1"); /* no such motor */
    ran("GAIN 12,1");
    assert_string_equal(listed(), "GAIN 0,1|GAIN 4, 3");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(nothing_set_nothing_listed, setup),
        cmocka_unit_test_setup(last_wins_units_first, setup),
        cmocka_unit_test_setup(tool_takes_its_point, setup),
        cmocka_unit_test_setup(gains_by_motor, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
