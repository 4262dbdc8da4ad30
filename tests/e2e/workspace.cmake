# SPDX-License-Identifier: MIT
# A session's work survives (docs/workspace.md): two fbrlmon processes on real fbrlsim
# processes (their command logs), damaged workspace files (label e2e).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME workspace_e2e COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/workspace_test.sh $<TARGET_FILE:fbrlmon>
    $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-workspace)
  set_tests_properties(workspace_e2e PROPERTIES LABELS e2e TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
