#!/bin/sh
# SPDX-License-Identifier: MIT
# debug_tmux.sh FBRLMON FBRLSIM WORKDIR
#
# The debugger at a real terminal (tmux), where its failures were seen (issue 27 item 9):
#   - BREAK on a word made only of built-ins, then s: each built-in is a stop, the failing
#     one included, before the error;
#   - BREAK FILE:LINE on the line that fails stops there;
#   - after UNBREAK ALL, in the middle of a step, no colon word typed stops again;
#   - EDIT of a file that makes three tasks, six times: no "no room for another task".
mon=$1 sim=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=debug-tmux
. "$here/tmux_session.sh"
cp "$(cd "$(dirname "$0")" && pwd)/debug_built.fbrl" built.fbrl
tmux -L "$sock" new-session -d -s said -x 100 -y 40 "EDITOR=true VISUAL= '$mon' --port '$work/robot' built.fbrl; sleep 600"
wait_for "ok>" || exit 1
key() { tmux -L "$sock" send-keys -t said -l -- "$1"; tmux -L "$sock" send-keys -t said Enter; }
# at_stop TEXT: typed at a debug> prompt, then wait for the next debug> (Forth run at the stop)
at_stop() {
    n=$(count "debug>")
    key "$1"
    k=0
    while [ "$(count "debug>")" -le "$n" ]; do
        k=$((k + 1)); [ $k -lt 100 ] || { fail "no debug> after '$1'"; return 1; }; sleep 0.1
    done
}

# 1. steps over built-ins, up to the failing one
type_line "BREAK MATH"
key "MATH"
wait_for "debug>" || exit 1
for w in '6' '7 \*' '0' '/'; do
    key "s"
    k=0
    while ! screen | grep -q "^stop: $w, in MATH at built.fbrl:2"; do
        k=$((k + 1)); [ $k -lt 100 ] || { fail "no step stop at $w"; break; }; sleep 0.1
    done
done
key "s"
shown screen "division by zero in MATH" 10 || fail "MATH did not fail after the steps"

# 2. UNBREAK ALL in the middle of a step: nothing stops any more
type_line "BREAK SPLIT"
key "9 SPLIT"
wait_for "stop: SPLIT (built.fbrl:3)" || fail "no stop at SPLIT"
at_stop "s"
shown screen "stop: DUP, in SPLIT" 10 || fail "no step into SPLIT"
at_stop "UNBREAK ALL"
key "c"
shown screen "division by zero in SPLIT" 10 || fail "SPLIT did not run on to its error"
stops=$(count "debug>")
type_line ": AGAIN-1 ( -- n ) 41 1+ ; " # (tmux takes a last ";" for its own)
type_line "AGAIN-1 ."
type_line "9 SPLIT"
sleep 0.5
[ "$(count "debug>")" = "$stops" ] || fail "a word typed after UNBREAK ALL stopped: $(screen | tail -n 12)"
[ "$(count "42 ")" -ge 1 ] || fail "AGAIN-1 did not run"

# 3. a FILE:LINE breakpoint on the line that fails
type_line "BREAK built.fbrl:5"
key "7 SPLIT"
shown screen "stop: SWAP, in SPLIT at built.fbrl:5" 10 || fail "BREAK FILE:LINE did not stop on the failing line"
n=$(prompts)
key "q" # the debugger off: SPLIT runs on to its error and the prompt
k=0
while [ "$(prompts)" -le "$n" ]; do k=$((k + 1)); [ $k -lt 100 ] || { fail "no prompt after q"; break; }; sleep 0.1; done

# 4. EDIT reloads a file that makes three tasks: six times, no task leaks
i=0
while [ $i -lt 6 ]; do type_line "EDIT MATH"; i=$((i + 1)); done
[ "$(count "no room for another task")" = 0 ] || fail "EDIT leaked tasks: $(screen | grep -m 1 'no room')"
type_line "TASKS"
[ "$(screen | grep -c '^T[ABC]  ')" -ge 3 ] || fail "TASKS does not list TA TB TC"

[ $fails = 0 ] && echo "debug_tmux: ok" && exit 0
exit 1
