/* SPDX-License-Identifier: MIT */
/* Compiled by the test fbrl_h_freestanding with -ffreestanding -nostdinc and only the
 * compiler's own headers: fbrl.h must need nothing from an operating system. */
#include "fbrl/fbrl.h"

int fbrl_freestanding_probe(void);
int fbrl_freestanding_probe(void)
{
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    return (int)c.data_bits + (int)sizeof(fbrl_port) * 0;
}
