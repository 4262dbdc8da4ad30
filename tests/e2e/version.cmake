# SPDX-License-Identifier: MIT
# --version on every program: the version CMake's project() names (label e2e).
set(_version_progs "")
foreach(t fbrlmon fbrlsim fbrl-dump)
  if(TARGET ${t})
    list(APPEND _version_progs $<TARGET_FILE:${t}>)
  endif()
endforeach()
add_test(NAME programs_version COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/version.sh ${PROJECT_VERSION}
  ${_version_progs})
set_tests_properties(programs_version PROPERTIES LABELS e2e TIMEOUT 60)
