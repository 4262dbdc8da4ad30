#!/bin/sh
# SPDX-License-Identifier: MIT
# Configure and build into a build directory. Usage: build.sh BUILD_DIR [cmake args...]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$1; shift
gen=""
command -v ninja >/dev/null 2>&1 && gen="-G Ninja"
# The generator can only be chosen when the directory is first configured.
[ -f "$dir/CMakeCache.txt" ] && gen=""
# shellcheck disable=SC2086
cmake -S "$here" -B "$dir" $gen "$@" >/dev/null
cmake --build "$dir" -j "$(nproc 2>/dev/null || echo 2)"
