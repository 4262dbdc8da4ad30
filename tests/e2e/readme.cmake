# SPDX-License-Identifier: MIT
# README.md's commands and examples, read from README.md itself and run as written
# (tests/e2e/readme_test.sh). The sample-preparation plan runs in the built-in emulator's
# real time (about a minute): label readme as well as e2e.
if(TARGET fbrlsim AND TARGET fbrlmon)
  add_test(NAME readme_examples COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/readme_test.sh
    ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR} $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim>)
  set_tests_properties(readme_examples PROPERTIES LABELS "e2e;readme" TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()

# docs/guide.md's sessions, plan file and commands, run in order; the outputs it shows must
# be what they print (tests/e2e/guide_test.sh).
if(TARGET fbrlsim AND TARGET fbrlmon)
  add_test(NAME docs_guide COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/guide_test.sh
    ${PROJECT_SOURCE_DIR}/docs/guide.md $<TARGET_FILE_DIR:fbrlmon> $<TARGET_FILE_DIR:fbrlsim>)
  set_tests_properties(docs_guide PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
