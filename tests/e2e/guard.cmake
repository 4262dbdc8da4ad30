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

# The guard attacked at random in a cluttered cell: 2,000 moves, jogs and stops (HALT, arm
# power off mid-motion, two tasks), fbrlsim's log the truth (tests/e2e/guard_random.c; label
# e2e). The seed comes from the clock and is printed first; GUARD_RANDOM_SEED fixes it.
if(TARGET fbrlsim AND EXISTS ${PROJECT_SOURCE_DIR}/src/uart_posix.c)
  add_executable(guard_random ${CMAKE_CURRENT_SOURCE_DIR}/e2e/guard_random.c)
  target_include_directories(guard_random PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/e2e)
  target_compile_definitions(guard_random PRIVATE _DEFAULT_SOURCE)
  target_link_libraries(guard_random PRIVATE fbrl_static Threads::Threads m)
  add_dependencies(guard_random fbrlsim)
  add_test(NAME guard_random COMMAND guard_random $<TARGET_FILE:fbrlsim>
    ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell/cluttered.fbrl 2000)
  set_tests_properties(guard_random PROPERTIES LABELS e2e TIMEOUT 600)
endif()

# The guard for C callers: the robot layer from C (fbrl_robot_motion), the link's own
# commands on a guarded link (refused, or sent around the guard explicitly and told), raw
# bytes (tests/e2e/guard_link.c; label e2e).
if(TARGET fbrlsim AND EXISTS ${PROJECT_SOURCE_DIR}/src/uart_posix.c)
  add_executable(guard_link ${CMAKE_CURRENT_SOURCE_DIR}/e2e/guard_link.c)
  target_include_directories(guard_link PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/e2e)
  target_compile_definitions(guard_link PRIVATE _DEFAULT_SOURCE)
  target_link_libraries(guard_link PRIVATE fbrl_static Threads::Threads m)
  add_dependencies(guard_link fbrlsim)
  add_test(NAME guard_link COMMAND guard_link $<TARGET_FILE:fbrlsim> ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell/cell.fbrl)
  set_tests_properties(guard_link PROPERTIES LABELS e2e TIMEOUT 120)
endif()
