# SPDX-License-Identifier: MIT
# Robot words end to end: a VM with the data glossary and the robot words, over a real
# link (POSIX uart on a pty) to the real fbrlsim binary; one test per Forth file
# tests/forth/robot_*.fs (label e2e). Each checks results with tester.fs and the exact
# commands fbrlsim executed with LOG: (its --log).
if(TARGET fbrlsim AND EXISTS ${PROJECT_SOURCE_DIR}/src/uart_posix.c)
  add_executable(robot_e2e ${CMAKE_CURRENT_SOURCE_DIR}/e2e/robot_e2e.c)
  target_include_directories(robot_e2e PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/e2e)
  target_compile_definitions(robot_e2e PRIVATE _DEFAULT_SOURCE FBRL_TEST_SRCDIR="${PROJECT_SOURCE_DIR}")
  target_link_libraries(robot_e2e PRIVATE fbrl_static Threads::Threads m)
  add_dependencies(robot_e2e fbrlsim)
  file(GLOB robot_fs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/forth/robot_*.fs)
  foreach(fs ${robot_fs})
    get_filename_component(name ${fs} NAME_WE)
    # optional companions: NAME.inputs (fbrlsim --inputs), NAME.state (its starting memory)
    set(inputs ${CMAKE_CURRENT_SOURCE_DIR}/forth/${name}.inputs)
    set(state ${CMAKE_CURRENT_SOURCE_DIR}/forth/${name}.state)
    if(NOT EXISTS ${inputs})
      set(inputs -)
    endif()
    if(EXISTS ${state})
      add_test(NAME e2e_${name} COMMAND robot_e2e $<TARGET_FILE:fbrlsim> ${fs} ${inputs} ${state})
    else()
      add_test(NAME e2e_${name} COMMAND robot_e2e $<TARGET_FILE:fbrlsim> ${fs} ${inputs})
    endif()
    set_tests_properties(e2e_${name} PROPERTIES LABELS e2e TIMEOUT 120)
  endforeach()
endif()

# Readings while the arm moves: W2 W0 ACTUAL live, ARM-HERE final, against fbrlsim's own
# trajectory (its arm model from fbrlsim_core), 200 motions.
if(TARGET fbrlsim AND TARGET fbrlsim_core AND EXISTS ${PROJECT_SOURCE_DIR}/src/uart_posix.c)
  add_executable(robot_e2e_live ${CMAKE_CURRENT_SOURCE_DIR}/e2e/robot_e2e_live.c)
  target_include_directories(robot_e2e_live PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/e2e)
  target_compile_definitions(robot_e2e_live PRIVATE _DEFAULT_SOURCE)
  target_link_libraries(robot_e2e_live PRIVATE fbrlsim_core fbrl_static Threads::Threads m)
  add_dependencies(robot_e2e_live fbrlsim)
  add_test(NAME e2e_robot_live COMMAND robot_e2e_live $<TARGET_FILE:fbrlsim> 200 1)
  set_tests_properties(e2e_robot_live PROPERTIES LABELS e2e TIMEOUT 120)
endif()
