#!/bin/sh
# Configure and build into a build directory. Usage: build.sh BUILD_DIR [cmake args...]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$1; shift
gen=""
command -v ninja >/dev/null 2>&1 && gen="-G Ninja"
# shellcheck disable=SC2086
[ -f "$dir/CMakeCache.txt" ] || cmake -S "$here" -B "$dir" $gen "$@" >/dev/null
cmake -S "$here" -B "$dir" "$@" >/dev/null
cmake --build "$dir" -j "$(nproc 2>/dev/null || echo 2)"
