# SPDX-License-Identifier: MIT
# The sample-preparation plan end to end (label e2e): examples/sample_prep.fbrl run by
# fbrlmon, and the C example examples/sample_prep.c, each against a real fbrlsim process on
# a pty; the emulator's command log must equal the committed examples/*.expected exactly.
# tests/e2e/plan_run.sh does the run and the comparison (FBRL_REGEN=1 rewrites the files).
if(TARGET fbrlsim AND TARGET fbrlmon)
  set(_plan_ex ${PROJECT_SOURCE_DIR}/examples)
  set(_plan_run sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/plan_run.sh $<TARGET_FILE:fbrlsim>)
  set(_plan_tmp ${PROJECT_BINARY_DIR}/e2e-plan)
  # tubes arrive on the separation unit: its sensor (input 3) is on
  add_test(NAME plan_sample_prep COMMAND ${_plan_run} ${_plan_tmp}/full
    ${_plan_ex}/tube_present.inputs
    ${_plan_ex}/sample_prep.expected ${_plan_ex}/sample_prep.out.expected
    $<TARGET_FILE:fbrlmon> -e "600 CONSTANT TIME-SCALE" --port @PORT@ ${_plan_ex}/sample_prep.fbrl)
  # the sensor never sees a tube: every WAIT-INPUT times out, no vacuum, no rinse
  add_test(NAME plan_sample_prep_notube COMMAND ${_plan_run} ${_plan_tmp}/notube -
    ${_plan_ex}/sample_prep_notube.expected ${_plan_ex}/sample_prep_notube.out.expected
    $<TARGET_FILE:fbrlmon> -e "600 CONSTANT TIME-SCALE" --port @PORT@ ${_plan_ex}/sample_prep.fbrl)
  set(_plan_tests plan_sample_prep plan_sample_prep_notube)
  if(TARGET example_sample_prep)
    add_test(NAME plan_sample_prep_c COMMAND ${_plan_run} ${_plan_tmp}/c
      ${_plan_ex}/tube_present.inputs
      ${_plan_ex}/sample_prep_c.expected ${_plan_ex}/sample_prep_c.out.expected
      $<TARGET_FILE:example_sample_prep> @PORT@)
    list(APPEND _plan_tests plan_sample_prep_c)
  endif()
  # fbrlmon's known leak suppressions for sanitizer builds (as in mon.cmake)
  set_tests_properties(${_plan_tests} PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
  set_tests_properties(plan_sample_prep_notube PROPERTIES ENVIRONMENT
    "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp;PLAN_COLLAPSE_POLLS=1")
endif()
