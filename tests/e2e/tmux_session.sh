# SPDX-License-Identifier: MIT
# tmux_session.sh - sourced by the e2e tests that drive fbrlmon on a real terminal: tmux
# gives it a pty of a chosen size (session "said" on a private server), fbrlsim (started
# here with --time-scale ${sim_scale:-20} and --log sim.log) is the controller on
# $work/robot ($sim_args: more fbrlsim options). Defines fail, screen, pane, wait_for, wait_long, type_line, count, logged, teach_jog; the caller sets
# $name (part of the tmux socket name) and starts the session.
sock=fbrl-$name-$$
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
simpid=
cleanup() { tmux -L "$sock" kill-server 2>/dev/null; [ -n "$simpid" ] && kill "$simpid" 2>/dev/null; }
trap cleanup EXIT
trap 'exit 1' INT TERM

"$sim" --time-scale "${sim_scale:-20}" ${sim_args:-} --log sim.log --link "$work/robot" >sim.out 2>sim.err &
simpid=$!
i=0
while [ ! -e robot ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done

screen() { tmux -L "$sock" capture-pane -p -J -S - -t said; }  # -J: wrapped lines joined
pane() { tmux -L "$sock" capture-pane -p -t said; }               # the visible screen only
# shown CAPTURE TEXT SECONDS: until CAPTURE (screen or pane) shows TEXT, at most SECONDS
shown() {
    k=0
    while ! "$1" | grep -qF -- "$2"; do
        k=$((k + 1))
        [ $k -lt $(($3 * 10)) ] || { fail "no '$2' on the screen in $3 s"; "$1"; return 1; }
        sleep 0.1
    done
}
# wait_for TEXT: until the screen (with its history) shows TEXT, at most 10 s
wait_for() { shown screen "$1" 10; }
# wait_long TEXT SECONDS: until the visible screen (no history) shows TEXT, at most SECONDS
wait_long() { shown pane "$1" "$2"; }
# type LINE: the line and Enter, then wait until a new prompt follows it
prompts() { screen | grep -c "^ok>"; }
type_line() {
    before=$(prompts)
    tmux -L "$sock" send-keys -t said -l -- "$1"
    tmux -L "$sock" send-keys -t said Enter
    k=0
    while [ "$(prompts)" -le "$before" ]; do
        k=$((k + 1))
        [ $k -lt 150 ] || { fail "no prompt after '$1'"; screen; return 1; }
        sleep 0.1
    done
}
count() { screen | grep -cF -- "$1"; }
logged() { grep -cxF -- "$1" sim.log; }
# teach_jog: in fbrlmon's TEACH pendant, one jog of +0.1 in X (Right) that fbrlsim's log
# shows, then Enter stores the arm's position into the place
teach_jog() {
    wait_for "TEACH keys" || return 1
    n=$(grep -c '^JOG 0.1,0,0$' sim.log)
    tmux -L "$sock" send-keys -t said Right
    k=0
    while [ "$(grep -c '^JOG 0.1,0,0$' sim.log)" = "$n" ] && [ $k -lt 100 ]; do sleep 0.1; k=$((k + 1)); done
    [ "$(grep -c '^JOG 0.1,0,0$' sim.log)" -gt "$n" ] || { fail "TEACH's jog never reached the controller"; return 1; }
    sleep 0.5
    tmux -L "$sock" send-keys -t said Enter
}
