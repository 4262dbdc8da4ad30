# SPDX-License-Identifier: MIT
# Issue 10 item 1, "said once, where it should go": fbrlmon on an 80x24 tmux terminal
# against a real fbrlsim (tests/e2e/said_once.sh; skipped without tmux).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME mon_said_once COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/said_once.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-said-once)
  set_tests_properties(mon_said_once PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()

# Issue 10 item 3, messages that tell the user what happened (tests/e2e/messages.sh; the
# emulator runs in real time: about 20 s).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME mon_messages COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/messages.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-messages)
  set_tests_properties(mon_messages PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()

# Issue 27 item 6: fbrlmon FILE > run.log typed at a terminal runs the file and ends
# (tests/e2e/terminal_run.sh; skipped without tmux).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME mon_terminal_run COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/terminal_run.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-terminal-run)
  set_tests_properties(mon_terminal_run PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
