# SPDX-License-Identifier: MIT
# The Debian packages (label package): tests/package/package_test.sh builds them with
# dpkg-buildpackage from a copy of the tree, runs lintian and checks their contents. It
# builds the project once more (a few minutes on 2 cores); CI's sanitizer run leaves it out.
add_test(NAME package_deb COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/package/package_test.sh ${PROJECT_SOURCE_DIR}
  ${PROJECT_BINARY_DIR}/package)
# alone: its compile would slow the timing-sensitive tests running beside it
set_tests_properties(package_deb PROPERTIES LABELS package TIMEOUT 900 SKIP_RETURN_CODE 77 RUN_SERIAL TRUE)
