# SPDX-License-Identifier: MIT
# Issue 16, the operator console: fbrlmon --console under tmux against fbrlsim
# (tests/e2e/console.sh: the sample-prep method run, paused, resumed, aborted, run again).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME console_e2e COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/console.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-console ${PROJECT_SOURCE_DIR})
  set_tests_properties(console_e2e PROPERTIES LABELS e2e TIMEOUT 180 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon AND TARGET fbrlsim)
  # the live arm panel and the abort question over a motion's progress (real-time fbrlsim)
  add_test(NAME console_live COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/console_live.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-console-live)
  set_tests_properties(console_live PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon AND TARGET fbrlsim)
  # issue 27: a taught place wins over a method file's; the exit prompt names what a save
  # changes and defaults to keeping what was taught (against the workspace file)
  add_test(NAME console_taught COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/console_taught.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-console-taught ${PROJECT_SOURCE_DIR})
  set_tests_properties(console_taught PROPERTIES LABELS e2e TIMEOUT 180 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon AND TARGET fbrlsim)
  # issue 28: a library with /dev/zero, a FIFO and a deep METHOD line starts at once; a run
  # log that cannot be written stops the run with the reason on the screen and exit status 1
  add_test(NAME console_library COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/console_library.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-console-library ${PROJECT_SOURCE_DIR})
  set_tests_properties(console_library PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon AND TARGET fbrlsim)
  # issue 27: the end screen of a run whose samples failed says so, sample by sample
  add_test(NAME console_outcome COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/console_outcome.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-console-outcome ${PROJECT_SOURCE_DIR})
  set_tests_properties(console_outcome PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
