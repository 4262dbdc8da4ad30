/* SPDX-License-Identifier: MIT */
/* abi.h - the sizes and alignments of the public structs a caller allocates.
 *
 * A program compiled against these headers may use sizeof; bindings that load the
 * shared library at run time (python/fbrl, cffi in ABI mode) must not hard-code
 * layouts, so they ask the running library: fbrl_abi_size(FBRL_ABI_LINK) bytes
 * aligned to fbrl_abi_align(FBRL_ABI_LINK) hold an fbrl_link. The codes are stable:
 * new types are appended to FBRL_ABI_TYPES, never inserted or renumbered. */
#ifndef FBRL_ABI_H
#define FBRL_ABI_H

#include "fbrl/export.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* X(CODE, type): every struct type, in code order (append only). */
#define FBRL_ABI_TYPES(X)                      \
    X(RING, fbrl_ring)                         \
    X(UART, fbrl_uart)                         \
    X(UART_CONFIG, fbrl_uart_config)           \
    X(PORT, fbrl_port)                         \
    X(PORT_OPTIONS, fbrl_port_options)         \
    X(LINK, fbrl_link)                         \
    X(LINK_CONFIG, fbrl_link_config)           \
    X(LINK_STATS, fbrl_link_stats)             \
    X(LINK_OUTCOME, fbrl_link_outcome)         \
    X(RAPL_READER, fbrl_rapl_reader)           \
    X(RAPL_POS, fbrl_rapl_pos)                 \
    X(LOC, fbrl_loc)                           \
    X(CALIB, fbrl_calib)                       \
    X(CALPTS, fbrl_calpts)                     \
    X(UNITS, fbrl_units)                       \
    X(FILE, fbrl_file)                         \
    X(GLOSSARY, fbrl_glossary)                 \
    X(ROBOT, fbrl_robot)                       \
    X(ROBOT_STOP, fbrl_robot_stop)             \
    X(VM_CONFIG, fbrl_vm_config)               \
    X(VM_ERROR, fbrl_vm_error)                 \
    X(WORKSPACE, fbrl_workspace)               \
    X(WORKSPACE_COUNTS, fbrl_workspace_counts) \
    X(UART_8250, fbrl_uart_8250)               \
    X(PORT_ENTRY, fbrl_port_entry)             \
    X(METHOD_SET, fbrl_method_set)             \
    X(RECOVER, fbrl_recover)                   \
    X(RUN, fbrl_run)                           \
    X(RUN_SNAP, fbrl_run_snap)                 \
    X(RUN_EVENT, fbrl_run_event)               \
    X(METHOD, fbrl_method)                     \
    X(USERS, fbrl_users)                       \
    X(USER, fbrl_user)                         \
    X(CELL_WORDS, fbrl_cell_words)             \
    X(METHOD_VERSION, fbrl_method_version)     \
    X(RUNLOG, fbrl_runlog)                     \
    X(RUNLOG_HEADER, fbrl_runlog_header)       \
    X(RUNLOG_PARAM, fbrl_runlog_param)         \
    X(AUDIT_KEY, fbrl_audit_key)               \
    X(AUDIT_VERIFIER, fbrl_audit_verifier)     \
    X(AUDIT_FILE, fbrl_audit_file)

#define FBRL_ABI_ENUM_(code, type) FBRL_ABI_##code,
typedef enum fbrl_abi_type { FBRL_ABI_TYPES(FBRL_ABI_ENUM_) FBRL_ABI_TYPE_COUNT } fbrl_abi_type;
#undef FBRL_ABI_ENUM_

/* Bytes of the type in the running library; 0 for a code it does not know. */
FBRL_API size_t fbrl_abi_size(fbrl_abi_type t);
/* Its alignment in bytes; 0 for a code it does not know. */
FBRL_API size_t fbrl_abi_align(fbrl_abi_type t);
/* The type's C name ("fbrl_link"), NULL for a code it does not know. */
FBRL_API const char *fbrl_abi_name(fbrl_abi_type t);

#ifdef __cplusplus
}
#endif
#endif
