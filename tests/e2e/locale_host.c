/* SPDX-License-Identifier: MIT */
/* locale_host.c - a host program embedding libfbrl that sets the user's locale, as a GUI
 * or a lab program does (setlocale(LC_ALL, "")), run under de_DE.UTF-8 (decimal comma) by
 * tests/e2e/with_de.sh. libfbrl must read and print numbers exactly as in the "C" locale:
 * the same FBRL program gives byte-for-byte the same output in both, float literals stay
 * numbers, locations print with a point, and fbrl_num round-trips every double. Exit 77
 * (skipped) when the locale is not active, with the reason. */
#include <locale.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fbrl/fbrl.h"
#include "support/vm_host.h"

static int fails;
#define CHECK(cond, ...)                  \
    do {                                  \
        if (!(cond)) {                    \
            printf("FAIL: " __VA_ARGS__); \
            printf("\n");                 \
            fails++;                      \
        }                                 \
    } while (0)

/* What an FBRL session prints: float literals, F. FS. FE., >FLOAT, REPRESENT, SEE of a
 * float literal, locations (DISPLAY-LOC, mapped too), matrices, the CALIBRATE-N report. */
static const char *const program =
    "1.5E0 F. 14.5E0 F. -0.125E0 F. 2.5E-3 FS. 1234.5E0 FE. 0.1E0 0.2E0 F+ F. CR "
    "S\" 3.75\" >FLOAT . F. S\" 3,75\" >FLOAT . CR "
    "PAD 8 1.5E0 REPRESENT . . PAD 8 TYPE CR "
    ": T 3.25E0 -1.0E-7 ; SEE T "
    "CREATE-LOC P 14.5E0 -2E0 1E0 0E0 -90E0 12.25E0 P DEFINE-LOC P DISPLAY-LOC CR "
    "P 0.75E0 0.75E0 0E0 RECTMAT RM ' RM SHOW-AUTOMAT "
    "CREATE-CAL C1 CREATE-CAL R1 CREATE-CAL-STRU S CREATE-LOC L "
    ": TEACH ( cal slot -- ) ( F: x y z -- ) L >R 0E0 -90E0 0E0 R> DEFINE-LOC L SET-CAL ; "
    "9.5E0 -2.5E0 2.5E0 C1 1 TEACH 13.5E0 -2.5E0 2.5E0 C1 2 TEACH 9.5E0 2.5E0 2.5E0 C1 3 TEACH "
    "9.8E0 -2.9E0 2.55E0 R1 1 TEACH 13.8E0 -2.76E0 2.55E0 R1 2 TEACH 9.63E0 2.1E0 2.55E0 R1 3 TEACH "
    "R1 C1 S CALIBRATE S WITH-CAL MAP-ON P DISPLAY-LOC MAP-OFF CR "
    "1 LOCATION ARRAY X1 ";

typedef struct {
    vmh_text out;
    fbrl_vm *vm;
    fbrl_glossary g;
    unsigned char mem[1 << 20];
} session;

static void run(session *s, const char *what)
{
    fbrl_vm_config cfg;
    memset(s, 0, sizeof *s);
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = s->mem;
    cfg.mem_size = sizeof s->mem;
    cfg.host.user = &s->out;
    cfg.host.write = vmh_write;
    if (fbrl_vm_create(&s->vm, &cfg) != FBRL_OK || fbrl_glossary_install(s->vm, &s->g) != FBRL_OK) {
        printf("FAIL: no VM (%s)\n", what);
        exit(1);
    }
    fbrl_status st = fbrl_vm_eval(s->vm, program, strlen(program));
    CHECK(st == FBRL_OK, "%s: the program failed: %s", what,
          fbrl_vm_last_error(s->vm) ? fbrl_vm_last_error(s->vm)->message : "?");
    fbrl_glossary_finish(&s->g);
}

static session de_run, c_run;

int main(void)
{
    char buf[128];
    if (!setlocale(LC_ALL, "") || strcmp(localeconv()->decimal_point, ",") != 0) {
        printf("SKIP: this test needs a locale with a decimal comma (LC_ALL=de_DE.UTF-8, as "
               "tests/e2e/with_de.sh sets); LC_ALL=%s gives decimal point '%s'\n",
               getenv("LC_ALL") ? getenv("LC_ALL") : "(unset)", localeconv()->decimal_point);
        return 77;
    }
    /* the C library really follows it: this is what broke libfbrl */
    snprintf(buf, sizeof buf, "%+.4f", 14.5);
    CHECK(strcmp(buf, "+14,5000") == 0, "printf under %s gives '%s'", setlocale(LC_NUMERIC, NULL), buf);
    printf("locale %s: printf(\"%%+.4f\", 14.5) = \"%s\", strtod(\"1.5\") = %g\n",
           setlocale(LC_NUMERIC, NULL), buf, strtod("1.5", NULL));

    /* the library's own conversions */
    double v = 0;
    CHECK(fbrl_num_parse("1.5E0", 5, &v) == FBRL_OK && v == 1.5, "fbrl_num_parse(1.5E0) = %g", v);
    CHECK(fbrl_num_parse("1,5", 3, &v) == FBRL_ESYNTAX, "fbrl_num_parse accepts 1,5");
    fbrl_num_fixed(buf, sizeof buf, 14.5, 10, 4, FBRL_NUM_PLUS, NULL);
    CHECK(strcmp(buf, "  +14.5000") == 0, "fbrl_num_fixed gives '%s'", buf);
    fbrl_loc l = {14.5, -2, 1, 0, -90, 0};
    char text[FBRL_LOC_TEXT_SIZE];
    CHECK(fbrl_loc_format(&l, 0, text, sizeof text) == FBRL_OK && strstr(text, "+14.5000") &&
              !strchr(text, ','),
          "fbrl_loc_format gives '%s'", text);
    printf("fbrl_loc_format: %s\n", text);
    /* 17 significant digits read back bit for bit, over many doubles */
    uint64_t x = 88172645463325252ull;
    int trips = 0;
    for (int i = 0; i < 100000; i++) {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        double d, back;
        memcpy(&d, &x, sizeof d);
        if (!isfinite(d))
            continue;
        fbrl_num_general(buf, sizeof buf, d, 17, NULL);
        if (fbrl_num_parse(buf, strlen(buf), &back) != FBRL_OK || memcmp(&back, &d, sizeof d) != 0) {
            printf("FAIL: %s does not read back\n", buf);
            fails++;
            break;
        }
        trips++;
    }
    printf("%d doubles printed and read back bit for bit\n", trips);

    /* the language: the same output under de_DE as under C */
    run(&de_run, "de_DE");
    setlocale(LC_ALL, "C");
    run(&c_run, "C");
    CHECK(strcmp(de_run.out.s, c_run.out.s) == 0, "FBRL output differs:\n--- de_DE:\n%s\n--- C:\n%s",
          de_run.out.s, c_run.out.s);
    CHECK(strstr(c_run.out.s, "1.5 14.5 -0.125 2.50000E-3 1.23450E3 0.3 \n-1 3.75 0 \n-1 0 15000000") != NULL,
          "unexpected numbers:\n%s", c_run.out.s);
    CHECK(strstr(c_run.out.s,
                 "X   +14.5000 Y    -2.0000 Z    +1.0000 in  O   +0.000 A  -90.000 T  +12.250 deg") != NULL,
          "unexpected DISPLAY-LOC:\n%s", c_run.out.s);
    CHECK(strchr(c_run.out.s, ',') == NULL, "a comma in the output:\n%s", c_run.out.s);
    printf("FBRL output, identical under de_DE.UTF-8 and C:\n%s\n", de_run.out.s);
    if (fails)
        return 1;
    printf("ok: libfbrl parses and prints numbers the same under de_DE.UTF-8 and C\n");
    return 0;
}
