/* words_fbrl.c - FBRL's own data words (thesis appendix I). Filled in below. */
#include "vm_internal.h"

fbrl_status fbrl__fbrl_words(fbrl_vm *vm)
{
    (void)vm;
    return FBRL_OK;
}
