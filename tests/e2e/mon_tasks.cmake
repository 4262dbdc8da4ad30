# SPDX-License-Identifier: MIT
# Tasks at fbrlmon's prompt on a real terminal (tmux) against a real fbrlsim
# (tests/e2e/mon_tasks.sh; skipped without tmux).
if(TARGET fbrlsim AND TARGET fbrlmon)
  add_test(NAME mon_tasks COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_tasks.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-mon-tasks)
  set_tests_properties(mon_tasks PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
