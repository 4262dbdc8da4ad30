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
