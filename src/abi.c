/* SPDX-License-Identifier: MIT */
/* abi.c - sizes and alignments of the public structs, for bindings (fbrl/abi.h). */
#include "fbrl/abi.h"

#include "fbrl/fbrl.h"
#include "fbrl/cell_words.h"
#include "fbrl/workspace.h"

/* C99 has no alignof: a type's alignment is its offset after one char in a struct (one
 * such struct per type, declared here: a type defined inside offsetof is not C99). */
#define ABI_PROBE_(code, type) \
    struct abi_probe_##code {  \
        char c;                \
        type t;                \
    };
FBRL_ABI_TYPES(ABI_PROBE_)
#undef ABI_PROBE_

static const struct {
    const char *name;
    size_t size, align;
} abi_types[] = {
#define ABI_ROW_(code, type) {#type, sizeof(type), offsetof(struct abi_probe_##code, t)},
    FBRL_ABI_TYPES(ABI_ROW_)
#undef ABI_ROW_
};

size_t fbrl_abi_size(fbrl_abi_type t) { return (unsigned)t < FBRL_ABI_TYPE_COUNT ? abi_types[t].size : 0; }

size_t fbrl_abi_align(fbrl_abi_type t) { return (unsigned)t < FBRL_ABI_TYPE_COUNT ? abi_types[t].align : 0; }

const char *fbrl_abi_name(fbrl_abi_type t)
{
    return (unsigned)t < FBRL_ABI_TYPE_COUNT ? abi_types[t].name : NULL;
}
