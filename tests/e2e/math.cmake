# SPDX-License-Identifier: MIT
# The rack example runs as a real program: its calibration survives save/load, and its
# own cross-checks (mapped vs. the true move, map then unmap) stay below 1e-10 in.
if(TARGET example_rack)
  add_test(NAME e2e_rack_example COMMAND $<TARGET_FILE:example_rack>)
  add_test(NAME e2e_rack_example_metric COMMAND $<TARGET_FILE:example_rack> --metric)
  set_tests_properties(e2e_rack_example e2e_rack_example_metric PROPERTIES LABELS e2e TIMEOUT 60
    PASS_REGULAR_EXPRESSION "reloaded identical.*D6 .*true move: [0-9.]+e-(1[0-9]|[2-9][0-9]) in;.*worst [0-9.]+e-(1[0-9]|[2-9][0-9]) in")
endif()
