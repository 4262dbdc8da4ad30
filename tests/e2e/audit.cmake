# SPDX-License-Identifier: MIT
# Issue 30, the audit trail: runs by fbrlmon against fbrlsim written as the chain, 1,000
# tamperings refused at their record, replays byte for byte, the review report
# (tests/e2e/audit_e2e.py).
if(TARGET fbrlmon AND TARGET fbrlsim AND TARGET fbrl-audit AND TARGET fbrl-users AND Python3_Interpreter_FOUND)
  add_test(NAME audit_e2e COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/audit_e2e.py
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> $<TARGET_FILE:fbrl-audit> $<TARGET_FILE:fbrl-users>
    ${PROJECT_BINARY_DIR}/e2e-audit ${PROJECT_SOURCE_DIR})
  set_tests_properties(audit_e2e PROPERTIES LABELS e2e TIMEOUT 600
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon AND TARGET fbrlsim AND TARGET fbrl-audit AND TARGET fbrl-users)
  # the console under tmux with named users: sign-in, a Released run, refusals, lockout, idle sign-out
  add_test(NAME console_audit COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/console_audit.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-console-audit ${PROJECT_SOURCE_DIR})
  set_tests_properties(console_audit PROPERTIES LABELS e2e TIMEOUT 240 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon AND TARGET fbrlsim AND TARGET fbrl-audit)
  # what is typed at fbrlmon's prompt joins the chain, sealed when the session ends
  add_test(NAME prompt_audit COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/prompt_audit.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> $<TARGET_FILE:fbrl-audit> ${PROJECT_BINARY_DIR}/e2e-prompt-audit)
  set_tests_properties(prompt_audit PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
