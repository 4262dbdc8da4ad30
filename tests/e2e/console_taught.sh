#!/bin/sh
# SPDX-License-Identifier: MIT
# console_taught.sh FBRLMON FBRLSIM WORKDIR SRCDIR
#
# Issue 27, item 2: taught data is never lost silently. On an 80x24 tmux terminal against
# a real fbrlsim, checked against the workspace file:
#   1. lab.ws holds PIN-1 as taught (X 9.8, not the method file's 9.5). The console starts
#      with --workspace lab.ws and opens SAMPLE-PREP, whose cell file says
#      `CREATE-LOC PIN-1 9.5E0 ... DEFINE-LOC`: the taught PIN-1 is kept (said under
#      Messages), the work cell shows it, and the exit prompt lists what a save adds
#      (the method file's other places) and does not touch PIN-1; Enter saves: PIN-1 in
#      the file is still the taught one.
#   2. A place taught in the console's work cell (TEACH, one jog) is kept when a method
#      that loads the same cell file is opened after it.
#   3. A taught value changed at the Forth line: the exit prompt names the change (now and
#      as taught) and defaults to keeping the file: Enter leaves lab.ws byte for byte.
mon=$1 sim=$2 work=$3 src=$4
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=taught
sim_scale=50
mkdir -p lib/methods && cp "$src"/examples/methods/*.fbrl lib/methods/ &&
    cp "$src/examples/asps_cell.fbrl" "$src/examples/asps_cell_objects.fbrl" lib/ || exit 1
# a second method on the same cell file (opened after the first: the file loads again)
cat >lib/methods/look.fbrl <<'EOF2'
INCLUDE ../asps_cell.fbrl
: LOOK ( -- ) ;
METHOD LOOK-AROUND  loads the cell file again
' LOOK STEP Look  nothing
END-METHOD
EOF2
. "$here/tmux_session.sh"
key() { tmux -L "$sock" send-keys -t said "$@"; }
# PIN-1 as taught on the lab's block: X 9.8 Y -2.4 (the file says 9.5 -2.5)
"$mon" --port "$work/robot" -e 'CREATE-LOC PIN-1 9.8E0 -2.4E0 2.5E0 0E0 -90E0 0E0 PIN-1 DEFINE-LOC' \
    -e 'SAVE-WORKSPACE lab.ws' </dev/null >ws.out 2>&1 || { fail "making lab.ws: $(cat ws.out)"; exit 1; }
# what the workspace file says about a place: "x y" (a session of its own, offline)
pin() {
    "$mon" --offline --workspace lab.ws -e "$1 GETX F. $1 GETY F." </dev/null 2>&1 | tail -n 1 | tr -s ' ' | sed 's/ $//'
}
[ "$(pin PIN-1)" = "9.8 -2.4" ] || fail "lab.ws does not hold the taught PIN-1: $(pin PIN-1)"

# run CMD in the session's pane (the first time a new session; then the pane restarted with
# its history cleared, so the server stays up)
run_in_pane() {
    if tmux -L "$sock" has-session -t said 2>/dev/null; then
        tmux -L "$sock" respawn-pane -k -t said "clear; $1"
        k=0 # until the last session's words are off the screen
        while pane | grep -q "fbrlmon-exit=" && [ $k -lt 50 ]; do sleep 0.1; k=$((k + 1)); done
        tmux -L "$sock" clear-history -t said
    else
        tmux -L "$sock" new-session -d -s said -x 80 -y 24 "$1"
    fi
}
start_console() {
    run_in_pane "'$mon' --port '$work/robot' --console --level developer --methods '$work/lib/methods' \
        --workspace lab.ws --operator tester -e '60 CONSTANT TIME-SCALE'; echo fbrlmon-exit=\$?; sleep 600"
}

# ---- 1. the workspace's taught PIN-1 against the method file's
start_console
wait_for "SAMPLE-PREP      ASPS sample preparation" || exit 1
key Down
key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
wait_for "kept taught PIN-1 X9.80 Y-2.40 Z2.50 (file: X9.50 Y-2.50 Z2.50)"
wait_for "1 taught place kept over the method file's"
key F6
wait_for "Work cell:"
pane | grep -q "^ PIN-1  *place X   9.80 Y  -2.40 Z   2.50" || fail "the work cell does not show the taught PIN-1"
key Escape
key F10
wait_for "Saving it to lab.ws would:"
screen >prompt1.txt
grep -q "add    A1 a location: X 10.000 Y -2.000 Z 3.000" prompt1.txt || fail "the prompt does not list the new A1"
grep -q "PIN-1" prompt1.txt && fail "the prompt lists PIN-1, which a save would not change: $(grep PIN-1 prompt1.txt)"
grep -q "Save it to lab.ws? \[Y/n\]" prompt1.txt || fail "adding only: the default is not yes"
key Enter
wait_for "fbrlmon-exit=0"
wait_for "saved "
[ "$(pin PIN-1)" = "9.8 -2.4" ] || fail "PIN-1 in lab.ws is not the taught one: $(pin PIN-1)"
[ "$(pin A1)" = "10. -2." ] || fail "A1 was not saved: $(pin A1)"

# ---- 2. taught in the work cell, then a method that loads the cell file again
start_console
wait_for "SAMPLE-PREP      ASPS sample preparation" || exit 1
key Down
key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
key F6
wait_for "Work cell:"
# SPOT: its row (the list starts on the screen's third line), then TEACH with one jog of +0.1 in X
row=$(pane | grep -n "^ SPOT  *place" | cut -d: -f1)
[ -n "$row" ] || { fail "no SPOT in the work cell"; exit 1; }
i=3
while [ $i -lt "$row" ]; do key Down; i=$((i + 1)); done
key t
teach_jog
wait_for "TEACH SPOT done"
spot=$(pane | sed -n 's/^ SPOT  *place X *\([-0-9.]*\) Y *\([-0-9.]*\) .*/\1 \2/p')
[ -n "$spot" ] || fail "SPOT is not shown after TEACH"
key Escape
key F2
wait_for "LOOK-AROUND"
key Up
key Enter
wait_for "Parameters of LOOK-AROUND" || exit 1
wait_for "kept taught SPOT X"
key F6
wait_for "Work cell:"
now=$(pane | sed -n 's/^ SPOT  *place X *\([-0-9.]*\) Y *\([-0-9.]*\) .*/\1 \2/p')
[ "$now" = "$spot" ] || fail "SPOT taught as $spot is $now after the method file loaded"
key Escape
key F10
wait_for "Save it to lab.ws?"
key Enter
wait_for "fbrlmon-exit=0"

# ---- 3. a taught value changed at the Forth line: named, and the default keeps the file
cp lab.ws lab.before
run_in_pane "'$mon' --port '$work/robot' --console --level programmer --methods '$work/lib/methods' \
    --workspace lab.ws; echo fbrlmon-exit=\$?; sleep 600"
wait_for "Method library" || exit 1
key F11
key -l "9.1E0 PIN-1 SETX"
key Enter
sleep 0.3
key Escape
key F10
wait_for "Save it to lab.ws?"
screen >prompt3.txt
grep -q "change PIN-1 a location: X 9.100 Y -2.400 Z 2.500 pitch -90.0 roll 0.0, was X 9.800 Y -2.400 Z 2.500 pitch -90.0 roll 0.0 (as taught)" prompt3.txt ||
    fail "the prompt does not show PIN-1's change: $(grep -i pin-1 prompt3.txt)"
grep -q "Save it to lab.ws? \[y/N\] (N keeps what was taught)" prompt3.txt || fail "the default is not to keep the file"
key Enter
wait_for "not saved: lab.ws is as it was"
wait_for "fbrlmon-exit=0"
cmp -s lab.ws lab.before || fail "lab.ws changed though the answer kept it"
[ "$(pin PIN-1)" = "9.8 -2.4" ] || fail "PIN-1 in lab.ws: $(pin PIN-1)"

[ $fails -eq 0 ] && echo "console_taught: all checks passed"
exit $((fails > 0))
