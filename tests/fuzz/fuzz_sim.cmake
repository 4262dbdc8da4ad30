# SPDX-License-Identifier: MIT
# fuzz_sim.cmake - fuzz targets for fbrlsim (command line and control lines, state
# file, --inputs file) and for the typed data file reader (src/fileio.c).
#  - fuzz_replay_<target> (every build, also under ASan): the seed corpus
#    tests/fuzz/corpus/<target>/ (seeds and regression inputs) through the target.
#  - fuzz_<target> (clang with libFuzzer only): libFuzzer for FBRL_FUZZ_SECONDS.
# docs/fuzzing.md says what each target checks and how to fuzz for longer.
set(_fuzz_dir ${CMAKE_CURRENT_SOURCE_DIR}/fuzz)
set(_fuzz_sim_targets sim_cmd sim_state sim_inputs)

# The emulator's sources, as fbrlsim_core has them, with the harness's clock
# (fuzz_sim_clock.c) in place of sim_clock.c.
get_target_property(_fuzz_sim_core_src fbrlsim_core SOURCES)
set(_fuzz_sim_src "")
foreach(f ${_fuzz_sim_core_src})
  if(NOT f MATCHES "(^|/)sim_clock\\.c$")
    get_filename_component(f ${f} ABSOLUTE BASE_DIR ${PROJECT_SOURCE_DIR}/sim)
    list(APPEND _fuzz_sim_src ${f})
  endif()
endforeach()
set(_fuzz_sim_harness ${_fuzz_dir}/fuzz_sim.c ${_fuzz_dir}/fuzz_sim_clock.c ${_fuzz_dir}/fuzz_util.c)
# ... and what fbrlsim_core links (libfbrl's RAPL command table, threads, libm).
get_target_property(_fuzz_sim_libs fbrlsim_core LINK_LIBRARIES)

function(_fuzz_sim_setup t)
  target_include_directories(${t} PRIVATE ${PROJECT_SOURCE_DIR}/sim ${PROJECT_SOURCE_DIR}/include ${PROJECT_BINARY_DIR}/include ${_fuzz_dir})
  target_compile_definitions(${t} PRIVATE _GNU_SOURCE)
  get_target_property(_type ${t} TYPE)
  if(_type STREQUAL "EXECUTABLE")
    target_link_libraries(${t} PRIVATE ${_fuzz_sim_libs})
  endif()
endfunction()

add_library(fuzz_sim_replay_obj OBJECT ${_fuzz_sim_src} ${_fuzz_sim_harness})
_fuzz_sim_setup(fuzz_sim_replay_obj)
foreach(t ${_fuzz_sim_targets})
  add_executable(fuzz_replay_${t} ${_fuzz_dir}/fuzz_replay.c ${_fuzz_dir}/fuzz_${t}.c
    $<TARGET_OBJECTS:fuzz_sim_replay_obj>)
  _fuzz_sim_setup(fuzz_replay_${t})
endforeach()
add_executable(fuzz_replay_fileio ${_fuzz_dir}/fuzz_replay.c ${_fuzz_dir}/fuzz_fileio.c ${_fuzz_dir}/fuzz_util.c)
target_compile_definitions(fuzz_replay_fileio PRIVATE _GNU_SOURCE)
target_link_libraries(fuzz_replay_fileio PRIVATE fbrl_static)

if(FBRL_HAVE_LIBFUZZER)
  # Compiled again with coverage instrumentation (and ASan+UBSan, see fuzz_common.cmake).
  string(REPLACE "-fsanitize=fuzzer" "-fsanitize=fuzzer-no-link" _fuzz_san_obj "${_fuzz_san}")
  add_library(fuzz_sim_obj OBJECT ${_fuzz_sim_src} ${_fuzz_sim_harness})
  _fuzz_sim_setup(fuzz_sim_obj)
  target_compile_options(fuzz_sim_obj PRIVATE ${_fuzz_san_obj} -fno-omit-frame-pointer)
  foreach(t ${_fuzz_sim_targets})
    add_executable(fuzz_${t} ${_fuzz_dir}/fuzz_${t}.c $<TARGET_OBJECTS:fuzz_sim_obj>)
    _fuzz_sim_setup(fuzz_${t})
  endforeach()
  add_executable(fuzz_fileio ${_fuzz_dir}/fuzz_fileio.c ${_fuzz_dir}/fuzz_util.c
    ${PROJECT_SOURCE_DIR}/src/fileio.c ${PROJECT_SOURCE_DIR}/src/fileio_posix.c ${PROJECT_SOURCE_DIR}/src/crc32.c)
  target_include_directories(fuzz_fileio PRIVATE ${PROJECT_SOURCE_DIR}/include ${PROJECT_BINARY_DIR}/include ${PROJECT_SOURCE_DIR}/src)
  target_compile_definitions(fuzz_fileio PRIVATE _GNU_SOURCE)
  foreach(t ${_fuzz_sim_targets} fileio)
    target_compile_options(fuzz_${t} PRIVATE ${_fuzz_san} -fno-omit-frame-pointer)
    target_link_options(fuzz_${t} PRIVATE ${_fuzz_san})
  endforeach()
endif()

math(EXPR _fuzz_timeout "${FBRL_FUZZ_SECONDS} + 120")
foreach(t ${_fuzz_sim_targets} fileio)
  add_test(NAME fuzz_replay_${t} COMMAND fuzz_replay_${t} ${_fuzz_dir}/corpus/${t})
  set_tests_properties(fuzz_replay_${t} PROPERTIES LABELS fuzz TIMEOUT 300)
  add_dependencies(fuzz_targets fuzz_replay_${t})
  if(FBRL_HAVE_LIBFUZZER)
    # New inputs go to a corpus in the build tree; the seeds stay read-only.
    file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/fuzz/${t} ${PROJECT_BINARY_DIR}/fuzz/artifacts)
    add_test(NAME fuzz_${t} COMMAND fuzz_${t} -max_total_time=${FBRL_FUZZ_SECONDS} -timeout=10
      -rss_limit_mb=2048 -artifact_prefix=${PROJECT_BINARY_DIR}/fuzz/artifacts/${t}-
      ${PROJECT_BINARY_DIR}/fuzz/${t} ${_fuzz_dir}/corpus/${t})
    set_tests_properties(fuzz_${t} PROPERTIES LABELS fuzz TIMEOUT ${_fuzz_timeout})
    add_dependencies(fuzz_targets fuzz_${t})
  endif()
endforeach()
