/* SPDX-License-Identifier: MIT */
/* internal_names.h - the link-time names of the word sets' internal functions and data
 * (private). The sources keep their short names (gl_ for the glossary, rb_ for the robot
 * words); the objects carry them with the prefix fbrli_, as zlib's Z_PREFIX does, so a
 * program that defines its own gl_loc or rb_cmd neither collides with the static library
 * nor changes what the library calls (tests: abi_namesakes). The shared library hides
 * them as well (visibility hidden, docs/abi.md). A new internal name shared between two
 * files of src/words gets its line here; the test abi_prefix lists any that does not. */
#ifndef FBRL_WORDS_INTERNAL_NAMES_H
#define FBRL_WORDS_INTERNAL_NAMES_H

#define cw_num           fbrli_cw_num
#define cw_place_blocks  fbrli_cw_place_blocks
#define gl_args          fbrli_gl_args
#define gl_in            fbrli_gl_in
#define gl_install_cal   fbrli_gl_install_cal
#define gl_install_file  fbrli_gl_install_file
#define gl_install_loc   fbrli_gl_install_loc
#define gl_loc           fbrli_gl_loc
#define gl_loc_tag       fbrli_gl_loc_tag
#define gl_make          fbrli_gl_make
#define gl_map           fbrli_gl_map
#define gl_out           fbrli_gl_out
#define gl_push_flag     fbrli_gl_push_flag
#define gl_rad_run       fbrli_gl_rad_run
#define gl_rect_run      fbrli_gl_rect_run
#define gl_rigid         fbrli_gl_rigid
#define gl_stru          fbrli_gl_stru
#define gl_throw         fbrli_gl_throw
#define gl_throw_st      fbrli_gl_throw_st
#define gl_type_cal      fbrli_gl_type_cal
#define gl_type_hndl     fbrli_gl_type_hndl
#define gl_type_rad      fbrli_gl_type_rad
#define gl_type_rect     fbrli_gl_type_rect
#define gl_type_stru     fbrli_gl_type_stru
#define rb_line_cmd      fbrli_rb_line_cmd
#define rb_line_loses    fbrli_rb_line_loses
#define rb_line_move     fbrli_rb_line_move
#define rb_line_moves    fbrli_rb_line_moves
#define rb_link_gate     fbrli_rb_link_gate
#define rb_motion        fbrli_rb_motion
#define rb_raw_send      fbrli_rb_raw_send
#define rb_send          fbrli_rb_send
#define rb_where_lost    fbrli_rb_where_lost
#define rb_now_us        fbrli_rb_now_us
#define rb_units         fbrli_rb_units
#define rb_pause_until   fbrli_rb_pause_until
#define rb_arm_where     fbrli_rb_arm_where
#define rb_cmd           fbrli_rb_cmd
#define rb_comm_asc      fbrli_rb_comm_asc
#define rb_comm_nwords   fbrli_rb_comm_nwords
#define rb_comm_words    fbrli_rb_comm_words
#define rb_fail          fbrli_rb_fail
#define rb_fail_st       fbrli_rb_fail_st
#define rb_finite        fbrli_rb_finite
#define rb_from_arm      fbrli_rb_from_arm
#define rb_import_nwords fbrli_rb_import_nwords
#define rb_import_words  fbrli_rb_import_words
#define rb_interrupted   fbrli_rb_interrupted
#define rb_io_nwords     fbrli_rb_io_nwords
#define rb_io_words      fbrli_rb_io_words
#define rb_len_in        fbrli_rb_len_in
#define rb_line_nwords   fbrli_rb_line_nwords
#define rb_line_words    fbrli_rb_line_words
#define rb_link_result   fbrli_rb_link_result
#define rb_loc_read      fbrli_rb_loc_read
#define rb_loc_write     fbrli_rb_loc_write
#define rb_metric        fbrli_rb_metric
#define rb_motion_nwords fbrli_rb_motion_nwords
#define rb_motion_words  fbrli_rb_motion_words
#define rb_name_arg      fbrli_rb_name_arg
#define rb_naxes         fbrli_rb_naxes
#define rb_now_ms        fbrli_rb_now_ms
#define rb_online        fbrli_rb_online
#define rb_param_nwords  fbrli_rb_param_nwords
#define rb_param_words   fbrli_rb_param_words
#define rb_params        fbrli_rb_params
#define rb_fetch         fbrli_rb_fetch
#define rb_parse_param   fbrli_rb_parse_param
#define rb_port_writer   fbrli_rb_port_writer
#define rb_puts          fbrli_rb_puts
#define rb_range         fbrli_rb_range
#define rb_rapl_nwords   fbrli_rb_rapl_nwords
#define rb_rapl_words    fbrli_rb_rapl_words
#define rb_raw           fbrli_rb_raw
#define rb_raw_lines     fbrli_rb_raw_lines
#define rb_resync        fbrli_rb_resync
#define rb_scratch_point fbrli_rb_scratch_point
#define rb_show          fbrli_rb_show
#define rb_sleep_ms      fbrli_rb_sleep_ms
#define rb_still         fbrli_rb_still
#define rb_stream        fbrli_rb_stream
#define rb_teach_nwords  fbrli_rb_teach_nwords
#define rb_teach_words   fbrli_rb_teach_words
#define rb_to_arm        fbrli_rb_to_arm
#define rb_wait_ms       fbrli_rb_wait_ms

#endif
