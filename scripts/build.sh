#!/bin/sh
# SPDX-License-Identifier: MIT
# Configure and build into a build directory.
# Usage: build.sh BUILD_DIR [--target NAME]... [cmake args...]
# Without --target everything is built; with it only NAME (and what it needs).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$1; shift
targets=""
n=$#
while [ "$n" -gt 0 ]; do # keep the cmake args in order, take out the targets
    a=$1; shift; n=$((n - 1))
    if [ "$a" = "--target" ] && [ "$n" -gt 0 ]; then
        targets="$targets --target $1"; shift; n=$((n - 1))
    else
        set -- "$@" "$a"
    fi
done
gen=""
command -v ninja >/dev/null 2>&1 && gen="-G Ninja"
# The generator can only be chosen when the directory is first configured.
[ -f "$dir/CMakeCache.txt" ] && gen=""
# shellcheck disable=SC2086
cmake -S "$here" -B "$dir" $gen "$@" >/dev/null
# shellcheck disable=SC2086
cmake --build "$dir" -j "$(nproc 2>/dev/null || echo 2)" $targets
