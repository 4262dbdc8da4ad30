#!/bin/sh
# SPDX-License-Identifier: MIT
# said_once.sh FBRLMON FBRLSIM WORKDIR
#
# "Said once, where it should go" (issue 10, item 1), in fbrlmon on a real terminal: tmux
# gives it an 80x24 pty, and a real fbrlsim process (--log) is the controller.
#   - ROBOT-STATUS and RAPL TYPEV print their output once, and the controller's log shows
#     each sent once;
#   - HELP alone says how to use HELP;
#   - GET-STRING says that it cut a line longer than the string;
#   - PRINT-LOC on the controller's line says what the controller answered (050), and with
#     --printer PATH the location goes to PATH and nothing to the controller;
#   - TEACH shows a refused jog on an 80-column terminal when the status line is long;
#   - the greeting is broken between words to fit the 80 columns.
mon=$1 sim=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=said-once
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 80 -y 24 "'$mon' --port '$work/robot'; sleep 600"
wait_for "ok>" || exit 1

# ---- the greeting fits the 80 columns: broken between words, none cut by the terminal
greeting=$(tmux -L "$sock" capture-pane -p -t said | sed -n '1,/^ok>/p' | sed '$d')
echo "$greeting" | awk 'length($0) > 79 { bad = 1 } END { exit bad }' || fail "a greeting line is wider than 79: $greeting"
echo "$greeting" | tr '\n' ' ' | grep -q "low latency: not supported). HELP name, WORDS; BYE or Ctrl-D ends." ||
    fail "the greeting lost words: $greeting"

# ---- ROBOT-STATUS and RAPL TYPEV: printed once, sent once
before=$(logged STATUS) # the connect's (the controller's units)
type_line "ROBOT-STATUS"
[ "$(count 'RAPL-II Version')" = 1 ] || fail "ROBOT-STATUS printed its block $(count 'RAPL-II Version') times"
[ "$(($(logged STATUS) - before))" = 1 ] || fail "ROBOT-STATUS sent STATUS $(($(logged STATUS) - before)) times"
type_line "RAPL TYPEV 3.5"
[ "$(count '+3.500000')" = 1 ] || fail "RAPL TYPEV printed its value $(count '+3.500000') times"
[ "$(logged 'TYPEV 3.5')" = 1 ] || fail "RAPL TYPEV sent TYPEV $(logged 'TYPEV 3.5') times"

# ---- HELP alone
type_line "HELP"
[ "$(count 'HELP name shows what a word does')" = 1 ] || fail "HELP alone does not say how to use it"
[ "$(count 'zero-length')" = 0 ] || fail "HELP alone still speaks of a zero-length string"

# ---- GET-STRING cuts a long line and says so
tmux -L "$sock" send-keys -t said -l "5 STRING S  S GET-STRING  S TYPE-STRING"
tmux -L "$sock" send-keys -t said Enter
sleep 0.5
tmux -L "$sock" send-keys -t said -l "abcdefgh"
tmux -L "$sock" send-keys -t said Enter
wait_for "kept the first 5, dropped 3"
wait_for "abcde"

# ---- PRINT-LOC on the controller's line: the controller's answer is told
type_line "CREATE-LOC P -15.0 -12.0 6.0 0.0 -90.0 170.0 P DEFINE-LOC  P PRINT-LOC  RAPL-ERROR ."
wait_for "read it as a command and answered 050-AMBIGUOUS COMMAND"
wait_for "50 "
grep -q '^X  *-15.0000 Y' sim.log || fail "PRINT-LOC's line did not reach the controller"

# ---- TEACH: a refused jog is shown at 80 columns with a long status line
type_line "HOME READY  P MOV"
tmux -L "$sock" send-keys -t said -l "TEACH P"
tmux -L "$sock" send-keys -t said Enter
wait_for "X-15.000 Y-12.000 Z+6.000 in  pitch-90.0 roll+170.0"
tmux -L "$sock" send-keys -t said 4
wait_for "step 1 in 10 deg"
k=0
while [ $k -lt 8 ] && [ "$(count '! JOG: controller error 029-TRANSFORM ILLEGAL')" = 0 ]; do
    tmux -L "$sock" send-keys -t said Left   # outwards, until the arm cannot reach
    sleep 0.8
    k=$((k + 1))
done
[ "$(count '! JOG: controller error 029-TRANSFORM ILLEGAL')" = 1 ] || { fail "TEACH: the refused jog is not on the 80x24 screen"; screen; }
# the status line itself is never wrapped: whole on one screen row
tmux -L "$sock" capture-pane -p -t said | grep -qx "X-15.000 Y-12.000 Z+6.000 in  pitch-90.0 roll+170.0  step 1 in 10 deg *" ||
    { fail "TEACH: the status line is not whole on one row"; screen; }
tmux -L "$sock" send-keys -t said Escape
wait_for "cancelled"
tmux -L "$sock" send-keys -t said -l "BYE"   # frees the port (fbrlmon holds it exclusively)
tmux -L "$sock" send-keys -t said Enter
sleep 1

# ---- PRINT-LOC with --printer: to the file, nothing to the controller
before=$(wc -l <sim.log)
"$mon" --port "$work/robot" --printer "$work/printer.txt" \
    -e 'CREATE-LOC Q 1.0 2.0 3.0 0.0 -90.0 0.0 Q DEFINE-LOC Q PRINT-LOC BYE' </dev/null >out.txt 2>err.txt ||
    fail "--printer: fbrlmon failed: $(cat err.txt)"
grep -q '^X    +1.0000 Y    +2.0000 Z    +3.0000 in' printer.txt || fail "--printer: the file holds '$(cat printer.txt)'"
[ ! -s out.txt ] || fail "--printer: something on the console: $(cat out.txt)"
tail -n +"$((before + 1))" sim.log | grep -q '^X' && fail "--printer: the location went to the controller too"

[ $fails = 0 ] && echo "said once: status, TYPEV, HELP, GET-STRING, PRINT-LOC and TEACH's refused jog as they should"
exit $((fails != 0))
