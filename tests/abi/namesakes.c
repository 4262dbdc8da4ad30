/* SPDX-License-Identifier: MIT */
/* namesakes.c - a program that defines, for itself, every internal name libfbrl 0.1.0
 * exported (gl_loc, rb_cmd ...: `nm -D libfbrl.so` before visibility was hidden), then
 * uses the library. Linked against the shared and against the static library
 * (tests/abi/abi.cmake): the static link must not fail with "multiple definition", and
 * the library must still call its own functions and read its own data, not these.
 * Before the fix, this program's gl_loc replaced the library's one. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fbrl/fbrl.h"

/* Every call of one of the program's own namesakes counts here. */
static int namesake_calls;

/* The library's functions of these names, defined again as the program's own. */
#define NAMESAKE_FN(name) \
    int name(void);       \
    int name(void) { return ++namesake_calls; }
/* Its data of these names: bytes that read as nothing the library expects. */
#define NAMESAKE_DATA(name) unsigned char name[256] = {0xA5};

NAMESAKE_FN(gl_define)
NAMESAKE_FN(gl_fpop)
NAMESAKE_FN(gl_in)
NAMESAKE_FN(gl_install_cal)
NAMESAKE_FN(gl_install_file)
NAMESAKE_FN(gl_install_loc)
NAMESAKE_FN(gl_loc)
NAMESAKE_FN(gl_make)
NAMESAKE_FN(gl_map)
NAMESAKE_FN(gl_out)
NAMESAKE_FN(gl_pop)
NAMESAKE_FN(gl_push_flag)
NAMESAKE_FN(gl_rad_run)
NAMESAKE_FN(gl_rect_run)
NAMESAKE_FN(gl_rigid)
NAMESAKE_FN(gl_stru)
NAMESAKE_FN(gl_throw)
NAMESAKE_FN(gl_throw_st)
NAMESAKE_FN(rb_arm_where)
NAMESAKE_FN(rb_cmd)
NAMESAKE_FN(rb_fail)
NAMESAKE_FN(rb_fail_st)
NAMESAKE_FN(rb_finite)
NAMESAKE_FN(rb_from_arm)
NAMESAKE_FN(rb_interrupted)
NAMESAKE_FN(rb_len_in)
NAMESAKE_FN(rb_link_result)
NAMESAKE_FN(rb_loc_read)
NAMESAKE_FN(rb_loc_write)
NAMESAKE_FN(rb_metric)
NAMESAKE_FN(rb_name_arg)
NAMESAKE_FN(rb_now_ms)
NAMESAKE_FN(rb_online)
NAMESAKE_FN(rb_params)
NAMESAKE_FN(rb_parse_param)
NAMESAKE_FN(rb_port_writer)
NAMESAKE_FN(rb_puts)
NAMESAKE_FN(rb_range)
NAMESAKE_FN(rb_raw)
NAMESAKE_FN(rb_raw_lines)
NAMESAKE_FN(rb_resync)
NAMESAKE_FN(rb_scratch_point)
NAMESAKE_FN(rb_show)
NAMESAKE_FN(rb_sleep_ms)
NAMESAKE_FN(rb_still)
NAMESAKE_FN(rb_stream)
NAMESAKE_FN(rb_to_arm)
NAMESAKE_FN(rb_wait_ms)
NAMESAKE_DATA(gl_loc_tag)
NAMESAKE_DATA(gl_type_cal)
NAMESAKE_DATA(gl_type_hndl)
NAMESAKE_DATA(gl_type_rad)
NAMESAKE_DATA(gl_type_rect)
NAMESAKE_DATA(gl_type_stru)
NAMESAKE_DATA(rb_comm_asc)
NAMESAKE_DATA(rb_comm_nwords)
NAMESAKE_DATA(rb_comm_words)
NAMESAKE_DATA(rb_import_nwords)
NAMESAKE_DATA(rb_import_words)
NAMESAKE_DATA(rb_io_nwords)
NAMESAKE_DATA(rb_io_words)
NAMESAKE_DATA(rb_line_nwords)
NAMESAKE_DATA(rb_line_words)
NAMESAKE_DATA(rb_motion_nwords)
NAMESAKE_DATA(rb_motion_words)
NAMESAKE_DATA(rb_param_nwords)
NAMESAKE_DATA(rb_param_words)
NAMESAKE_DATA(rb_rapl_nwords)
NAMESAKE_DATA(rb_rapl_words)
NAMESAKE_DATA(rb_teach_nwords)
NAMESAKE_DATA(rb_teach_words)

#define NAMESAKES 71 /* names defined above */

static char output[4096];
static size_t output_len;

static void on_write(void *user, const char *s, size_t n)
{
    (void)user;
    if (n > sizeof output - 1 - output_len)
        n = sizeof output - 1 - output_len;
    memcpy(output + output_len, s, n);
    output_len += n;
    output[output_len] = 0;
}

/* Evaluates text; its output must be want exactly. */
static int expect(fbrl_vm *vm, const char *text, const char *want)
{
    fbrl_status st;
    output_len = 0;
    output[0] = 0;
    st = fbrl_vm_eval(vm, text, strlen(text));
    if (st != FBRL_OK || strcmp(output, want) != 0) {
        fprintf(stderr, "namesakes: '%s' gave %s (%s) and output '%s', want '%s'\n", text,
                fbrl_status_name(st), st == FBRL_OK ? "" : fbrl_vm_last_error(vm)->message, output, want);
        return 1;
    }
    return 0;
}

int main(void)
{
    static union {
        unsigned char bytes[1 << 21];
        long double align; /* fbrl_vm_config: mem aligned to 16 bytes */
    } mem;
    static fbrl_glossary g;
    static fbrl_robot r;
    fbrl_vm_config cfg;
    fbrl_vm *vm = NULL;
    fbrl_status st;
    int fails = 0;

    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem.bytes;
    cfg.mem_size = sizeof mem.bytes;
    cfg.host.write = on_write;
    st = fbrl_vm_create(&vm, &cfg);
    if (st == FBRL_OK)
        st = fbrl_glossary_install(vm, &g);
    if (st == FBRL_OK)
        st = fbrl_robot_install(vm, &r, NULL, &g);
    if (st != FBRL_OK) {
        fprintf(stderr, "namesakes: could not set up the VM: %s\n", fbrl_status_name(st));
        return 1;
    }
    fails += expect(vm, "CREATE-LOC P  1.0 2.0 3.0 4.0 5.0 6.0 P DEFINE-LOC  P GETY F.", "2. ");
    fails += expect(vm, "P GETX F. P GETZ F. P GETT F.", "1. 3. 6. ");
    fails += expect(vm, "CREATE-LOC Q  Q P SET-LOC  Q GETA F.", "5. ");
    /* A robot word without a controller fails, and says so. */
    output_len = 0;
    if (fbrl_vm_eval(vm, "HOME", 4) == FBRL_OK) {
        fprintf(stderr, "namesakes: HOME without a controller succeeded\n");
        fails++;
    }
    if (namesake_calls != 0) {
        fprintf(stderr, "namesakes: the library called the program's own functions %d times\n",
                namesake_calls);
        fails++;
    }
    /* The program's own names are its own. */
    if (gl_loc() != 1 || rb_cmd() != 2 || gl_loc_tag[0] != 0xA5) {
        fprintf(stderr, "namesakes: the program's own gl_loc, rb_cmd, gl_loc_tag are not its own\n");
        fails++;
    }
    printf("namesakes: %d internal names defined by the program, %d failures\n", NAMESAKES, fails);
    return fails ? 1 : 0;
}
