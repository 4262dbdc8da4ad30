#!/bin/sh
# SPDX-License-Identifier: MIT
# Builds an optimised tree and runs every benchmark, printing their figures, then one
# summary table (issue 11: the link on fbrlsim's strict line, the POINT text, the next
# command after a wait, many robots, the Forth engine beside gforth-fast, gforth and
# pforth). Benchmarks never run inside the test suite: speed is reported, not asserted.
# The whole run takes about 4 minutes. Benches that print rows of the summary print
# them as lines starting with "| ".
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/deps.sh" gforth pforth
"$here/scripts/build.sh" "$here/build-bench" -DCMAKE_BUILD_TYPE=Release -DFBRL_TESTS=OFF >/dev/null
log=$(mktemp "${TMPDIR:-/tmp}/fbrlbench.XXXXXX")
trap 'rm -f "$log"' EXIT INT TERM
machine="$(nproc) cores, $(uname -m), $(uname -sr)"
echo "machine: $machine, load $(cut -d' ' -f1-3 /proc/loadavg)"
status=0
# bench args...: runs one bench from the build directory (benches that need fbrlsim
# find it at ./sim/fbrlsim), its output on the terminal and in the log
bench() {
    name=$1
    shift
    echo "== $name $*" | tee -a "$log"
    if ! (cd "$here/build-bench" && "./bench/$name" "$@") >"$log.one" 2>&1; then
        echo "$name failed" | tee -a "$log"
        status=1
    fi
    tee -a "$log" <"$log.one"
    rm -f "$log.one"
}
for b in "$here"/build-bench/bench/bench_*; do
    [ -x "$b" ] || continue
    name=$(basename "$b")
    case $name in
    bench_link_rate | bench_transport | bench_link_wait) ;; # below, with their summary rows
    *) bench "$name" ;;
    esac
done
bench bench_link_rate
bench bench_link_wait ./sim/fbrlsim 5
# POINT text, the event-driven host, 1/8/32 robots with fbrl_link_poll_many (3 s per figure)
bench bench_transport ./sim/fbrlsim 3 123n
forth=
if [ -x "$here/bench/run_forth.sh" ]; then
    echo "== Forth engine: start-up, peak memory and benchmarks (fbrlmon vs gforth-fast, gforth, pforth)" | tee -a "$log"
    forth=$("$here/bench/run_forth.sh" "$here/build-bench") || status=1
    printf '%s\n' "$forth" | tee -a "$log"
fi
# fbrl-station on loopback: property reads and observable commands, TLS or not, 4 arms (docs/sila.md)
if [ -x "$here/build-bench/apps/fbrl-station" ]; then
    echo "== fbrl-station (bench/station_bench.py)" | tee -a "$log"
    /usr/bin/python3 "$here/bench/station_bench.py" "$here/build-bench" >"$log.one" 2>&1 || status=1
    tee -a "$log" <"$log.one"
    rm -f "$log.one"
fi

echo
echo "== Summary, $(date -u '+%Y-%m-%d %H:%M UTC'), $machine, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| what | figure | share of the bound |"
echo "|---|---|---|"
grep '^| ' "$log" || true
# run_forth.sh's start-up lines ("  NAME  MS  MB (MIN-MAX)", or "  NAME  MS  -" without
# /usr/bin/time) and its geometric means
printf '%s\n' "$forth" | awk '
    /^start-up/ { s = 1; next }
    s && /^  system/ { next }
    s && /^  / { n = NF; k = ($n ~ /^\(/) ? 2 : 1; mb = (k == 2) ? $(n-1) " MB " $n : $n
                 name = $1; for (i = 2; i <= n - k - 1; i++) name = name " " $i
                 printf "| start-up and peak memory, empty program: %s | %s ms | %s |\n",
                        name, $(n-k), mb; next }
    s && !/^  / { s = 0 }
    /^benchmark/ { for (i = 1; i <= NF; i++) if ($i ~ /^\//) cols[++nc] = $i; next }
    /^geomean/ { for (i = 1; i <= nc; i++) printf "| Forth compute, geometric mean fbrlmon %s (bench/forth) | %s | below 1: fbrlmon faster |\n", cols[i], $(i + 1) }
'
printf '%s\n' "$forth" | grep -q pforth || echo "| pforth | not installed: skipped | |"
exit $status
