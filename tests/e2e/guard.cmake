# SPDX-License-Identifier: MIT
# One gate for every motion (docs/workcell.md "The guard"): the five ways past the guard that
# once drove the arm into the cell, each against fbrlsim --cell with the same cell, fbrlmon at a
# real terminal (tests/e2e/guard_bypass.c; label e2e).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_executable(guard_bypass ${CMAKE_CURRENT_SOURCE_DIR}/e2e/guard_bypass.c)
  target_compile_definitions(guard_bypass PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE)
  add_test(NAME guard_bypass COMMAND guard_bypass $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim>
    ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell ${PROJECT_BINARY_DIR}/e2e-guard)
  set_tests_properties(guard_bypass PROPERTIES LABELS e2e TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
