# SPDX-License-Identifier: MIT
# Calibrated orientation against the emulated arm (label unit): the mapping's stability
# under teaching error and the grip's heading through the emulator's inverse kinematics;
# and the sample-preparation plan with its pins jogged to different heights (label e2e).
if(TARGET fbrlsim)
  add_executable(calib_arm_test ${CMAKE_CURRENT_SOURCE_DIR}/e2e/calib_arm_test.c)
  target_include_directories(calib_arm_test PRIVATE ${CMOCKA_INCLUDE})
  target_link_libraries(calib_arm_test PRIVATE fbrlsim_core fbrl_static ${CMOCKA_LIB} m)
  add_test(NAME calib_arm COMMAND calib_arm_test)
  set_tests_properties(calib_arm PROPERTIES LABELS unit TIMEOUT 60)
endif()
if(TARGET fbrlsim AND TARGET fbrlmon)
  add_test(NAME calib_plan_jogged COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/calib_plan.sh
    $<TARGET_FILE:fbrlsim> $<TARGET_FILE:fbrlmon> ${PROJECT_SOURCE_DIR}/examples
    ${PROJECT_BINARY_DIR}/e2e-calib-plan ${CMAKE_CURRENT_SOURCE_DIR}/e2e/plan_run.sh
    ${PROJECT_SOURCE_DIR}/examples/tube_present.inputs)
  set_tests_properties(calib_plan_jogged PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
