#!/bin/sh
# SPDX-License-Identifier: MIT
# console_library.sh FBRLMON FBRLSIM WORKDIR SRCDIR
#
# Issue 28, item 3, on an 80x24 tmux terminal against a real fbrlsim:
#   1. a method library holding a *.fbrl that is a symlink to /dev/zero, one that is a FIFO
#      and one of 8 MB whose METHOD line comes after the head the console reads: the console
#      shows its screen within a second, lists the real method, and says what it left out;
#   2. a run log that cannot be written (--run-log /dev/full, no file an audit chain can be
#      kept in): the run is refused, the error is on the operator's screen with the reason,
#      and fbrlmon's exit status is 1.
mon=$1 sim=$2 work=$3 src=$4
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work/lib/methods" || exit 1
cd "$work" || exit 1
name=library
cp "$src/examples/methods/sample_prep.fbrl" lib/methods/ &&
    cp "$src/examples/asps_cell.fbrl" "$src/examples/asps_cell_objects.fbrl" lib/ || exit 1
ln -s /dev/zero lib/methods/zero.fbrl
mkfifo lib/methods/fifo.fbrl || exit 1
# a big regular file: its METHOD line lies past the head a library scan reads
{ head -c 8388608 /dev/zero | tr '\0' ' '; printf '\nMETHOD TOO-DEEP  never seen\n'; } >lib/methods/big.fbrl
. "$here/tmux_session.sh"
start=$(date +%s%N)
tmux -L "$sock" new-session -d -s said -x 80 -y 24 \
    "'$mon' --port '$work/robot' --console --methods '$work/lib/methods' --run-log /dev/full; \
     echo fbrlmon-exit=\$?; sleep 600"
key() { tmux -L "$sock" send-keys -t said "$@"; }
# ---- 1. the screen within a second; the odd entries left out, said
shown pane "SAMPLE-PREP      ASPS sample preparation" 1 || {
    shown pane "SAMPLE-PREP      ASPS sample preparation" 20 # (how long it took, then)
    echo "the screen came after $((($(date +%s%N) - start) / 1000000)) ms"
    exit 1
}
echo "the library screen after $((($(date +%s%N) - start) / 1000000)) ms"
pane | grep -Eq "left out (zero|fifo)\.fbrl and others: not a regular file" || fail "the left-out entries are not told"
pane | grep -q "TOO-DEEP" && fail "a METHOD line past the head was read"
# ---- 2. the run log cannot be written: the run does not start, the operator is told why
key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
before=$(grep -vc '^#' sim.log)
key F5
wait_long "/dev/full: the audit trail cannot be opened: not a regular file" 10
wait_long "the run did not start: see the errors" 5
wait_long "Parameters of SAMPLE-PREP" 5
pane >screen-full.txt
sleep 0.5
[ "$(grep -vc '^#' sim.log)" -le $((before + 1)) ] || fail "the run went on without its log: $(tail -3 sim.log)"
key F10
wait_for "fbrlmon-exit=1"
[ $fails -eq 0 ] && echo "console_library: all checks passed"
exit $((fails > 0))
