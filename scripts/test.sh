#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what is missing, builds libfbrl with warnings as errors, and runs every test.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/deps.sh"
"$here/scripts/build.sh" "$here/build" -DFBRL_WERROR=ON
cd "$here/build"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
