# TEACH, fbrlmon's keyboard teach pendant, on a real pty against a real fbrlsim
# process (label e2e; tests/e2e/mon_teach.c).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_executable(mon_teach ${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_teach.c)
  target_compile_definitions(mon_teach PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE)
  add_test(NAME mon_teach COMMAND mon_teach $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim>
    ${PROJECT_BINARY_DIR}/e2e-teach)
  set_tests_properties(mon_teach PROPERTIES LABELS e2e TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
