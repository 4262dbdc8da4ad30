# SPDX-License-Identifier: MIT
# fbrlsim tests: the emulator driven over real
# pseudo-terminals by a small raw client (label e2e), one ctest entry per group.
if(TARGET fbrlsim)
  add_executable(sim_e2e_test ${CMAKE_CURRENT_SOURCE_DIR}/e2e/sim_e2e_test.c)
  target_include_directories(sim_e2e_test PRIVATE ${CMOCKA_INCLUDE})
  target_compile_definitions(sim_e2e_test PRIVATE _GNU_SOURCE FBRLSIM_PATH="$<TARGET_FILE:fbrlsim>")
  target_link_libraries(sim_e2e_test PRIVATE fbrlsim_core ${CMOCKA_LIB} Threads::Threads m)
  add_dependencies(sim_e2e_test fbrlsim)
  foreach(group line motion io persist baud faults log tcp embed model clients flow ctlq)
    add_test(NAME sim_${group} COMMAND sim_e2e_test ${group})
    set(labels e2e)
    if(group STREQUAL "embed")
      list(APPEND labels threads)
    endif()
    set_tests_properties(sim_${group} PROPERTIES LABELS "${labels}" TIMEOUT 120)
  endforeach()
  if(TARGET fbrlmon)
    add_test(NAME sim_mon_a465 COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/sim_mon_a465.sh $<TARGET_FILE:fbrlmon>
                                       $<TARGET_FILE:fbrlsim> ${CMAKE_CURRENT_BINARY_DIR}/sim_mon_a465)
    set_tests_properties(sim_mon_a465 PROPERTIES LABELS e2e TIMEOUT 120)
  endif()
endif()

# A client the project did not write (docs/fbrlsim.md, "A real client"): the York Xarm serial
# code for the CRSPLUS 250 (1992), xarmopen.c from a checkout of murray484/MediaMathConveyor
# named by FBRL_XARM_DIR, compiled as it is (its 1992 C, warnings off) beside a driver that
# sends 23 commands with it and checks each reply is the command's own (test sim_xarm_client).
set(FBRL_XARM_DIR "" CACHE PATH "a checkout of murray484/MediaMathConveyor: the York Xarm client for sim_xarm_client")
if(TARGET fbrlsim AND FBRL_XARM_DIR AND EXISTS ${FBRL_XARM_DIR}/xarmopen.c)
  add_library(xarm_open OBJECT ${FBRL_XARM_DIR}/xarmopen.c)
  set_target_properties(xarm_open PROPERTIES C_STANDARD 90 C_EXTENSIONS ON)
  target_compile_options(xarm_open PRIVATE -w)
  target_include_directories(xarm_open PRIVATE ${FBRL_XARM_DIR})
  add_executable(xarm_client ${CMAKE_CURRENT_SOURCE_DIR}/e2e/xarm_client.c $<TARGET_OBJECTS:xarm_open>)
  target_compile_definitions(xarm_client PRIVATE _DEFAULT_SOURCE)
  target_link_options(xarm_client PRIVATE -Wl,--wrap=read)
  add_test(NAME sim_xarm_client COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/xarm_sync.sh $<TARGET_FILE:fbrlsim>
                                        $<TARGET_FILE:xarm_client> ${CMAKE_CURRENT_BINARY_DIR}/sim_xarm_client)
  set_tests_properties(sim_xarm_client PROPERTIES LABELS e2e TIMEOUT 120)
endif()
