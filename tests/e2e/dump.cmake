# SPDX-License-Identifier: MIT
# fbrl-dump (label e2e): data files and workspaces written by fbrlmon, read back as JSON and
# CSV and compared with an independent reader of the on-disk format (tests/e2e/dump_test.py).
if(TARGET fbrl-dump AND TARGET fbrlmon AND Python3_Interpreter_FOUND)
  add_test(NAME fbrl_dump COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/dump_test.py
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrl-dump> ${PROJECT_BINARY_DIR}/e2e-dump)
  set_tests_properties(fbrl_dump PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
