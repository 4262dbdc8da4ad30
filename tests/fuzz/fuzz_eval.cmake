# SPDX-License-Identifier: MIT
# fuzz_eval.cmake - fuzzing the FBRL evaluator (tests/fuzz/fuzz_eval.c), once the engine exists.
#  - fuzz_replay (every build): runs the seed corpus through the fuzz entry point.
#  - fuzz_eval (clang with -fsanitize=fuzzer only): libFuzzer for a bounded time.
# See docs/fbrlmon.md ("Fuzzing") for running the real fuzzer by hand.
file(GLOB _fuzz_engine ${PROJECT_SOURCE_DIR}/src/lang/*.c)
if(_fuzz_engine)
  set(_fuzz_dir ${CMAKE_CURRENT_SOURCE_DIR}/fuzz)

  add_executable(fuzz_replay ${_fuzz_dir}/fuzz_replay.c ${_fuzz_dir}/fuzz_eval.c)
  target_compile_definitions(fuzz_replay PRIVATE _POSIX_C_SOURCE=200809L)
  target_link_libraries(fuzz_replay PRIVATE fbrl_static)
  add_test(NAME fuzz_replay COMMAND fuzz_replay ${_fuzz_dir}/corpus/eval)
  set_tests_properties(fuzz_replay PROPERTIES LABELS fuzz TIMEOUT 300)
  add_dependencies(fuzz_targets fuzz_replay)

  if(FBRL_HAVE_LIBFUZZER)
    # The engine is compiled into the target again with coverage instrumentation
    # (the library objects are not), and with ASan+UBSan unless the build has them.
    add_executable(fuzz_eval ${_fuzz_dir}/fuzz_eval.c ${FBRL_SOURCES} ${FBRL_WORD_SOURCES})
    target_include_directories(fuzz_eval PRIVATE ${PROJECT_SOURCE_DIR}/include ${PROJECT_BINARY_DIR}/include ${PROJECT_SOURCE_DIR}/src)
    target_compile_definitions(fuzz_eval PRIVATE _POSIX_C_SOURCE=200809L)
    if(FBRL_HAVE_SERIALPORT)
      target_compile_definitions(fuzz_eval PRIVATE FBRL_HAVE_SERIALPORT=1)
      target_include_directories(fuzz_eval PRIVATE ${SERIALPORT_INCLUDE_DIRS})
    endif()
    target_compile_options(fuzz_eval PRIVATE ${_fuzz_san} -fno-omit-frame-pointer)
    target_link_options(fuzz_eval PRIVATE ${_fuzz_san})
    target_link_libraries(fuzz_eval PRIVATE ${FBRL_LINK_LIBS})
    # New inputs go to a corpus in the build tree; the seeds stay read-only.
    file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/fuzz/corpus ${PROJECT_BINARY_DIR}/fuzz/artifacts)
    add_test(NAME fuzz_eval COMMAND fuzz_eval -max_total_time=${FBRL_FUZZ_SECONDS} -timeout=10 -rss_limit_mb=2048
      -artifact_prefix=${PROJECT_BINARY_DIR}/fuzz/artifacts/
      ${PROJECT_BINARY_DIR}/fuzz/corpus ${_fuzz_dir}/corpus/eval)
    math(EXPR _fuzz_timeout "${FBRL_FUZZ_SECONDS} + 120")
    set_tests_properties(fuzz_eval PROPERTIES LABELS fuzz TIMEOUT ${_fuzz_timeout})
    add_dependencies(fuzz_targets fuzz_eval)
  endif()
endif()
