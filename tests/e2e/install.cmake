# SPDX-License-Identifier: MIT
# The installed library serves lab programs: find_package(fbrl) and pkg-config.
add_test(NAME install_consumers
  COMMAND ${PROJECT_SOURCE_DIR}/tests/install/install_test.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR})
set_tests_properties(install_consumers PROPERTIES LABELS "e2e;install" TIMEOUT 180)
