/* SPDX-License-Identifier: MIT */
/* lang_random.c - long random-program runs against the FBRL engine (label fuzz).
 * Usage: lang_random [first-seed [seeds [lines]]]
 * Each seed builds lines of random tokens from the dictionary's own words and a
 * few literals and control words, evaluates them, and checks that the VM always
 * answers (OK or an error), keeps its stacks in bounds and still computes 6 7 *
 * at the end. Run under ASan+UBSan in CI; any crash or sanitizer report fails. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fbrl/vm.h"

typedef struct names {
    char list[800][40];
    int n;
} names;

/* words that could wait or loop for ever on random input (legitimately) */
static const char *const skip[] = {
    "BYE",   "MS",    "SPACES", ".R",         "U.R", "D.R",        "QUIT",          "DUMP",
    "WORDS", "KEY",   "ACCEPT", "GET-STRING", ">IN", "SAVE-INPUT", "RESTORE-INPUT", "BEGIN",
    "AGAIN", "UNTIL", "WHILE",  "REPEAT",     "DO",  "?DO",        "LOOP",          "+LOOP"};

static int collect(void *ctx, const char *name, size_t len)
{
    names *nm = ctx;
    for (size_t i = 0; i < sizeof skip / sizeof skip[0]; i++)
        if (strlen(skip[i]) == len && memcmp(skip[i], name, len) == 0)
            return 0;
    if (nm->n < 800 && len < 39) {
        memcpy(nm->list[nm->n], name, len);
        nm->list[nm->n][len] = 0;
        nm->n++;
    }
    return 0;
}

static void discard(void *user, const char *s, size_t n)
{
    (void)user;
    (void)s;
    (void)n;
}

int main(int argc, char **argv)
{
    static const char *const extra[] = {
        "0",    "1",   "-1",     "3",       "100", "65535",   "-9999999999", "PAD",  "HERE",
        "1E0",  "0E0", "-2.5E3", "S\" x\"", ":",   ";",       "IF",          "THEN", "ELSE",
        "CASE", "OF",  "ENDOF",  "'",       "[']", "RECURSE", "EXECUTE",     "DUP",  "5"};
    unsigned first = argc > 1 ? (unsigned)atoi(argv[1]) : 1;
    unsigned seeds = argc > 2 ? (unsigned)atoi(argv[2]) : 8;
    int lines = argc > 3 ? atoi(argv[3]) : 4000;
    size_t size = 1 << 20;
    void *mem = malloc(size);
    static names nm;
    if (!mem)
        return 2;
    for (unsigned seed = first; seed < first + seeds; seed++) {
        fbrl_vm_config cfg;
        fbrl_vm *vm;
        memset(&cfg, 0, sizeof cfg);
        cfg.mem = mem;
        cfg.mem_size = size;
        cfg.host.write = discard;
        if (fbrl_vm_create(&vm, &cfg) != FBRL_OK)
            return 2;
        nm.n = 0;
        fbrl_vm_words(vm, collect, &nm);
        if (fbrl_vm_eval(vm, "MARKER FUZZ-START", 17) != FBRL_OK)
            return 2;
        uint32_t r = seed * 2654435761u + 1;
        int errors = 0;
        for (int line = 0; line < lines; line++) {
            char src[600];
            /* some arguments first, so that most lines get past their first words */
            size_t n = (size_t)snprintf(src, sizeof src, "1 2 3 4 5 PAD HERE 1E0 2E0 3E0 ");
            for (int t = 0; t < 12; t++) {
                r = r * 1103515245u + 12345u;
                uint32_t x = r >> 8;
                const char *w = (x & 1) ? nm.list[(x >> 1) % (uint32_t)nm.n]
                                        : extra[(x >> 1) % (sizeof extra / sizeof extra[0])];
                n += (size_t)snprintf(src + n, sizeof src - n, "%s ", w);
            }
            if (fbrl_vm_eval(vm, src, n) != FBRL_OK) {
                errors++;
                if (getenv("LANG_RANDOM_VERBOSE"))
                    printf("%d %s\n", fbrl_vm_last_error(vm)->throw_code, fbrl_vm_last_error(vm)->word);
            }
            if (fbrl_vm_depth(vm) > 256 || fbrl_vm_fdepth(vm) > 64) {
                printf("seed %u line %d: stack out of bounds after: %s\n", seed, line, src);
                return 1;
            }
            if (line % 50 == 49)
                fbrl_vm_reset(vm);
        }
        fbrl_vm_reset(vm);
        fbrl_cell v = 0;
        if (fbrl_vm_eval(vm, "FUZZ-START DECIMAL 6 7 *", 24) != FBRL_OK || fbrl_vm_pop(vm, &v) != FBRL_OK ||
            v != 42) {
            printf("seed %u: VM unusable after the run\n", seed);
            return 1;
        }
        printf("seed %u: %d lines, %d errors\n", seed, lines, errors);
    }
    free(mem);
    return 0;
}
