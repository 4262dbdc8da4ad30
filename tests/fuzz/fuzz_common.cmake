# SPDX-License-Identifier: MIT
# fuzz_common.cmake - what every fuzz fragment uses (included first: the fragments
# are read in name order and this name sorts before them).
#  - FBRL_FUZZ_SECONDS: how long ctest runs each libFuzzer target (label fuzz).
#  - FBRL_HAVE_LIBFUZZER: the compiler is clang and links -fsanitize=fuzzer.
#  - _fuzz_san: the sanitizers of a libFuzzer target (ASan+UBSan unless the build has its own).
#  - fuzz_targets: builds every fuzz program (the CI's clang step builds only these).
set(FBRL_FUZZ_SECONDS 5 CACHE STRING "Seconds ctest runs each libFuzzer target (docs/fuzzing.md)")
if(NOT FBRL_FUZZ_SECONDS MATCHES "^[1-9][0-9]*$")
  message(FATAL_ERROR "FBRL_FUZZ_SECONDS must be a whole number of seconds >= 1")
endif()
add_custom_target(fuzz_targets)
if(CMAKE_C_COMPILER_ID MATCHES "Clang")
  include(CheckCSourceCompiles)
  set(CMAKE_REQUIRED_FLAGS -fsanitize=fuzzer)
  check_c_source_compiles("
    #include <stddef.h>
    #include <stdint.h>
    int LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }"
    FBRL_HAVE_LIBFUZZER)
  unset(CMAKE_REQUIRED_FLAGS)
endif()
set(_fuzz_san -fsanitize=fuzzer)
if(FBRL_SANITIZE STREQUAL "")
  set(_fuzz_san -fsanitize=fuzzer,address,undefined)
endif()
