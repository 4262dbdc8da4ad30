#!/bin/sh
# SPDX-License-Identifier: MIT
# console_live.sh FBRLMON FBRLSIM WORKDIR
#
# The console's live arm panel (issue 16: "the arm's live position") on an 80x24 tmux
# terminal against fbrlsim in real time: during a long motion the panel shows readings
# taken while the arm moves (W2 in fbrlsim's log between the MOVE and the motion's end),
# away from both ends of the motion and near the box they span. The abort
# question stays on the screen while the motion's progress is shown, and a key other
# than y lets the method go on.
mon=$1 sim=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work/methods" || exit 1
cd "$work" || exit 1
name=console-live
sim_scale=1
# READY is X 12 Y 0 Z 20; FAR is X 4 Y 14 Z 6: at SPEED 20 a joint motion of some 6 s
cat >methods/far.fbrl <<'EOF2'
CREATE-LOC FAR  4.0 14.0 6.0 0.0 -90.0 0.0 FAR DEFINE-LOC
: GO ( -- ) HOME READY FINISH 20 SPEED FAR MOV FINISH 50 SPEED READY FINISH ;
METHOD FAR-AND-BACK  one long motion out and back
' GO STEP Go  out to FAR and back to READY
END-METHOD
EOF2
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 80 -y 24 \
    "'$mon' --port '$work/robot' --console --methods '$work/methods'; echo fbrlmon-exit=\$?; sleep 600"
key() { tmux -L "$sock" send-keys -t said "$@"; }
wait_for "FAR-AND-BACK" || exit 1
key Enter
wait_for "Parameters of FAR-AND-BACK" || exit 1
key F5
wait_long "RUNNING" 10 || exit 1
# the motion to FAR: readings on the way
wait_long "Arm (moving, at" 20 || exit 1
: >readings.txt
for i in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
    pane | sed -n 's/.*|  X *\([-0-9.]*\) Y *\([-0-9.]*\) Z *\([-0-9.]*\)$/\1 \2 \3/p' >>readings.txt
    sleep 0.2
done
# F8 while the motion's progress is shown: the question stays on the screen
key F8
sleep 1.5
pane >screen-question.txt
grep -q "Abort the run?  y or F8 Abort   any other key Go on" screen-question.txt ||
    fail "the abort question is not on the screen: $(tail -3 screen-question.txt)"
key n
wait_long "not aborted: the method goes on" 5
wait_long "DONE" 40 || exit 1
# the truth: fbrlsim's log has W2 readings while the arm moved to FAR
python3 - <<'PY' || fail "the live readings are not readings of the moving arm"
log = [l.strip() for l in open("sim.log") if not l.startswith("#")]
far = next(i for i, l in enumerate(log) if l.startswith("MOVE"))
end = next(i for i in range(far + 1, len(log)) if log[i].startswith("MOVE") or log[i] == "READY")
assert any(l == "W2" for l in log[far:end]), log[far:end]
pts = {tuple(map(float, l.split())) for l in open("readings.txt") if l.strip()}
start, stop = (12.0, 0.0, 20.0), (4.0, 14.0, 6.0)
far_from = lambda p, q: sum((a - b) ** 2 for a, b in zip(p, q)) ** 0.5 > 0.5
# a joint motion bulges off the straight line, never far outside the box of its ends
near_box = lambda p: all(min(a, b) - 3 < v < max(a, b) + 3 for v, a, b in zip(p, start, stop))
between = [p for p in pts if far_from(p, start) and far_from(p, stop)]
assert between, ("no reading on the way", pts)
assert all(near_box(p) for p in pts), ("a reading off the path", pts)
print("live readings on the way:", sorted(between))
PY
[ $fails -eq 0 ] && echo "console_live: all checks passed"
exit $((fails > 0))
