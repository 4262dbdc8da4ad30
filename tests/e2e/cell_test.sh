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
[ "$n" = 5 ] || fail "guard on: $n of 5 moves refused: $(cat "$work/on.out")"
# the log holds only the two moves to the start points (NEAR-NG, RIGHT): no motion of the four
moves=$(grep -cE '^(MOVE|APPRO|DEPART|JOG)' "$work/sim.log")
[ "$moves" = 2 ] || fail "guard on: $moves motions reached fbrlsim, want 2: $(grep -E '^(MOVE|POINT)' "$work/sim.log")"
grep -q '^POINT FBRLT.,8,-8,-0.5' "$work/sim.log" && fail "guard on: the point below the table was sent"
grep -q '^POINT FBRLT.,0,-16,4,' "$work/sim.log" && fail "guard on: the point past the rack was sent"
# the tool's end stays clear of the tall rack: the refusal names the forearm
"$mon" --port "$port" -e "INCLUDE $dir/cell.fbrl" "$dir/moves.fbrl" -e "HOME READY BEYOND MOV" >"$work/rack.out" 2>&1 &&
    fail "BEYOND MOV at the top level did not fail"
grep -q 'MOV: would hit TALL-RACK with the forearm at X .* Z 9.0000 in (.*% of the way); nothing was sent' \
    "$work/rack.out" || fail "the rack's refusal: $(cat "$work/rack.out")"

# guard off: fbrlsim stops each at the contact with 190
: >"$work/sim.log"
"$mon" --port "$port" -e "INCLUDE $dir/cell.fbrl CELL-GUARD-OFF" "$dir/moves.fbrl" >"$work/off.out" 2>"$work/off.err" || fail "guard off: fbrlmon failed: $(cat "$work/off.err")"
n=$(grep -c 'controller 190' "$work/off.out")
[ "$n" = 5 ] || fail "guard off: $n of 5 moves ended in 190-COLLISION: $(cat "$work/off.out")"
moves=$(grep -cE '^(MOVE|APPRO|DEPART|JOG)' "$work/sim.log")
[ "$moves" = 7 ] || fail "guard off: $moves motions sent, want 7"
# where each stopped (the line after it: "at X Y Z" of the tool point), the arm touching (a path is
# sampled at most 0.09 in, 0.9 FBRL_CELL_THIN, past the contact): the tool envelope (0.5 in past the tool
# point, 0.25 in thick) the table (z = 0.75) and the post's top edge (z 6 to 6.8); the wrist housing (the
# forearm's end, 1 in around the wrist centre 2 in above the tool point) the keep-out zone
# (y = 5 - 1) and the post's top edge (y = -1 - 1, z 6); the forearm the rack's top while the tool
# is past the rack (y < -13 - 0.25)
awk -v f="$work/off.check" '
  /^table:/ { w = "table"; next } /^box:/ { w = "box"; next } /^keep-out:/ { w = "keep"; next } /^arc:/ { w = "arc"; next }
  /^rack:/ { w = "rack"; next }
  /^at / { x = $2 + 0; y = $3 + 0; z = $4 + 0
    if (w == "table" && (z < 0.66 || z > 0.76)) print "table: stopped at z " z
    if (w == "keep" && (y < 3.99 || y > 4.09)) print "keep-out: stopped at y " y
    if (w == "arc" && (y < -2.01 || y > -1.91)) print "arc: stopped at y " y
    if (w == "box" && (x < 12.7 || x > 15.3 || z < 6.0 || z > 6.8)) print "box: stopped at " x " " z
    if (w == "rack" && !(y < -13.25 || z > 9.75)) print "rack: the tool stopped at y " y " z " z " (not past the rack)" }' "$work/off.out" >"$work/off.check"
[ -s "$work/off.check" ] && fail "guard off: wrong place: $(cat "$work/off.check")"

# a recalibrated block carries its box: clear before, refused after, nothing of it sent
: >"$work/sim.log"
"$mon" --port "$port" "$dir/block.fbrl" -e "CELL-SVG $work/block.svg" >"$work/block.out" 2>"$work/block.err" || fail "block: fbrlmon failed: $(cat "$work/block.err")"
grep -q '^as taught: moved$' "$work/block.out" || fail "block: the move beside the block as taught did not run: $(cat "$work/block.out")"
grep -q '^moved block: refused -302 $' "$work/block.out" || fail "block: the move into the moved block was not refused: $(cat "$work/block.out")"
grep -q '<title>HEATER</title>' "$work/block.svg" 2>/dev/null || fail "CELL-SVG at the prompt drew no HEATER"
n=$(grep -c '^POINT FBRLT.,12,3.5,1,' "$work/sim.log")
[ "$n" = 1 ] || fail "block: the location beside the block was sent $n times, want once (before the block moved)"

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
[ $fails = 0 ] && echo "cell guard: 5 refused before sending (one by the forearm), 5 stopped by fbrlsim at the contact, a moved block's box followed"
exit $fails
