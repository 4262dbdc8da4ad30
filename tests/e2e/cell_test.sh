#!/bin/sh
# SPDX-License-Identifier: MIT
# cell_test.sh FBRLMON FBRLSIM CELLDIR WORKDIR - see cell.cmake.
mon=$1 sim=$2 dir=$3 work=$4
rm -rf "$work" && mkdir -p "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

"$sim" --time-scale 50 --cell "$dir/cell.fbrl" --log "$work/sim.log" >"$work/sim.out" 2>"$work/sim.err" &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
i=0
while [ ! -s "$work/sim.out" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 "$work/sim.out")
case $port in /dev/*) ;; *) echo "FAIL: no fbrlsim: $(cat "$work/sim.err")"; exit 1 ;; esac

# guard on: every move refused, nothing of it sent
"$mon" --port "$port" -e "INCLUDE $dir/cell.fbrl" "$dir/moves.fbrl" >"$work/on.out" 2>"$work/on.err" || fail "guard on: fbrlmon failed: $(cat "$work/on.err")"
n=$(grep -c ': refused -302 ' "$work/on.out")
[ "$n" = 4 ] || fail "guard on: $n of 4 moves refused: $(cat "$work/on.out")"
# the log holds only the two moves to the start points (NEAR-NG, RIGHT): no motion of the four
moves=$(grep -cE '^(MOVE|APPRO|DEPART|JOG)' "$work/sim.log")
[ "$moves" = 2 ] || fail "guard on: $moves motions reached fbrlsim, want 2: $(grep -E '^(MOVE|POINT)' "$work/sim.log")"
grep -q '^POINT FBRLT.,8,-8,-0.5' "$work/sim.log" && fail "guard on: the point below the table was sent"

# guard off: fbrlsim stops each at the contact with 190
: >"$work/sim.log"
"$mon" --port "$port" -e "INCLUDE $dir/cell.fbrl CELL-GUARD-OFF" "$dir/moves.fbrl" >"$work/off.out" 2>"$work/off.err" || fail "guard off: fbrlmon failed: $(cat "$work/off.err")"
n=$(grep -c 'controller 190' "$work/off.out")
[ "$n" = 4 ] || fail "guard off: $n of 4 moves ended in 190-COLLISION: $(cat "$work/off.out")"
moves=$(grep -cE '^(MOVE|APPRO|DEPART|JOG)' "$work/sim.log")
[ "$moves" = 6 ] || fail "guard off: $moves motions sent, want 6"
# where each stopped (the line after it: "at X Y Z"): the envelope (0.5 in past the tool point,
# 0.25 in thick) touching (a path is sampled at most FBRL_CELL_THIN / 2 past the contact): the table (z = 0.75), the keep-out zone (y = 5 - 0.25), the post (y = -1 - 0.25)
awk -v f="$work/off.check" '
  /^table:/ { w = "table"; next } /^box:/ { w = "box"; next } /^keep-out:/ { w = "keep"; next } /^arc:/ { w = "arc"; next }
  /^at / { x = $2 + 0; y = $3 + 0; z = $4 + 0
    if (w == "table" && (z < 0.70 || z > 0.80)) print "table: stopped at z " z
    if (w == "keep" && (y < 4.70 || y > 4.80)) print "keep-out: stopped at y " y
    if (w == "arc" && (y < -1.26 || y > -1.15)) print "arc: stopped at y " y
    if (w == "box" && (x < 12.7 || x > 15.3 || z < 6.0 || z > 6.8)) print "box: stopped at " x " " z }' "$work/off.out" >"$work/off.check"
[ -s "$work/off.check" ] && fail "guard off: wrong place: $(cat "$work/off.check")"

# a recalibrated block carries its box: clear before, refused after, nothing of it sent
: >"$work/sim.log"
"$mon" --port "$port" "$dir/block.fbrl" -e "CELL-SVG $work/block.svg" >"$work/block.out" 2>"$work/block.err" || fail "block: fbrlmon failed: $(cat "$work/block.err")"
grep -q '^as taught: moved$' "$work/block.out" || fail "block: the move beside the block as taught did not run: $(cat "$work/block.out")"
grep -q '^moved block: refused -302 $' "$work/block.out" || fail "block: the move into the moved block was not refused: $(cat "$work/block.out")"
grep -q '<title>HEATER</title>' "$work/block.svg" 2>/dev/null || fail "CELL-SVG at the prompt drew no HEATER"
n=$(grep -c '^POINT FBRLT.,12,3.5,1,' "$work/sim.log")
[ "$n" = 1 ] || fail "block: the location beside the block was sent $n times, want once (before the block moved)"

# a 6-axis arm: the guard knows the A255's kinematics only and says so instead of guessing
"$mon" --sim --sim-model a465 -e "0E0 CELL-TABLE HOME READY" >"$work/a465.out" 2>&1 && fail "a465: READY went unchecked"
grep -q 'READY: the guard knows 5-axis arms (A255); this arm has 6 axes' "$work/a465.out" || fail "a465: $(cat "$work/a465.out")"

# fbrlsim refuses a bad description, naming the line
printf '0E0 CELL-TABLE\n0 0 0 1 1 1 CELL-BOX A\n0 0 0 1 1 1 CELL-BOX a\n' >"$work/bad1.fbrl"
printf '0E0 CELL-TABLE\n0 0 0 -1 1 1 CELL-BOX A\n' >"$work/bad2.fbrl"
printf '0E0 CELL-TABLE\nCREATE-LOC P\n' >"$work/bad3.fbrl"
for b in "bad1:3: CELL-BOX: a name used twice" "bad2:2: CELL-BOX: a size that is not positive" "bad3:2: CREATE-LOC is not a work-cell word"; do
    f=${b%%:*} want=${b#*:}
    "$sim" --cell "$work/$f.fbrl" >"$work/$f.out" 2>&1 && fail "fbrlsim took $f.fbrl"
    grep -qF "$f.fbrl:$want" "$work/$f.out" || fail "fbrlsim on $f.fbrl: $(cat "$work/$f.out"), want $want"
done

kill $simpid 2>/dev/null
wait $simpid 2>/dev/null
trap - EXIT
[ $fails = 0 ] && echo "cell guard: 4 refused before sending, 4 stopped by fbrlsim at the contact, a moved block's box followed"
exit $fails
