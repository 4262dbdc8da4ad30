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
