# SPDX-License-Identifier: MIT
# The shared library's interface (label abi, docs/abi.md): it exports exactly the
# FBRL_API names of the public headers; every global name of the static library carries
# the prefix; a program with its own copies of the names 0.1.0 leaked still gets the
# library's results (shared and static); the ABI matches the committed baseline.
set(_abi_dir ${CMAKE_CURRENT_SOURCE_DIR}/abi)
set(_abi_tests "")
foreach(kind shared static)
  set(_lib fbrl)
  if(kind STREQUAL "static")
    set(_lib fbrl_static)
  endif()
  add_executable(abi_namesakes_${kind} ${_abi_dir}/namesakes.c)
  target_link_libraries(abi_namesakes_${kind} PRIVATE ${_lib})
  add_test(NAME abi_namesakes_${kind} COMMAND abi_namesakes_${kind})
  list(APPEND _abi_tests abi_namesakes_${kind})
endforeach()
# A sanitizer adds its own names to the library (ASan's __odr_asan.*): names, exports and
# the ABI are checked on the plain build only.
if(FBRL_SANITIZE STREQUAL "")
  add_test(NAME abi_prefix COMMAND ${Python3_EXECUTABLE} ${_abi_dir}/exports.py --static $<TARGET_FILE:fbrl_static>
    ${PROJECT_SOURCE_DIR}/include/fbrl ${FBRL_GENERATED_INCLUDE}/fbrl)
  list(APPEND _abi_tests abi_prefix)
  add_test(NAME abi_exports COMMAND ${Python3_EXECUTABLE} ${_abi_dir}/exports.py --shared $<TARGET_FILE:fbrl>
    ${PROJECT_SOURCE_DIR}/include/fbrl ${FBRL_GENERATED_INCLUDE}/fbrl)
  add_test(NAME abi_check COMMAND sh ${_abi_dir}/abi_check.sh $<TARGET_FILE:fbrl> ${PROJECT_SOURCE_DIR}/abi/libfbrl.abi
    ${PROJECT_BINARY_DIR}/abi-check)
  set_tests_properties(abi_check PROPERTIES SKIP_RETURN_CODE 77)
  list(APPEND _abi_tests abi_exports abi_check)
endif()
set_tests_properties(${_abi_tests} PROPERTIES LABELS "abi;unit" TIMEOUT 120)
