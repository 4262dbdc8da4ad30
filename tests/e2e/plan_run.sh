#!/bin/sh
# SPDX-License-Identifier: MIT
# plan_run.sh FBRLSIM WORKDIR INPUTS EXPECTED_LOG EXPECTED_OUT CMD [ARG...]
#
# Runs CMD (fbrlmon with a plan, or a C example) against a real fbrlsim process on a pty
# and checks it end to end:
#   - CMD exits with status 0;
#   - fbrlsim's command log (--log: every command line the emulator executed) equals
#     EXPECTED_LOG exactly;
#   - CMD's standard output equals EXPECTED_OUT ("-": not checked), leaving out the one line
#     "run time N s" of the plan's summary (wall-clock seconds, the only output that varies).
# Every ARG that is @PORT@ is replaced by the emulator's pty path. INPUTS is an fbrlsim
# --inputs file, or "-" for none. fbrlsim runs with --time-scale 600 (motions 600 times
# faster; the plans get the same factor through TIME-SCALE).
#
# PLAN_COLLAPSE_POLLS=1: runs of the same "TYPEI SIG(n)" line in the log count as one (a
# WAIT-INPUT that times out polls every 20 ms: how often depends on the machine's speed).
# FBRL_REGEN=1: write the log and output to EXPECTED_LOG / EXPECTED_OUT instead of comparing
# (after an intended change of the plan; review the diff before committing).
sim=$1 work=$2 inputs=$3 want_log=$4 want_out=$5
shift 5
[ $# -ge 1 ] || { echo "usage: plan_run.sh FBRLSIM WORKDIR INPUTS EXPECTED_LOG EXPECTED_OUT CMD [ARG...]"; exit 2; }
rm -rf "$work" && mkdir -p "$work" || exit 2

set -- "$@" @END@
if [ "$inputs" = - ]; then
    "$sim" --time-scale 600 --log "$work/sim.log" >"$work/sim.out" 2>"$work/sim.err" &
else
    "$sim" --time-scale 600 --log "$work/sim.log" --inputs "$inputs" >"$work/sim.out" 2>"$work/sim.err" &
fi
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
trap 'exit 1' INT TERM
i=0
while [ ! -s "$work/sim.out" ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 "$work/sim.out")
case $port in
/dev/*) ;;
*) echo "FAIL: fbrlsim printed no device path: $(cat "$work/sim.out" "$work/sim.err")"; exit 1 ;;
esac

# the command line, with @PORT@ replaced
while [ "$1" != @END@ ]; do
    a=$1
    shift
    [ "$a" = @PORT@ ] && a=$port
    set -- "$@" "$a"
done
shift

"$@" </dev/null >"$work/out.txt" 2>"$work/err.txt"
st=$?
kill $simpid 2>/dev/null
wait $simpid 2>/dev/null
trap - EXIT

fails=0
if [ $st != 0 ]; then
    echo "FAIL: $1 exited with status $st"
    echo "--- stderr:"; cat "$work/err.txt"
    fails=1
fi

# A run of W5 lines counts as one: the robot words read the velocity (W5) before a motion
# while the arm still moves (docs/robot.md "Stopping safely"), as often as timing has it.
if [ "${PLAN_COLLAPSE_POLLS:-0}" = 1 ]; then
    awk '!((/^TYPEI SIG\(/ || /^W5$/) && $0 == prev) { print } { prev = $0 }' "$work/sim.log" >"$work/log.txt"
else
    awk '!(/^W5$/ && $0 == prev) { print } { prev = $0 }' "$work/sim.log" >"$work/log.txt"
fi
grep -v '^run time [0-9]* s$' "$work/out.txt" >"$work/out.cmp"

if [ "${FBRL_REGEN:-0}" = 1 ]; then
    [ $fails = 0 ] || { echo "not regenerated: the run failed"; exit 1; }
    cp "$work/log.txt" "$want_log"
    [ "$want_out" = - ] || cp "$work/out.cmp" "$want_out"
    echo "regenerated $want_log $([ "$want_out" = - ] || echo "$want_out")"
    exit 0
fi

# STATUS lines are compared apart from the rest: the link asks STATUS by itself when a
# prompt comes after its echo timeout (a busy host: the suite under ASan) to learn whether
# a line ran, so the plan's own STATUS lines (the connect's) are counted at least
grep -v '^STATUS$' "$want_log" >"$work/want.cmds"
grep -v '^STATUS$' "$work/log.txt" >"$work/log.cmds"
if ! cmp -s "$work/want.cmds" "$work/log.cmds" ||
    [ "$(grep -c '^STATUS$' "$work/log.txt")" -lt "$(grep -c '^STATUS$' "$want_log")" ]; then
    echo "FAIL: fbrlsim's command log differs from $want_log (expected, got):"
    diff "$want_log" "$work/log.txt" | head -40
    fails=1
fi
if [ "$want_out" != - ] && ! cmp -s "$want_out" "$work/out.cmp"; then
    echo "FAIL: the output differs from $want_out (expected, got):"
    diff "$want_out" "$work/out.cmp" | head -40
    fails=1
fi
[ $fails = 0 ] && echo "ok: $(wc -l <"$work/log.txt") commands as expected, status 0"
exit $fails
