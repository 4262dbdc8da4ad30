# SPDX-License-Identifier: MIT
# TEACH, fbrlmon's keyboard teach pendant, on a real pty against a real fbrlsim
# process (label e2e; tests/e2e/mon_teach.c).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_executable(mon_teach ${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_teach.c)
  target_compile_definitions(mon_teach PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE)
  add_test(NAME mon_teach COMMAND mon_teach $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim>
    ${PROJECT_BINARY_DIR}/e2e-teach)
  set_tests_properties(mon_teach PROPERTIES LABELS e2e TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
  # GET-CAL-POINTS at the terminal: line editing, retries, TEACH inside, Ctrl-C (needs libedit)
  get_target_property(_calpts_edit fbrlmon FBRLMON_LIBEDIT)
  if(_calpts_edit)
    add_executable(mon_calpts ${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_calpts.c)
    target_compile_definitions(mon_calpts PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE)
    add_test(NAME mon_calpts COMMAND mon_calpts $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim>
      ${PROJECT_BINARY_DIR}/e2e-calpts)
    set_tests_properties(mon_calpts PROPERTIES LABELS e2e TIMEOUT 300
      ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
  endif()
endif()
