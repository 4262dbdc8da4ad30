#!/bin/sh
# SPDX-License-Identifier: MIT
# terminal_run.sh FBRLMON FBRLSIM WORKDIR
#
# fbrlmon started from a shell on a real terminal (tmux), as the user guide (section 7)
# types it: with a FILE and the output in a file it runs the file and ends, its exit status
# says how the run went, and the terminal is free again; it does not wait for a session
# nobody sees. With the output on the terminal the same command opens the session.
mon=$1 sim=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=terminal-run
. "$here/tmux_session.sh"
cat >method.fbrl <<'PLAN'
\ method.fbrl - two moves and a word
CREATE-LOC SPOT  14E0 2E0 8E0 0E0 -90E0 0E0 SPOT DEFINE-LOC
HOME READY SPOT MOV FINISH
.( method done) CR
PLAN
cat >broken.fbrl <<'PLAN'
\ broken.fbrl - an error on line 2
HOME 1 0 /
PLAN
tmux -L "$sock" new-session -d -s said -x 100 -y 30 "sh"
sleep 0.3
say() { tmux -L "$sock" send-keys -t said -l -- "$1"; tmux -L "$sock" send-keys -t said Enter; }

say "'$mon' --port '$work/robot' method.fbrl > run.log; echo \"ended \$?\""
shown pane "ended 0" 30 || fail "fbrlmon FILE > run.log did not end by itself at the terminal"
grep -qx "method done" run.log || fail "run.log lacks the method's output: $(cat run.log)"
grep -q "^MOVE " sim.log || fail "no MOVE reached the controller: $(cat sim.log)"

say "'$mon' --port '$work/robot' broken.fbrl > broken.log 2> broken.err; echo \"broken \$?\""
shown pane "broken 1" 30 || fail "a run that failed did not end with status 1"
grep -q "broken.fbrl:2: error: division by zero" broken.err || fail "the error is not named: $(cat broken.err)"

# the output on the terminal: the file runs, then the session (its prompt) as before
say "'$mon' --port '$work/robot' method.fbrl; echo \"after \$?\""
shown pane "ok>" 30 || fail "no session after the file with the output on the terminal"
say "BYE"
shown pane "after 0" 10 || fail "BYE did not end the session"

[ $fails = 0 ] && echo "terminal_run: ok" && exit 0
exit 1
