#!/bin/sh
# SPDX-License-Identifier: MIT
# Builds an optimised tree and runs every benchmark, printing their figures.
# Benchmarks never run inside the test suite: speed is reported, not asserted.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/deps.sh" gforth pforth
"$here/scripts/build.sh" "$here/build-bench" -DCMAKE_BUILD_TYPE=Release -DFBRL_TESTS=OFF >/dev/null
echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)"
status=0
for b in "$here"/build-bench/bench/bench_*; do
    [ -x "$b" ] || continue
    echo "== $(basename "$b")"
    # from the build directory: benches that need fbrlsim find it at ./sim/fbrlsim
    (cd "$here/build-bench" && "$b") || { echo "$(basename "$b") failed"; status=1; }
done
if [ -x "$here/bench/run_forth.sh" ]; then
    echo "== Forth engine: start-up, peak memory and benchmarks (fbrlmon vs gforth-fast, gforth, pforth)"
    "$here/bench/run_forth.sh" "$here/build-bench" || status=1
fi
exit $status
