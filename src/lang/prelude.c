/* SPDX-License-Identifier: MIT */
/* prelude.c - the few built-in words written in FBRL itself (compiled at
 * fbrl_vm_create). The "( stack ) \ help" after each name is its HELP text (FBRL_DOC_SRC:
 * left out under FBRL_NO_HELP). */
#include "vm_internal.h"

/* (clang-format cannot lay out strings joined to a macro's string) */
/* clang-format off */
const char fbrl__prelude[] =
    ": BEGIN-STRUCTURE "
        FBRL_DOC_SRC("( \"name\" -- struct-sys 0 ) \\ start a structure definition; "
                     "name pushes its size") "\n"
    "   CREATE HERE 0 0 , DOES> @ ;\n"
    ": END-STRUCTURE "
        FBRL_DOC_SRC("( struct-sys +n -- ) \\ end a structure definition, setting its size") "\n"
    "   SWAP ! ;\n"
    ": +FIELD "
        FBRL_DOC_SRC("( n1 n2 \"name\" -- n3 ) \\ make a field of n2 bytes at offset n1; "
                     "name adds the offset") "\n"
    "   CREATE OVER , + DOES> @ + ;\n"
    ": FIELD: " FBRL_DOC_SRC("( n1 \"name\" -- n2 ) \\ make an aligned one-cell field") "\n"
    "   ALIGNED 1 CELLS +FIELD ;\n"
    ": CFIELD: " FBRL_DOC_SRC("( n1 \"name\" -- n2 ) \\ make a one-character field") "\n"
    "   1 CHARS +FIELD ;\n"
    ": FFIELD: " FBRL_DOC_SRC("( n1 \"name\" -- n2 ) \\ make an aligned float field") "\n"
    "   FALIGNED 1 FLOATS +FIELD ;\n"
    ": 2FIELD: " FBRL_DOC_SRC("( n1 \"name\" -- n2 ) \\ make an aligned two-cell field") "\n"
    "   ALIGNED 2 CELLS +FIELD ;\n"
    ": NOOP " FBRL_DOC_SRC("( -- ) \\ do nothing") "\n"
    "   ;\n"
    ": CELL " FBRL_DOC_SRC("( -- n ) \\ size of a cell in bytes") "\n"
    "   1 CELLS ;\n"
    ": FLOAT " FBRL_DOC_SRC("( -- n ) \\ size of a float in bytes") "\n"
    "   1 FLOATS ;\n"
    ": OFF " FBRL_DOC_SRC("( a -- ) \\ store false (0) at a") "\n"
    "   0 SWAP ! ;\n"
    ": ON " FBRL_DOC_SRC("( a -- ) \\ store true (-1) at a") "\n"
    "   -1 SWAP ! ;\n";
/* clang-format on */
