# SPDX-License-Identifier: MIT
# End-to-end tests of fbrlmon (label e2e): scripts and piped input, the bad-input
# cases (tests/e2e/mon_badinput.txt) and an interactive session on a real pty.
if(TARGET fbrlmon)
  set(_mon_dir ${CMAKE_CURRENT_SOURCE_DIR}/e2e)
  set(_mon_tmp ${PROJECT_BINARY_DIR}/e2e-mon)
  file(MAKE_DIRECTORY ${_mon_tmp})

  foreach(t mon_cases mon_pty)
    add_executable(${t} ${_mon_dir}/${t}.c)
    target_compile_definitions(${t} PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE)
  endforeach()

  add_test(NAME mon_script COMMAND sh ${_mon_dir}/mon_script.sh $<TARGET_FILE:fbrlmon> ${_mon_dir} ${_mon_tmp}/script)
  add_test(NAME mon_badinput COMMAND mon_cases $<TARGET_FILE:fbrlmon> ${_mon_dir}/mon_badinput.txt ${_mon_tmp})
  set(_mon_tests mon_script mon_badinput)
  # Editing, completion and history need libedit; the plain line loop has none.
  get_target_property(_mon_edit fbrlmon FBRLMON_LIBEDIT)
  if(_mon_edit)
    add_test(NAME mon_pty COMMAND mon_pty $<TARGET_FILE:fbrlmon> ${_mon_tmp}/pty)
    list(APPEND _mon_tests mon_pty)
  endif()
  if(TARGET fbrlsim)
    add_test(NAME mon_conn COMMAND sh ${_mon_dir}/mon_conn.sh $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${_mon_tmp}/conn)
    list(APPEND _mon_tests mon_conn)
    add_test(NAME mon_nonfinite COMMAND sh ${_mon_dir}/mon_nonfinite.sh $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${_mon_tmp}/nonfinite)
    list(APPEND _mon_tests mon_nonfinite)
    add_test(NAME mon_units COMMAND sh ${_mon_dir}/mon_units.sh $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${_mon_tmp}/units)
    list(APPEND _mon_tests mon_units)
  endif()
  set_tests_properties(${_mon_tests} PROPERTIES LABELS e2e TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${_mon_dir}/mon_lsan.supp")
endif()
