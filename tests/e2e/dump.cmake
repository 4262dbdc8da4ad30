# SPDX-License-Identifier: MIT
# fbrl-dump (label e2e): data files and workspaces written by fbrlmon, read back as JSON and
# CSV and compared with an independent reader of the on-disk format (tests/e2e/dump_test.py).
if(TARGET fbrl-dump AND TARGET fbrlmon AND Python3_Interpreter_FOUND)
  add_test(NAME fbrl_dump COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/dump_test.py
    $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrl-dump> ${PROJECT_BINARY_DIR}/e2e-dump)
  set_tests_properties(fbrl_dump PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()

# Errors that say what happened (tests/e2e/file_errors.sh): a link loop, saving through a
# symlink, a read-only file and file system, permission denied, a full disk (a small tmpfs
# when one can be mounted, else a file size limit).
if(TARGET fbrlmon)
  add_test(NAME file_errors COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/file_errors.sh $<TARGET_FILE:fbrlmon>
    ${PROJECT_BINARY_DIR}/e2e-file-errors)
  set_tests_properties(file_errors PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
