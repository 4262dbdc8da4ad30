# SPDX-License-Identifier: MIT
# sim_control_test (label unit): fbrlsim's control lines, --inputs file, long RUNs and state file lines,
# called in-process through fbrlsim_core (no pty, no client).
if(TARGET fbrlsim_core)
  add_executable(sim_control_test ${CMAKE_CURRENT_SOURCE_DIR}/e2e/sim_control_test.c)
  target_include_directories(sim_control_test PRIVATE ${CMOCKA_INCLUDE} ${PROJECT_SOURCE_DIR}/sim)
  target_compile_definitions(sim_control_test PRIVATE _GNU_SOURCE)
  target_link_libraries(sim_control_test PRIVATE fbrlsim_core ${CMOCKA_LIB} Threads::Threads m)
  add_test(NAME sim_control COMMAND sim_control_test)
  set_tests_properties(sim_control PROPERTIES LABELS unit TIMEOUT 60)
endif()
