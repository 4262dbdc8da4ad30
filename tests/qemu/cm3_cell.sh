#!/bin/sh
# SPDX-License-Identifier: MIT
# cm3_cell.sh QEMU IMAGE FBRLSIM EXAMPLES WORKDIR
#
# The work cell's guard on the Cortex-M3 firmware. The ASPS cell (examples/
# asps_cell_objects.fbrl) is typed at the firmware's console (UART0, QEMU's stdio); UART1 is
# a real fbrlsim that knows the same cell (--cell) and logs every command with its result
# (--log-format stamped): the truth for what ran and what hit what. With the guard on, a move
# into the heating block is refused before a byte of it is sent and a clear move runs: the
# log holds the clear one only. With the guard off (CELL-GUARD-OFF) the firmware sends both
# and fbrlsim stops the first at the block with 190-COLLISION: the log can tell.
qemu=$1 image=$2 sim=$3 examples=$4 work=$5
[ $# -eq 5 ] || { echo "usage: cm3_cell.sh QEMU IMAGE FBRLSIM EXAMPLES WORKDIR"; exit 2; }
rm -rf "$work" && mkdir -p "$work" || exit 2
. "$(dirname "$0")/cm3_lib.sh"
DEADLINE_S=60
DICT_MIN=16384 # the budget: a dictionary of at least 16 KB free for programs after boot
cell=$examples/asps_cell_objects.fbrl

pids=""
cleanup() { for p in $pids; do kill "$p" 2>/dev/null; done; }
trap cleanup EXIT
trap 'exit 1' INT TERM
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# the text typed at the console: the cell, two moves from READY (into the heating block's
# body, 0.75 in deep, then 5 in over it), the refusal's message, the stack's high water
# typed NAME [GUARD-WORD]
typed() {
    {
        cat "$cell"
        echo "$2"
        echo "HOME READY"
        echo "CREATE-LOC INTO 11.5E0 0E0 1E0 0E0 -90E0 0E0 INTO DEFINE-LOC"
        echo "CREATE-LOC CLEAR 12E0 0E0 6E0 0E0 -90E0 0E0 CLEAR DEFINE-LOC"
        echo ': TRY ( xt a u -- ) TYPE ." : " CATCH ?DUP IF ." refused " . ." controller " RAPL-ERROR . ELSE ." moved" THEN CR ;'
        echo ':NONAME INTO MOV ; S" into the block" TRY'
        echo ':NONAME CLEAR MOV ; S" clear" TRY'
        echo "READY INTO MOV"
        echo "FW-STATS"
        echo "BYE"
    } >"$work/$1.fbrl"
}

# run NAME [GUARD-WORD]: the firmware against a fresh fbrlsim; its console in NAME.out, the
# emulator's log in NAME.log
run() {
    typed "$1" "$2"
    "$sim" --time-scale 50 --cell "$cell" --log "$work/$1.log" --log-format stamped >"$work/$1.sim.out" \
        2>"$work/$1.sim.err" &
    simpid=$!
    pids="$pids $simpid"
    i=0
    while [ ! -s "$work/$1.sim.out" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    port=$(head -n 1 "$work/$1.sim.out")
    case $port in
    /dev/*) ;;
    *) echo "FAIL: fbrlsim printed no device path: $(cat "$work/$1.sim.out" "$work/$1.sim.err")"; exit 1 ;;
    esac
    run_fw "$qemu" "$image" "$port" "$work/$1.fbrl" "$work/$1.out" "$DEADLINE_S"
    st=$?
    kill $simpid 2>/dev/null
    wait $simpid 2>/dev/null
    [ $st = 0 ] || fail "$1: QEMU exited with status $st (124: not done within ${DEADLINE_S} s)"
    tr -d '\r' <"$work/$1.out" >"$work/$1.txt"
}
# the motions in a stamped log: "T RESULT MOVE ..."
motions() { grep -E '^[0-9.]+ [0-9A-Z]+ (MOVE|APPRO|DEPART|JOG|MA|MI|READY)' "$1"; }

# 1. the guard on
run on
free=$(sed -n 's/^dictionary: \([0-9]*\) bytes free.*/\1/p' "$work/on.txt")
[ -n "$free" ] && [ "$free" -ge $DICT_MIN ] || fail "dictionary: '$free' bytes free after boot, $DICT_MIN asked"
grep -q '^into the block: refused -302 controller -1 $' "$work/on.txt" ||
    fail "guard on: the move into the block was not refused: $(grep -a 'into the block' "$work/on.txt")"
grep -q '^clear: moved$' "$work/on.txt" || fail "guard on: the clear move did not run: $(grep -a 'clear' "$work/on.txt")"
grep -q 'MOV: would hit HEATING-BLOCK-BODY with the tool at X .* in (.*% of the way); nothing was sent' \
    "$work/on.txt" || fail "guard on: no refusal naming the block at the top level"
grep -q ' POINT FBRLT.,11.5,0,1,' "$work/on.log" && fail "guard on: the point in the block was sent"
n=$(motions "$work/on.log" | grep -c ' MOVE ')
[ "$n" = 1 ] || fail "guard on: $n moves reached fbrlsim, want the clear one: $(motions "$work/on.log")"
motions "$work/on.log" | grep -q ' OK MOVE FBRLT.$' || fail "guard on: the clear move did not end OK"
motions "$work/on.log" | grep -v ' OK ' && fail "guard on: a motion ended in an error"
grep -a '^stack:' "$work/on.txt" | head -1

# 2. the guard off: the firmware sends the move into the block, fbrlsim stops it there
run off CELL-GUARD-OFF
grep -q '^into the block: refused -[0-9]* controller 190 $' "$work/off.txt" ||
    fail "guard off: $(grep -a 'into the block' "$work/off.txt")"
grep -q '^[0-9.]* OK POINT FBRLT.,11.5,0,1,' "$work/off.log" || fail "guard off: the point in the block was not sent"
n=$(motions "$work/off.log" | grep -c ' 190 MOVE ')
[ "$n" -ge 1 ] || fail "guard off: fbrlsim saw no collision: $(motions "$work/off.log")"

[ $fails = 0 ] && echo "cm3_cell: on the firmware the move into the heating block was refused before a byte was sent and the clear move ran (fbrlsim's log); unguarded, fbrlsim stopped it with 190"
exit $fails
