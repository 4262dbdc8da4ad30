#!/bin/sh
# SPDX-License-Identifier: MIT
# messages.sh FBRLMON FBRLSIM WORKDIR
#
# "Messages that tell the user what happened" (issue 10, item 3), in fbrlmon on an 80x24
# tmux terminal against a real fbrlsim process running in real time:
#   - a controller error comes with its meaning and what to do (029 = out of reach);
#   - a motion says what it started; FINISH shows that it waits, then how long it waited;
#   - a timed wait (WAIT-UNTIL) counts down the seconds left, and the countdown is erased;
#   - W2's WORLD numbers are labelled, follow METRIC-ON, and the yaw is the arm's own;
#   - with output to a file none of the progress or motion chatter appears.
mon=$1 sim=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=messages sim_scale=1
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 80 -y 24 "'$mon' --port '$work/robot'; sleep 600"
wait_for "ok>" || exit 1

# ---- a controller error with its meaning
type_line "HOME READY  CREATE-LOC FAR 40.0 0.0 3.0 0.0 -90.0 0.0 FAR DEFINE-LOC  FAR MOV"
wait_for "MOV: controller error 029-TRANSFORM ILLEGAL (the position is out of the arm's reach"

# ---- a motion says what it started; FINISH shows its wait, then how long it waited
# (10 %: a motion of about 8 s, so that the progress line, erased when the motion ends,
# stays on the screen for seconds even when the machine is loaded and tmux slow to show it)
type_line "10 SPEED  CREATE-LOC P 14.0 2.0 8.0 0.0 -90.0 0.0 P DEFINE-LOC"
tmux -L "$sock" send-keys -t said -l "P MOV FINISH"
tmux -L "$sock" send-keys -t said Enter
wait_for "MOV: the arm is moving to X +14.0000 Y +2.0000 Z +8.0000 in (MOVE FBRLT"
k=0  # the seconds it shows count up (2 s, 3 s, ...): any of them
until screen | grep -qE -- "FINISH: waiting for the arm, [2-9] s"; do
    k=$((k + 1))
    [ $k -lt 100 ] || { fail "no 'FINISH: waiting for the arm, N s' on the screen"; screen; break; }
    sleep 0.1
done
k=0
while [ "$(count 'FINISH: waited ')" = 0 ] && [ $k -lt 300 ]; do sleep 0.1; k=$((k + 1)); done
screen | grep -q '^FINISH: waited [0-9]*\.[0-9] s for the arm$' || { fail "FINISH does not say how long it waited"; screen; }
wait_for "ok>"
# the progress line was erased: it is not left on the screen
tmux -L "$sock" capture-pane -p -t said | grep -q 'waiting for the arm' && fail "FINISH's progress line was left on the screen"

# ---- a timed wait counts down, and the countdown goes away
tmux -L "$sock" send-keys -t said -l "START-TIMER 3500 WAIT-UNTIL  .( tim) .( er done)"
tmux -L "$sock" send-keys -t said Enter
wait_for "WAIT-UNTIL: 3 s left"
wait_for "WAIT-UNTIL: 1 s left"
wait_for "timer done"   # (the output: the typed line shows "tim) .( er done")
tmux -L "$sock" capture-pane -p -t said | grep -q 's left' && { fail "the countdown was left on the screen"; tmux -L "$sock" capture-pane -p -t said; }

# ---- W2: the WORLD numbers labelled, in inches and after METRIC-ON in centimetres
type_line "P MOV FINISH W2"
# yaw: a 5-axis arm points its waist at the place: atan2(2, 14)
yaw=$(awk 'BEGIN { printf "%+.3f", atan2(2, 14) * 45 / atan2(1, 1) }')
wait_for "world: X +14.0000 Y +2.0000 Z +8.0000 in  yaw $yaw (the arm's own)  pitch -90.000  roll +0.000 deg"
type_line "METRIC-ON W2 METRIC-OFF"
cm=$(awk 'BEGIN { printf "X %+.4f Y %+.4f Z %+.4f cm", 14 * 2.54, 2 * 2.54, 8 * 2.54 }')
wait_for "world: $cm  yaw $yaw (the arm's own)"

# ---- output to a file: no progress, no motion chatter, the error still explained
tmux -L "$sock" send-keys -t said -l "BYE"
tmux -L "$sock" send-keys -t said Enter
sleep 1
printf 'HOME 10 SPEED CREATE-LOC P 14.0 2.0 8.0 0.0 -90.0 0.0 P DEFINE-LOC P MOV FINISH\nSTART-TIMER 2500 WAIT-UNTIL\n' |
    "$mon" --port "$work/robot" >file.out 2>file.err || fail "piped run failed: $(cat file.err)"
grep -q 'waiting\|s left\|is moving\|waited' file.out && fail "progress or motion chatter in a file: $(cat file.out)"

[ $fails = 0 ] && echo "messages: error meaning, motion start and end, countdown, labelled W2 as they should"
exit $((fails != 0))
