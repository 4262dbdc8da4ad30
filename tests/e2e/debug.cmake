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
