#!/bin/sh
# SPDX-License-Identifier: MIT
# mon_tasks.sh FBRLMON FBRLSIM WORKDIR
#
# Tasks at fbrlmon's prompt (docs/tasks.md), on a real terminal (tmux) against a real
# fbrlsim process (--log):
#   - a task started at the prompt goes on running while the prompt waits for keys: its
#     output pulses reach the controller's log while nobody types, and the prompt answers
#     meanwhile;
#   - TASKS lists it with its state; STOP ends it, and its pulses stop too;
#   - STOP in the middle of a pulse: the output is switched off before the task ends.
mon=$1 sim=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=mon-tasks
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 100 -y 30 "'$mon' --port '$work/robot'; sleep 600"
wait_for "ok>" || exit 1

type_line "5 OUTPUT-DEVICE VALVE  TASK TICKER  VARIABLE TICKS"
type_line ": TICK ( -- ) BEGIN 200 EVERY  20 VALVE PULSE  1 TICKS +! AGAIN ; DECIMAL"
type_line "' TICK TICKER START"
sleep 1.5 # nobody types: the prompt waits for a key, the task runs
n=$(logged "OUTPUT 5")
[ "$n" -ge 4 ] || fail "the task pulsed $n times in 1.5 s at the idle prompt (4 or more expected)"
type_line "TICKS @ ."
type_line "TASKS"
[ "$(count 'TICKER           waiting')" -ge 1 ] || fail "TASKS does not show TICKER waiting"
type_line "TICKER STOP  TICKER TASK-STATE ."
[ "$(count ' 7 ')" -ge 1 ] || [ "$(screen | grep -c '^7 \| 7 *$')" -ge 1 ] || fail "TICKER not stopped"
n1=$(logged "OUTPUT 5")
sleep 0.6
n2=$(logged "OUTPUT 5")
[ "$n1" = "$n2" ] || fail "pulses went on after STOP ($n1 then $n2)"
[ "$(logged 'OUTPUT 5')" = "$(logged 'OUTPUT -5')" ] || fail "a pulse was left on"
# STOP in the middle of a pulse: the task's PULSE switches its output off before it ends
type_line "6 OUTPUT-DEVICE PUMP  TASK HOLDER  : HOLD ( -- ) BEGIN 2000 PUMP PULSE AGAIN ; DECIMAL"
type_line "' HOLD HOLDER START"
sleep 0.5 # inside the first 2 s pulse
type_line "HOLDER STOP"
[ "$(logged 'OUTPUT 6')" -ge 1 ] || fail "the long pulse never started"
[ "$(logged 'OUTPUT 6')" = "$(logged 'OUTPUT -6')" ] || fail "STOP in a pulse left its output on"
[ $fails = 0 ] || { screen; exit 1; }
echo "mon_tasks: $n pulses in 1.5 s at the idle prompt; STOP ended them"
