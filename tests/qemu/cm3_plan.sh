#!/bin/sh
# SPDX-License-Identifier: MIT
# cm3_plan.sh QEMU IMAGE FBRLSIM FBRLMON EXAMPLES WORKDIR [SCALE]
#
# The sample-preparation plan on the Cortex-M3 firmware, checked against the same plan
# run by fbrlmon on the host. The plan (examples/sample_prep.fbrl with asps_cell.fbrl
# put in place of its INCLUDE, waits SCALE times shorter) is typed at the firmware's
# console (UART0, QEMU's stdio); UART1 is a real fbrlsim on a pty. Then fbrlmon runs
# the same text, typed on its standard input, against a fresh fbrlsim. The two
# emulators' command logs (every command the controller executed) must be identical,
# and neither run may report an error. The firmware then also checks its data files
# (cm3_files.fbrl) and Ctrl-C, and prints FW-STATS.
#
# Runs of the same W5 or "TYPEI SIG(n)" line count as one: a robot word reads the
# velocity while the arm moves and WAIT-INPUT polls its input, as often as timing has it.
qemu=$1 image=$2 sim=$3 mon=$4 examples=$5 work=$6 scale=${7:-600}
[ $# -ge 6 ] || { echo "usage: cm3_plan.sh QEMU IMAGE FBRLSIM FBRLMON EXAMPLES WORKDIR [SCALE]"; exit 2; }
rm -rf "$work" && mkdir -p "$work" || exit 2
. "$(dirname "$0")/cm3_lib.sh"
plan=$work/plan.fbrl
DEADLINE_S=60
DICT_MIN=16384 # the budget: a dictionary of at least 16 KB free for programs after boot

# the plan as one text: TIME-SCALE, the cell with its objects (the guard checks every motion
# on both sides, docs/workcell.md), the method, then BYE (the firmware resets; QEMU, run with
# -no-reboot, exits). The firmware also gets the data-file check (cm3_files.fbrl: its storage
# region) and FW-STATS before its BYE.
{
    echo "$scale CONSTANT TIME-SCALE"
    sed -e '/^INCLUDE asps_cell.fbrl/{r '"$examples"'/asps_cell.fbrl' -e 'd;}' "$examples/sample_prep.fbrl" |
        sed -e '/INCLUDE asps_cell_objects\.fbrl/{s/INCLUDE asps_cell_objects\.fbrl//' \
            -e 'r '"$examples"'/asps_cell_objects.fbrl' -e '}'
} >"$plan"
{
    cat "$plan" "$(dirname "$0")/cm3_files.fbrl"
    # Ctrl-C (0x03) stops a running word: an endless loop, and a 10-minute MS
    printf ': SPIN BEGIN AGAIN ;\nSPIN\n\003\n.( AFTER-SPIN) CR\n600000 MS\n\003\n.( AFTER-MS) CR\n'
    echo "FW-STATS"
    echo "BYE"
} >"$work/fw.fbrl"
echo "BYE" >>"$plan"

pids=""
cleanup() { for p in $pids; do kill "$p" 2>/dev/null; done; }
trap cleanup EXIT
trap 'exit 1' INT TERM

# start_sim NAME: fbrlsim on a pty with the plan's inputs; sets $port
start_sim() {
    "$sim" --time-scale "$scale" --log "$work/$1.log" --inputs "$examples/tube_present.inputs" \
        >"$work/$1.sim.out" 2>"$work/$1.sim.err" &
    simpid=$!
    pids="$pids $simpid"
    i=0
    while [ ! -s "$work/$1.sim.out" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    port=$(head -n 1 "$work/$1.sim.out")
    case $port in
    /dev/*) ;;
    *) echo "FAIL: fbrlsim printed no device path: $(cat "$work/$1.sim.out" "$work/$1.sim.err")"; exit 1 ;;
    esac
}

# (and STATUS, which a link asks by itself when a prompt comes after its echo timeout, on a
# busy host, to learn whether a line ran: not a line of the plan)
normalise() {
    grep -v '^STATUS$' "$1" | awk '!((/^TYPEI SIG\(/ || /^W5$/) && $0 == prev) { print } { prev = $0 }'
}

fails=0
t0=$(date +%s)

# 1. the firmware
start_sim fw
# -serial stdio is UART0 (the console), the second -serial UART1 (the controller)
run_fw "$qemu" "$image" "$port" "$work/fw.fbrl" "$work/fw.out" "$DEADLINE_S"
st=$?
kill $simpid 2>/dev/null
wait $simpid 2>/dev/null
t1=$(date +%s)
if [ $st != 0 ]; then
    echo "FAIL: QEMU exited with status $st (124: the plan did not end within ${DEADLINE_S} s)"
    tail -5 "$work/fw.out"
    fails=1
fi
# the console's own XON/XOFF bytes (its ring passing the marks) may fall inside a line
tr -d '\r\021\023' <"$work/fw.out" >"$work/fw.txt"
if grep -a '^error:' "$work/fw.txt" | grep -v 'user interrupt' >/dev/null; then
    echo "FAIL: the firmware reported errors:"
    grep -a '^error:' "$work/fw.txt" | head -10
    fails=1
fi
grep -a -q 'prepared 3 of 3 samples' "$work/fw.txt" || { echo "FAIL: the firmware's plan did not finish"; fails=1; }
dict=$(sed -n 's/^dictionary: \([0-9]*\) bytes free;.*/\1/p' "$work/fw.txt" | head -n 1)
if [ -z "$dict" ] || [ "$dict" -lt $DICT_MIN ]; then
    echo "FAIL: the dictionary has ${dict:-?} bytes free at boot, $DICT_MIN asked"
    fails=1
fi
for want in "FILE-CHECK 3 1234 0" "FOURTH -304" "REWRITE 0" "REREAD 6 1234 0" "error: user interrupt in SPIN" \
    "AFTER-SPIN" "error: user interrupt in MS" "AFTER-MS"; do
    grep -a -q "^$want *\$" "$work/fw.txt" || { echo "FAIL: data files: no \"$want\""; fails=1; }
done

# 2. the host: fbrlmon with the same text on its standard input
start_sim host
"$mon" --port "$port" <"$plan" >"$work/host.out" 2>"$work/host.err"
st=$?
kill $simpid 2>/dev/null
wait $simpid 2>/dev/null
if [ $st != 0 ]; then
    echo "FAIL: fbrlmon exited with status $st"
    head -10 "$work/host.err"
    fails=1
fi

normalise "$work/fw.log" >"$work/fw.cmp"
normalise "$work/host.log" >"$work/host.cmp"
n=$(wc -l <"$work/host.cmp")
if [ "$n" -lt 100 ]; then
    echo "FAIL: the host run sent only $n commands"
    fails=1
fi
if ! cmp -s "$work/host.cmp" "$work/fw.cmp"; then
    echo "FAIL: the command logs differ (host, firmware):"
    diff "$work/host.cmp" "$work/fw.cmp" | head -40
    fails=1
fi
[ $fails = 0 ] && echo "ok: $n commands, identical on the firmware and the host (firmware run $((t1 - t0)) s);" \
    "dictionary $dict bytes free at boot"
exit $fails
