# SPDX-License-Identifier: MIT
# lang.cmake - random-program runs against the FBRL language engine (label fuzz).
add_executable(lang_random ${PROJECT_SOURCE_DIR}/tests/fuzz/lang_random.c)
target_link_libraries(lang_random PRIVATE fbrl_static m)
add_test(NAME lang_random COMMAND lang_random 1 32 10000)
set_tests_properties(lang_random PROPERTIES LABELS fuzz TIMEOUT 300)
