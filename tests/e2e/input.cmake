# SPDX-License-Identifier: MIT
# fbrlmon and INCLUDED on input without an end (issue 20 item 4; label e2e): devices and
# FIFOs refused, over-long lines stopped at the limit with file:line, each within a second.
if(TARGET fbrlmon)
  add_test(NAME mon_input COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_input.sh $<TARGET_FILE:fbrlmon>
    ${PROJECT_BINARY_DIR}/e2e-mon-input)
  set_tests_properties(mon_input PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
