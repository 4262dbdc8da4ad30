/* SPDX-License-Identifier: MIT */
/* glossary.h - the thesis's data glossary in the FBRL language: location templates and
 * matrices (appendix III), calibration and mapping (appendix II), metric conversion (I-7)
 * and typed data files (I-9), bound to the loc, matrix, calib, units and fileio modules.
 *
 * fbrl_glossary_install() defines the words in one VM. Their state (metric switch, mapping
 * switch, WITH-CAL structure, open files, PRINT-LOC's port) lives in an fbrl_glossary the
 * caller owns, one per VM, never in a global. docs/glossary.md lists every word.
 *
 * The robot words (another part of the language) use the mapping and metric state through
 * fbrl_glossary_map_out / _map_in / _units, and locations in VM memory through
 * fbrl_glossary_loc. */
#ifndef FBRL_GLOSSARY_H
#define FBRL_GLOSSARY_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/loc.h"
#include "fbrl/units.h"
#include "fbrl/fileio.h"
#include "fbrl/calib.h"
#include "fbrl/vm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Files that may be open at once in one VM (OPEN-FILE beyond this throws "too many open
 * files"). Each open file gets an equal share of the storage given to
 * fbrl_glossary_set_file_storage(). */
#define FBRL_GLOSSARY_FILES 8

/* Most point pairs CALIBRATE-N takes (its residuals live on the C stack). */
#define FBRL_GLOSSARY_NPOINT_MAX 256

/* User record tag under which SAVE-CAL stores a calibration (fileio user type of
 * FBRL_CALIB_BYTES bytes). */
#define FBRL_GLOSSARY_CAL_TAG 0x434Cu /* "CL" */

/* One slot of the file table. Private. */
typedef struct fbrl_glossary_file {
    fbrl_file file;  /* the open file (fileio handle) */
    fbrl_cell owner; /* VM address of the handle word's data field; 0 = slot free */
} fbrl_glossary_file;

/* Per-VM state. Caller-owned (static, heap or stack); fbrl_glossary_install() initialises
 * every field. All fields are private: use the functions below. */
typedef struct fbrl_glossary {
    uint32_t magic;     /* set by install; marks an installed glossary */
    fbrl_vm *vm;        /* the VM the words were installed in */
    fbrl_units units;   /* METRIC-ON / METRIC-OFF */
    int map_on;         /* MAP-ON / MAP-OFF */
    fbrl_cell with_cal; /* VM address of the WITH-CAL structure; 0 = none */
    void (*port_write)(void *ctx, const char *s, size_t n); /* PRINT-LOC's destination */
    void *port_ctx;
    unsigned char *file_mem; /* fbrl_glossary_set_file_storage() */
    size_t file_mem_size;
    fbrl_glossary_file files[FBRL_GLOSSARY_FILES];
} fbrl_glossary;

/* Initialise g (metric off, mapping off, no calibration, no files, no port) and define all
 * the glossary words in vm, after the FBRL data words they stand on (LOCATION, ARRAY, ...:
 * fbrl_vmx_data_words). g must outlive vm (the words keep a pointer to it). FBRL_EINVAL for NULL,
 * FBRL_ENOMEM if the dictionary is full. */
FBRL_API fbrl_status fbrl_glossary_install(fbrl_vm *vm, fbrl_glossary *g);

/* Give the file words their buffer storage (the VM never allocates): mem[0..size) is cut
 * into FBRL_GLOSSARY_FILES equal slices, one per open file, so one file can hold
 * size / FBRL_GLOSSARY_FILES bytes of records (fileio: 8 + payload bytes per record).
 * Call after install, while no file is open (FBRL_ESTATE otherwise). mem must stay valid
 * until fbrl_glossary_finish(). Without storage OPEN-FILE throws "no file storage". */
FBRL_API fbrl_status fbrl_glossary_set_file_storage(fbrl_glossary *g, void *mem, size_t size);

/* Close every open file, committing its changes to disk (CLOSE-FILE for each). Call when
 * the VM is done. Every file is closed even if one fails (its changes are then discarded
 * and the first error is returned). */
FBRL_API fbrl_status fbrl_glossary_finish(fbrl_glossary *g);

/* Mapping for the robot words (DESIGN 7). With MAP-ON, map_out carries a location from the
 * original block frame to the moved block through the WITH-CAL structure
 * (fbrl_calib_map_arm) and map_in carries a taught/read-back location back
 * (fbrl_calib_unmap_arm). axis: the arm's base axis (x, y) in the user's frame (NULL:
 * the origin); *off (may be NULL): the tool-axis tilt the arm cannot follow, degrees (0
 * with MAP-OFF). With MAP-OFF both leave loc unchanged and return FBRL_OK. Errors (loc
 * unchanged): FBRL_EINVAL for NULL or an uninstalled g, FBRL_ESTATE if mapping is on but
 * the WITH-CAL structure is gone or was overwritten, FBRL_ERANGE from map_out when *off
 * passes FBRL_CALIB_AXIS_MAX, FBRL_ENONFINITE / FBRL_EOVERFLOW from the mapping. */
FBRL_API fbrl_status fbrl_glossary_map_out(const fbrl_glossary *g, fbrl_loc *loc, const double axis[2],
                                           double *off);
FBRL_API fbrl_status fbrl_glossary_map_in(const fbrl_glossary *g, fbrl_loc *loc, const double axis[2]);

/* The location at VM address addr: 48 bytes wholly inside the VM's data space and aligned
 * to 8 bytes (as CREATE-LOC and ARRAY cells are). FBRL_EINVAL for NULL, FBRL_ERANGE for an
 * address outside the data space or misaligned. Its contents are not checked: call
 * fbrl_loc_check() before using it as a position. */
FBRL_API fbrl_status fbrl_glossary_loc(fbrl_vm *vm, fbrl_cell addr, fbrl_loc **out);

/* Is the word xt a location template (CREATE-LOC name)? FBRL_OK and its data field in
 * *addr, FBRL_ETYPE for any other word (the console's work-cell view lists them). */
FBRL_API fbrl_status fbrl_glossary_loc_word(const fbrl_vm *vm, fbrl_cell xt, fbrl_cell *addr);

/* The three location slots of the CREATE-CAL structure at VM address addr (what the
 * structure's name pushes), e.g. for GET-CAL-POINTS teaching them with the arm. FBRL_EINVAL
 * for NULL, FBRL_ERANGE if addr is outside the data space, FBRL_ETYPE if no CREATE-CAL
 * structure is there. Slot k (1..3) is (*out)->p[k - 1]. */
FBRL_API fbrl_status fbrl_glossary_calpts(fbrl_vm *vm, fbrl_cell addr, fbrl_calpts **out);

/* The metric switch of this VM (for converting user input and output with the units
 * module); NULL for NULL g. */
FBRL_API const fbrl_units *fbrl_glossary_units(const fbrl_glossary *g);

/* The glossary's named data, as a workspace keeps it (fbrl/workspace.h): what the word
 * xt is and the C address of its contents in the VM. */
typedef enum fbrl_glossary_kind {
    FBRL_GLOSSARY_NONE = 0, /* not one of the glossary's data words */
    FBRL_GLOSSARY_LOC,      /* CREATE-LOC: fbrl_loc */
    FBRL_GLOSSARY_RECTMAT,  /* RECTMAT / AUTOMAT: fbrl_rectmat */
    FBRL_GLOSSARY_RADMAT,   /* RADMAT: fbrl_radmat */
    FBRL_GLOSSARY_CAL,      /* CREATE-CAL: fbrl_calpts */
    FBRL_GLOSSARY_CALSTRU   /* CREATE-CAL-STRU: fbrl_calib */
} fbrl_glossary_kind;

/* *kind (FBRL_GLOSSARY_NONE for any other word) and *obj its contents. FBRL_EINVAL for
 * NULL or an uninstalled g. */
FBRL_API fbrl_status fbrl_glossary_object(fbrl_glossary *g, fbrl_cell xt, fbrl_glossary_kind *kind,
                                          void **obj);

/* Make a new named object of that kind, as its defining word would: name (1..31
 * characters), contents zero (a location at 0, a matrix of zeros: fill it with
 * fbrl_rectmat_init / fbrl_radmat_init), a calibration structure the identity. *obj gets
 * the contents' C address. All or nothing: on failure (dictionary full, bad name) no word
 * is left and the failure is thrown in the VM (FBRL_ETHROW). */
FBRL_API fbrl_status fbrl_glossary_make(fbrl_glossary *g, fbrl_glossary_kind kind, const char *name,
                                        size_t len, void **obj);

/* WITH-CAL's structure (VM address, 0 = none) and the MAP-ON switch; set_mapping takes a
 * structure address 0 (none) or a CREATE-CAL-STRU's (FBRL_ETYPE otherwise) and map_on only
 * with a rigid one (FBRL_ESTATE). */
FBRL_API fbrl_status fbrl_glossary_mapping(const fbrl_glossary *g, fbrl_cell *with_cal, int *map_on);
FBRL_API fbrl_status fbrl_glossary_set_mapping(fbrl_glossary *g, fbrl_cell with_cal, int map_on);

/* PRINT-LOC's destination, the communication port: write(ctx, s, n) receives each line
 * (the DISPLAY-LOC text followed by CR LF). write = NULL removes it; PRINT-LOC then
 * throws "no communication port". */
FBRL_API void fbrl_glossary_set_port_writer(fbrl_glossary *g,
                                            void (*write)(void *ctx, const char *s, size_t n), void *ctx);

#ifdef __cplusplus
}
#endif
#endif
