# SPDX-License-Identifier: MIT
# Issue 27, outcomes per sample and per run: the sample-prep method with and without its
# tube against fbrlsim, checked against fbrlsim's log, the run log and fbrlmon's exit status;
# its dry run's time-outs and predicted outcomes (tests/e2e/method_run.sh).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME method_run COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/method_run.sh
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/e2e-method-run ${PROJECT_SOURCE_DIR})
  set_tests_properties(method_run PROPERTIES LABELS e2e TIMEOUT 240
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
if(TARGET fbrlmon)
  # issue 28: a run log on a full small tmpfs ends in a clear error and a non-zero exit
  add_test(NAME runlog_full COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/runlog_full.sh $<TARGET_FILE:fbrlmon>
    ${PROJECT_BINARY_DIR}/e2e-runlog-full)
  set_tests_properties(runlog_full PROPERTIES LABELS e2e TIMEOUT 120 SKIP_RETURN_CODE 77
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
