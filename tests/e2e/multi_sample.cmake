# SPDX-License-Identifier: MIT
# examples/multi_sample.fbrl shortened, on a real fbrlsim (tests/e2e/multi_sample.sh, ~8 s).
if(TARGET fbrlsim AND TARGET fbrlmon)
  add_test(NAME plan_multi_sample COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/multi_sample.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-multi-sample)
  set_tests_properties(plan_multi_sample PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
