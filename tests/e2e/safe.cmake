# SPDX-License-Identifier: MIT
# Ctrl-C makes the cell safe, and a controller that goes away comes back: fbrlmon on a
# real pty against a real fbrlsim process (label e2e; tests/e2e/mon_safe.c).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_executable(mon_safe ${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_safe.c)
  target_compile_definitions(mon_safe PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE)
  target_link_libraries(mon_safe PRIVATE m)
  add_test(NAME mon_safe COMMAND mon_safe $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim>
    ${PROJECT_BINARY_DIR}/e2e-safe)
  set_tests_properties(mon_safe PROPERTIES LABELS e2e TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
