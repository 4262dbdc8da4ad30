# SPDX-License-Identifier: MIT
# The engine with the Cortex-M3 firmware's compile-time options, on the host (label unit):
# the Forth conformance suite and the cases the options change (cm3_engine_test.c). Built
# from the library's sources again with those options; needs no cross compiler.
# FBRL_PATH_MAX is left at its default: the suite is included by full paths, and the
# firmware reads no source files. FBRL_NO_FTRANS too: the suite's float.fs checks the
# transcendental words the firmware leaves out (FTAN, FSINH ... F**).
include(${PROJECT_SOURCE_DIR}/ports/cortex-m3/engine.cmake)
set(_cm3_engine_defs ${FBRL_CM3_ENGINE_DEFS})
list(FILTER _cm3_engine_defs EXCLUDE REGEX "^(FBRL_PATH_MAX=.*|FBRL_NO_FTRANS)$")
set(_cm3_engine_sources ${FBRL_SOURCES} ${FBRL_WORD_SOURCES})
add_executable(cm3_engine_test ${CMAKE_CURRENT_SOURCE_DIR}/qemu/cm3_engine_test.c ${_cm3_engine_sources})
target_include_directories(cm3_engine_test PRIVATE ${CMOCKA_INCLUDE} ${PROJECT_SOURCE_DIR}/include ${PROJECT_BINARY_DIR}/include
  ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/src/lang ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(cm3_engine_test PRIVATE _POSIX_C_SOURCE=200809L _DEFAULT_SOURCE
  FBRL_TEST_SRCDIR="${PROJECT_SOURCE_DIR}" ${_cm3_engine_defs})
target_link_libraries(cm3_engine_test PRIVATE ${CMOCKA_LIB} ${FBRL_LINK_LIBS})
add_test(NAME cm3_engine COMMAND cm3_engine_test)
set_tests_properties(cm3_engine PROPERTIES LABELS unit TIMEOUT 300)
