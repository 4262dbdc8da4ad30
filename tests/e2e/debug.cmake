# SPDX-License-Identifier: MIT
# Finding and fixing a plan (docs/debugging.md): backtraces, breakpoints and steps, EDIT,
# against fbrlsim on a pty.
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME debug_session COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/debug_session.sh $<TARGET_FILE:fbrlmon>
                                      $<TARGET_FILE:fbrlsim> ${CMAKE_CURRENT_BINARY_DIR}/debug_session)
  set_tests_properties(debug_session PROPERTIES LABELS e2e TIMEOUT 120)
endif()
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME recover_session COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/recover_session.sh $<TARGET_FILE:fbrlmon>
                                        $<TARGET_FILE:fbrlsim> ${CMAKE_CURRENT_BINARY_DIR}/recover_session)
  set_tests_properties(recover_session PROPERTIES LABELS e2e TIMEOUT 180)
endif()
# The debugger at a real terminal (tmux; skipped without it): steps over built-ins, a line
# breakpoint on the failing line, UNBREAK ALL, EDIT of a file with tasks.
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME debug_tmux COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/debug_tmux.sh $<TARGET_FILE:fbrlmon>
                                   $<TARGET_FILE:fbrlsim> ${CMAKE_CURRENT_BINARY_DIR}/debug_tmux)
  set_tests_properties(debug_tmux PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
