# SPDX-License-Identifier: MIT
"""The C declarations the bindings use, and loading libfbrl (cffi, ABI mode).

ABI mode reads the shared library with dlopen: nothing is compiled when the package is
installed or imported. Structs the bindings only pass around are opaque here and
allocated with the size and alignment the running library reports (fbrl/abi.h); the
few whose fields Python reads or fills are declared in full below and checked against
fbrl_abi_size() at import, so a layout change is an ImportError, never silent garbage.
"""
import ctypes.util
import os

from cffi import FFI

CDEF = """
typedef int fbrl_status;
const char *fbrl_status_str(fbrl_status st);
const char *fbrl_status_name(fbrl_status st);
const char *fbrl_version(void);
int fbrl_version_number(void);
size_t fbrl_abi_size(int t);
size_t fbrl_abi_align(int t);
const char *fbrl_abi_name(int t);

/* opaque: allocated with fbrl_abi_size/fbrl_abi_align */
typedef struct fbrl_uart fbrl_uart;
typedef struct fbrl_port fbrl_port;
typedef struct fbrl_port_options fbrl_port_options;
typedef struct fbrl_link fbrl_link;
typedef struct fbrl_link_config fbrl_link_config;
typedef struct fbrl_glossary fbrl_glossary;
typedef struct fbrl_robot fbrl_robot;
typedef struct fbrl_vm fbrl_vm;
typedef struct fbrl_file fbrl_file;
typedef struct fbrl_cell_words fbrl_cell_words;

/* ports */
void fbrl_port_options_init(fbrl_port_options *o);
fbrl_status fbrl_port_set_option(fbrl_port_options *o, const char *key, const char *value);
fbrl_status fbrl_port_open(fbrl_port *p, const char *url, const fbrl_port_options *opt);
fbrl_uart *fbrl_port_uart(fbrl_port *p);
fbrl_status fbrl_port_describe(const fbrl_port *p, char *buf, size_t cap);
fbrl_status fbrl_port_close(fbrl_port *p);
typedef struct fbrl_port_entry {
    char device[128];
    char by_id[256];
    char description[128];
    char manufacturer[64];
    char serial[64];
    int usb;
    unsigned vid, pid;
    char driver[32];
    int latency_timer_ms;
} fbrl_port_entry;
fbrl_status fbrl_port_list(const char *sysfs_root, const char *dev_root, fbrl_port_entry *out, size_t max,
                           size_t *count);

/* the link */
typedef struct fbrl_rapl_arg {
    int kind;
    long i;
    double r;
    const char *s;
} fbrl_rapl_arg;
typedef struct fbrl_rapl_pos {
    char kind;
    long pulses[8];
    double joints[8];
    double world[6];
    unsigned char npulses, njoints, nworld;
    unsigned char part;
} fbrl_rapl_pos;
typedef struct fbrl_rapl_status_info {
    int last_error;
    double speed;
    int homed;
    unsigned naxes;
    char lock[8], done[8];
    char limp[8], axis_homed[8];
    uint32_t inputs, outputs;
    unsigned have;
    int metric;
} fbrl_rapl_status_info;
/* The settings at the start of fbrl_link_config (fbrl/link.h keeps their order): the rest
 * of the struct stays opaque and keeps fbrl_link_config_init()'s defaults. */
typedef struct fbrl_link_config_head {
    int form;
    int lower_case;
    uint32_t echo_timeout_ms;
    uint32_t reply_timeout_ms;
    uint32_t wait_timeout_ms;
    unsigned max_attempts;
    unsigned query_reads;
    unsigned naxes;
} fbrl_link_config_head;
typedef void (*fbrl_link_line_fn)(void *ctx, const char *line, size_t len, int flawed);
typedef void (*fbrl_link_exec_fn)(void *ctx, const char *line, size_t len, fbrl_status result);
void fbrl_link_config_init(fbrl_link_config *c);
fbrl_status fbrl_link_init(fbrl_link *l, fbrl_uart *u, const fbrl_link_config *cfg);
fbrl_status fbrl_link_connect(fbrl_link *l);
fbrl_status fbrl_link_line_check(const char *line, size_t len);
fbrl_status fbrl_link_start_cmd(fbrl_link *l, int cmd, const fbrl_rapl_arg *args, size_t nargs, int straight);
fbrl_status fbrl_link_start_raw(fbrl_link *l, const char *line);
fbrl_status fbrl_link_start_stream(fbrl_link *l, int cmd, unsigned lines);
fbrl_status fbrl_link_poll(fbrl_link *l, uint32_t timeout_ms, int *done);
int fbrl_link_busy(const fbrl_link *l);
const fbrl_rapl_pos *fbrl_link_last_pos(const fbrl_link *l);
const fbrl_rapl_status_info *fbrl_link_last_status(const fbrl_link *l);
fbrl_status fbrl_link_get_form(const fbrl_link *l, int *form);
fbrl_status fbrl_rapl_encode(char *buf, size_t cap, size_t *len, int form, int cmd, const fbrl_rapl_arg *args,
                             size_t nargs, int straight);
fbrl_status fbrl_link_unguarded(fbrl_link *l);
fbrl_status fbrl_link_typei(fbrl_link *l, const char *expr, long *value);
fbrl_status fbrl_link_typev(fbrl_link *l, const char *expr, double *value);
fbrl_status fbrl_link_input(fbrl_link *l, int n, int *on);
fbrl_status fbrl_link_set_line_handler(fbrl_link *l, fbrl_link_line_fn fn, void *ctx,
                                       fbrl_link_line_fn *old_fn, void **old_ctx);
fbrl_status fbrl_link_set_exec_handler(fbrl_link *l, fbrl_link_exec_fn fn, void *ctx, fbrl_link_exec_fn *old_fn,
                                       void **old_ctx);
fbrl_status fbrl_link_error(const fbrl_link *l, int *code, const char **text);
int fbrl_link_units(const fbrl_link *l);
int fbrl_link_fate_of(fbrl_status result);
fbrl_status fbrl_link_get_runs(const fbrl_link *l, unsigned *runs, unsigned *maybe_runs);
fbrl_status fbrl_rapl_cmd_find(const char *keyword, int *cmd);
const char *fbrl_rapl_error_text(int code);

/* locations and calibration */
typedef struct fbrl_loc {
    double x, y, z;
    double o;
    double a;
    double t;
} fbrl_loc;
typedef struct fbrl_calib {
    double r[3][3];
    double t[3];
} fbrl_calib;
typedef struct fbrl_calpts {
    fbrl_loc p[3];
} fbrl_calpts;
fbrl_status fbrl_loc_check(const fbrl_loc *loc);
fbrl_status fbrl_loc_distance(const fbrl_loc *a, const fbrl_loc *b, double *inches);
fbrl_status fbrl_loc_format(const fbrl_loc *loc, int metric, char *buf, size_t size);
fbrl_status fbrl_calib_identity(fbrl_calib *c);
fbrl_status fbrl_calib_3point(fbrl_calib *c, const fbrl_calpts *cal, const fbrl_calpts *recal);
fbrl_status fbrl_calib_npoint(fbrl_calib *c, const fbrl_loc *cal, const fbrl_loc *recal, size_t n,
                              double *residuals, double *rms, size_t *worst);
fbrl_status fbrl_calib_map(const fbrl_calib *c, const fbrl_loc *in, fbrl_loc *out);
fbrl_status fbrl_calib_unmap(const fbrl_calib *c, const fbrl_loc *in, fbrl_loc *out);
fbrl_status fbrl_calib_invert(const fbrl_calib *c, fbrl_calib *inv);

/* data files */
typedef struct fbrl_ftype {
    int code;
    uint16_t tag;
    uint32_t size;
} fbrl_ftype;
fbrl_ftype fbrl_ftype_user(uint16_t tag, uint32_t size);
fbrl_status fbrl_file_create(const char *path);
fbrl_status fbrl_file_open(fbrl_file *f, const char *path, void *buf, size_t cap);
fbrl_status fbrl_file_reset(fbrl_file *f);
fbrl_status fbrl_file_append(fbrl_file *f);
fbrl_status fbrl_file_truncate(fbrl_file *f);
fbrl_status fbrl_file_write(fbrl_file *f, fbrl_ftype type, const void *value);
fbrl_status fbrl_file_read(fbrl_file *f, fbrl_ftype type, void *value);
fbrl_status fbrl_file_peek(const fbrl_file *f, fbrl_ftype *type);
fbrl_status fbrl_file_tell(const fbrl_file *f, uint32_t *index, uint32_t *count);
fbrl_status fbrl_file_commit(fbrl_file *f);
fbrl_status fbrl_file_close(fbrl_file *f);
fbrl_status fbrl_file_discard(fbrl_file *f);

/* the FBRL engine */
typedef intptr_t fbrl_cell;
typedef struct fbrl_vm_host {
    void *user;
    void (*write)(void *user, const char *s, size_t n);
    int (*key)(void *user);
    int (*key_ready)(void *user);
    fbrl_status (*file_open)(void *user, const char *path, void **handle);
    fbrl_status (*file_read_line)(void *user, void *handle, char *buf, size_t cap, size_t *len);
    void (*file_close)(void *user, void *handle);
    uint64_t (*now_us)(void *user);
    void (*sleep_ms)(void *user, uint32_t ms);
    void (*time_date)(void *user, int out[6]);
    fbrl_status (*read_line)(void *user, const char *prompt, char *buf, size_t cap, size_t *len);
    const void *files; /* the standard FILE words (fbrl_vm_files): none from Python */
} fbrl_vm_host;
typedef struct fbrl_vm_config {
    void *mem;
    size_t mem_size;
    size_t data_stack_cells;
    size_t return_stack_cells;
    size_t float_stack_cells;
    fbrl_vm_host host;
    int mem_zeroed;
} fbrl_vm_config;
typedef struct fbrl_vm_error {
    int throw_code;
    char message[256];
    char word[64];
    char file[256];
    unsigned long line;
} fbrl_vm_error;
fbrl_status fbrl_vm_create(fbrl_vm **out, const fbrl_vm_config *cfg);
size_t fbrl_vm_size_for(const fbrl_vm_config *cfg, size_t dict_bytes);
fbrl_status fbrl_vm_eval(fbrl_vm *vm, const char *text, size_t len);
fbrl_status fbrl_vm_include(fbrl_vm *vm, const char *path);
const fbrl_vm_error *fbrl_vm_last_error(const fbrl_vm *vm);
void fbrl_vm_interrupt(fbrl_vm *vm);
int fbrl_vm_interrupt_pending(const fbrl_vm *vm);
int fbrl_vm_bye(const fbrl_vm *vm);
void fbrl_vm_reset(fbrl_vm *vm);
fbrl_status fbrl_vm_push(fbrl_vm *vm, fbrl_cell v);
fbrl_status fbrl_vm_pop(fbrl_vm *vm, fbrl_cell *v);
fbrl_status fbrl_vm_fpush(fbrl_vm *vm, double v);
fbrl_status fbrl_vm_fpop(fbrl_vm *vm, double *v);
size_t fbrl_vm_depth(const fbrl_vm *vm);
size_t fbrl_vm_fdepth(const fbrl_vm *vm);
fbrl_status fbrl_glossary_install(fbrl_vm *vm, fbrl_glossary *g);
fbrl_status fbrl_glossary_set_file_storage(fbrl_glossary *g, void *mem, size_t size);
fbrl_status fbrl_robot_install(fbrl_vm *vm, fbrl_robot *r, fbrl_link *link, fbrl_glossary *g);
fbrl_status fbrl_robot_set_link(fbrl_robot *r, fbrl_link *link);
typedef void (*fbrl_robot_watch_fn)(void *ctx, fbrl_robot *r);
void fbrl_robot_set_watch(fbrl_robot *r, fbrl_robot_watch_fn fn, void *ctx);
typedef struct fbrl_link_stop {
    fbrl_status result;
    int halted;
    fbrl_status status_result;
    int have_status, homed, have_outputs;
    uint32_t switched_off, off_failed, left_on, unknown;
    int have_where;
    double where[6];
} fbrl_link_stop;
typedef struct fbrl_robot_stop {
    fbrl_status result;
    int was_moving;
    char motion[81];
    fbrl_link_stop stop;
} fbrl_robot_stop;
fbrl_status fbrl_robot_safe_stop_link(fbrl_link *link, uint32_t outputs, const char *motion, fbrl_robot_stop *out);
fbrl_status fbrl_robot_line_effect(const char *line, unsigned *effect, uint32_t *outputs_on);
int fbrl_robot_still_line(const char *line, size_t len, int flawed);
int fbrl_robot_last_error(const fbrl_robot *r);
/* the work cell's words and the guard on every robot motion (fbrl/cell_words.h); the guard's record
 * starts with these two counters */
typedef struct fbrl_cell_stats_head {
    unsigned long moves;
    unsigned long refused;
} fbrl_cell_stats_head;
fbrl_status fbrl_cell_install(fbrl_vm *vm, fbrl_cell_words *cw, fbrl_robot *r, fbrl_glossary *g);
const fbrl_cell_stats_head *fbrl_cell_stats_get(const fbrl_cell_words *cw);
uint64_t fbrl_clock_now_us(void);
/* the arm models and their kinematics (fbrl/arm.h); a model is only pointed at */
typedef struct fbrl_arm fbrl_arm;
const fbrl_arm *fbrl_arm_find(const char *name);
size_t fbrl_arm_names(char *buf, size_t cap, char sep);
fbrl_status fbrl_arm_fk(const fbrl_arm *m, const double *q, double tool, double pose[6]);
fbrl_status fbrl_arm_chain(const fbrl_arm *m, const double *q, double tool, double p[4][3]);
"""

# fbrl_abi_type codes (fbrl/abi.h; stable, append only)
ABI = {
    "fbrl_ring": 0, "fbrl_uart": 1, "fbrl_uart_config": 2, "fbrl_port": 3, "fbrl_port_options": 4,
    "fbrl_link": 5, "fbrl_link_config": 6, "fbrl_link_stats": 7, "fbrl_link_outcome": 8,
    "fbrl_rapl_reader": 9, "fbrl_rapl_pos": 10, "fbrl_loc": 11, "fbrl_calib": 12, "fbrl_calpts": 13,
    "fbrl_units": 14, "fbrl_file": 15, "fbrl_glossary": 16, "fbrl_robot": 17, "fbrl_robot_stop": 18,
    "fbrl_vm_config": 19, "fbrl_vm_error": 20, "fbrl_workspace": 21, "fbrl_workspace_counts": 22,
    "fbrl_uart_8250": 23, "fbrl_port_entry": 24, "fbrl_cell_words": 33,
}
# The structs declared in full above: their layout must be the library's.
DECLARED = ("fbrl_port_entry", "fbrl_rapl_pos", "fbrl_loc", "fbrl_calib", "fbrl_calpts", "fbrl_vm_config", "fbrl_vm_error",
            "fbrl_robot_stop")

ffi = FFI()
ffi.cdef(CDEF)


def _load():
    """FBRL_LIBRARY names the shared library (the tests point it at the build tree);
    otherwise the one scripts/install.sh installed with this package (_installed.py: by
    path, so no ldconfig or LD_LIBRARY_PATH is needed); otherwise the system's
    libfbrl.so.1 (the libfbrl1 package)."""
    names = [os.environ["FBRL_LIBRARY"]] if os.environ.get("FBRL_LIBRARY") else []
    try:
        from ._installed import LIBRARY
        names.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), LIBRARY))
    except ImportError:
        pass  # not installed by install.sh: the source tree or the Debian package
    names += ["libfbrl.so.1", ctypes.util.find_library("fbrl") or "libfbrl.so"]
    err = None
    for name in names:
        try:
            return ffi.dlopen(name)
        except OSError as e:  # try the next name
            err = e
    raise ImportError("fbrl: cannot load libfbrl (set FBRL_LIBRARY to its path): %s" % err)


lib = _load()

for _name in DECLARED:
    _have = (ffi.sizeof(_name), ffi.alignof(_name))
    _want = (lib.fbrl_abi_size(ABI[_name]), lib.fbrl_abi_align(ABI[_name]))
    if _have != _want or ffi.string(lib.fbrl_abi_name(ABI[_name])).decode() != _name:
        raise ImportError("fbrl: %s is %s bytes/alignment here but %s in the library: rebuild the bindings"
                          % (_name, _have, _want))


def abi_code(name):
    """The library's fbrl_abi_type code of a struct, found by its name (never hard-coded)."""
    for code in range(256):
        n = lib.fbrl_abi_name(code)
        if n == ffi.NULL:
            break
        if ffi.string(n).decode() == name:
            return code
    raise ImportError("fbrl: the library does not know %s: it is older than these bindings" % name)


def opaque_later(*names):
    """Structs a module only passes around (alloc() them): each one's code by its name."""
    for name in names:
        ABI.setdefault(name, abi_code(name))


def declared_later(*names):
    """Structs a module declares after this one (its own cdef): each one's fbrl_abi_type code
    found by its name in the library, and its layout required to be the library's."""
    for name in names:
        ABI.setdefault(name, abi_code(name))
        have, want = (ffi.sizeof(name), ffi.alignof(name)), (lib.fbrl_abi_size(ABI[name]), lib.fbrl_abi_align(ABI[name]))
        if have != want:
            raise ImportError("fbrl: %s is %s bytes/alignment here but %s in the library: rebuild the bindings"
                              % (name, have, want))


def alloc(type_name):
    """Zeroed storage for an opaque struct, aligned as the library needs, as a typed pointer.
    The returned pointer keeps its memory alive (ffi.gc-free: the owner keeps the pointer)."""
    size = lib.fbrl_abi_size(ABI[type_name])
    align = lib.fbrl_abi_align(ABI[type_name])
    if size == 0:
        raise ImportError("fbrl: the library does not know %s" % type_name)
    raw = ffi.new("char[]", size + align)
    addr = int(ffi.cast("uintptr_t", raw))
    ptr = ffi.cast(type_name + " *", addr + (-addr) % align)
    return _Owned(ptr, raw)


class _Owned:
    """A typed pointer into storage this object keeps alive."""

    __slots__ = ("ptr", "_raw")

    def __init__(self, ptr, raw):
        self.ptr = ptr
        self._raw = raw
