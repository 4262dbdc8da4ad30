#!/bin/sh
# SPDX-License-Identifier: MIT
# cell_a465.sh FBRLMON FBRLSIM EXAMPLES CELLDIR WORKDIR - see cell.cmake: the A465 (fbrlmon
# --arm a465) guarded end to end in the ASPS cell, against an fbrlsim --model a465 that
# knows the same cell (--cell) and logs every command with its result (--log-format stamped).
mon=$1 sim=$2 ex=$3 dir=$4 work=$5
rm -rf "$work" && mkdir -p "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
# the ASPS cell, and a rack 10 in tall the A465 reaches over (0, -17: the tool 2 in past it)
cell=$work/cell.fbrl
{ cat "$ex/asps_cell_objects.fbrl"; echo '-2E0 -15E0 0E0 2E0 -14E0 10E0 CELL-BOX TALL-RACK'; } >"$cell" || exit 2

"$sim" --model a465 --time-scale 50 --cell "$cell" --log "$work/sim.log" --log-format stamped \
    >"$work/sim.out" 2>"$work/sim.err" &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
i=0
while [ ! -s "$work/sim.out" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 "$work/sim.out")
case $port in /dev/*) ;; *) echo "FAIL: no fbrlsim: $(cat "$work/sim.err")"; exit 1 ;; esac
# the log's motions: "T RESULT MOVE ..." (and where each went: the POINT before it)
motions() { grep -E '^[0-9.]+ [0-9A-Z]+ (MOVE|APPRO|DEPART|JOG|MA|MI|READY)' "$1"; }

# guard on: the clear moves run, the move into the heating block is refused and nothing of
# it reaches the controller; the one position read (W2) is believed at once (the A465's
# position block checks itself: pulses, joints and world agree)
"$mon" --port "$port" --arm a465 -e "INCLUDE $cell" "$dir/a465.fbrl" >"$work/on.out" 2>"$work/on.err" ||
    fail "guard on: fbrlmon failed: $(cat "$work/on.err")"
printf 'clear: moved\ninto the block: refused -302  controller -1 \nclear again: moved\nover the rack: refused -302  controller -1 \n' >"$work/on.want"
cmp -s "$work/on.out" "$work/on.want" || fail "guard on: $(cat "$work/on.out")"
grep -q ' POINT FBRLT.,13.5,0,1,' "$work/sim.log" && fail "guard on: the point in the block was sent"
grep -q ' POINT FBRLT.,0,-17,5,' "$work/sim.log" && fail "guard on: the point past the rack was sent"
n=$(motions "$work/sim.log" | grep -c ' OK MOVE ')
[ "$n" = 2 ] || fail "guard on: $n clear moves ran, want 2: $(cat "$work/sim.log")"
motions "$work/sim.log" | grep -v ' OK ' && fail "guard on: a motion ended in an error"
n=$(grep -c ' W2$' "$work/sim.log")
[ "$n" = 1 ] || fail "guard on: $n position reads, want 1 (the A465's block checks itself)"
# the refusal names what and where, and no byte of the motion left
: >"$work/sim.log"
"$mon" --port "$port" --arm a465 -e "INCLUDE $cell" "$dir/a465.fbrl" -e "INTO MOV" >"$work/msg.out" 2>&1 &&
    fail "INTO MOV at the top level did not fail"
grep -q 'MOV: would hit HEATING-BLOCK-BODY with the tool at X .* in (.*% of the way); nothing was sent' "$work/msg.out" ||
    fail "the refusal: $(cat "$work/msg.out")"
n=$(grep -c ' POINT ' "$work/sim.log")
[ "$n" = 2 ] || fail "INTO MOV sent something: $n points defined, want the plan's 2"
: >"$work/sim.log"
"$mon" --port "$port" --arm a465 -e "INCLUDE $cell" "$dir/a465.fbrl" -e "BEYOND MOV" >"$work/rack.out" 2>&1 &&
    fail "BEYOND MOV at the top level did not fail"
grep -q 'MOV: would hit TALL-RACK with the forearm at X .* Z 10.0000 in (.*% of the way); nothing was sent' \
    "$work/rack.out" || fail "the rack's refusal: $(cat "$work/rack.out")"
n=$(grep -c ' POINT ' "$work/sim.log")
[ "$n" = 2 ] || fail "BEYOND MOV sent something: $n points defined, want the plan's 2"

# guard off: the host sends the move into the block, and fbrlsim stops the arm at the
# block with 190-COLLISION; the clear moves run as before
: >"$work/sim.log"
"$mon" --port "$port" --arm a465 -e "INCLUDE $cell CELL-GUARD-OFF" "$dir/a465.fbrl" >"$work/off.out" \
    2>"$work/off.err" || fail "guard off: fbrlmon failed: $(cat "$work/off.err")"
grep -q '^into the block: refused -[0-9]*  controller 190 $' "$work/off.out" &&
    grep -q '^over the rack: refused -[0-9]*  controller 190 $' "$work/off.out" ||
    fail "guard off: $(cat "$work/off.out")"
grep -q '^[0-9.]* OK POINT FBRLT.,13.5,0,1,' "$work/sim.log" || fail "guard off: the point in the block was not sent"
n=$(motions "$work/sim.log" | grep -c ' 190 MOVE ')
[ "$n" = 2 ] || fail "guard off: $n motions ended in 190, want 2: $(cat "$work/sim.log")"
grep -q '^[0-9.]* OK POINT FBRLT.,0,-17,5,' "$work/sim.log" || fail "guard off: the point past the rack was not sent"
n=$(motions "$work/sim.log" | grep -c ' OK MOVE ')
[ "$n" = 2 ] || fail "guard off: $n clear moves ran, want 2"

# a controller that is not the arm fbrlmon was told (--arm a255: 5 axes): the guard cannot
# read where the arm is (its 6-axis readout does not parse) and sends nothing
: >"$work/sim.log"
"$mon" --port "$port" --arm a255 -e "0E0 CELL-TABLE HOME READY" >"$work/wrong.out" 2>&1 &&
    fail "--arm a255 on an A465: READY went unchecked"
motions "$work/sim.log" | grep -q READY && fail "--arm a255 on an A465: READY was sent: $(cat "$work/wrong.out")"

# fbrlmon told of a 6-axis readout (--axes 6) but not of the arm (the A255 by default): the
# guard says which arm it computes instead of guessing
: >"$work/sim.log"
"$mon" --port "$port" --axes 6 -e "0E0 CELL-TABLE HOME READY" >"$work/axes.out" 2>&1 &&
    fail "--axes 6: READY went unchecked"
grep -q 'READY: the guard computes the A255 (5 axes); this controller reports 6' "$work/axes.out" ||
    fail "--axes 6: $(cat "$work/axes.out")"
motions "$work/sim.log" | grep -q READY && fail "--axes 6: READY was sent"

kill $simpid 2>/dev/null
wait $simpid 2>/dev/null
trap - EXIT
[ $fails = 0 ] && echo "cell_a465: the moves into the heating block and over the rack (the forearm) refused before a byte was sent, clear moves ran; unguarded, fbrlsim stopped both with 190"
exit $fails
