/* SPDX-License-Identifier: MIT */
/* A lab program built against an installed libfbrl: every public header compiles,
 * and a calibrated rack location and a VM evaluation work through the library. */
#include <stdio.h>
#include <string.h>
#include "fbrl/fbrl.h"
#include "fbrl/uart_posix.h" /* the OS backends are not in fbrl.h (it stays freestanding) */
#ifdef FBRL_HAVE_SERIALPORT
#include "fbrl/uart_serialport.h"
#endif

static char out[256];
static size_t used;
static void collect(void *user, const char *s, size_t n)
{
    (void)user;
    if (used + n < sizeof out) {
        memcpy(out + used, s, n);
        used += n;
    }
}

int main(void)
{
    static unsigned char mem[1 << 20];
    fbrl_vm *vm;
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = sizeof mem;
    cfg.host.write = collect;
    if (fbrl_vm_create(&vm, &cfg) != FBRL_OK)
        return 1;
    if (fbrl_vm_eval(vm, "6 7 * .", 7) != FBRL_OK || strcmp(out, "42 ") != 0)
        return 2;
    printf("%s: %s\n", fbrl_status_name(FBRL_EDEGENERATE), fbrl_status_str(FBRL_EDEGENERATE));
    printf("consumer ok: %s\n", out);
    return 0;
}
