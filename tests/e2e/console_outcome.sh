#!/bin/sh
# SPDX-License-Identifier: MIT
# console_outcome.sh FBRLMON FBRLSIM WORKDIR SRCDIR
#
# Issue 27, item 1, the console's end screen: the sample-prep method, 2 samples, on fbrlsim
# with no tube ever on the separation unit. The end screen says FAILED, 0 of 2 samples
# succeeded, each sample's outcome and why, as the run log's summary does; a per-sample
# step's progress counts the samples done, not the one started.
mon=$1 sim=$2 work=$3 src=$4
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "SKIP: no python3"; exit 77; }
rm -rf "$work" && mkdir -p "$work/lib/methods" || exit 1
cd "$work" || exit 1
name=outcome
sim_scale=50
cp "$src/examples/methods/sample_prep.fbrl" lib/methods/ &&
    cp "$src/examples/asps_cell.fbrl" "$src/examples/asps_cell_objects.fbrl" lib/ || exit 1
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 80 -y 24 \
    "'$mon' --port '$work/robot' --console --methods '$work/lib/methods' --run-log '$work/run.jsonl' \
     --operator ann -e '60 CONSTANT TIME-SCALE'; echo fbrlmon-exit=\$?; sleep 600"
key() { tmux -L "$sock" send-keys -t said "$@"; }
wait_for "SAMPLE-PREP      ASPS sample preparation" || exit 1
key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
key -l 2; key Down Down Down; key -l 1
wait_for "REACTION-MIN   [1 "
key F5
wait_long "RUNNING" 10 || exit 1
# the buffer step's progress while it works on its first sample: 0 done
wait_long "->  2 Buffer         sample 0/2" 20 || exit 1
wait_long "FAILED" 60 || exit 1
wait_long "SAMPLE-PREP failed: 0 of 2 samples succeeded (2 failed, 0 skipped)" 5
pane >screen-end.txt
grep -q "samples 2/2 done: 1 FAILED 2 FAILED" screen-end.txt || fail "the samples' outcomes are not on the end screen"
grep -q "sample 1 failed: its tube never reached the separation unit's sensor" screen-end.txt ||
    fail "sample 1's reason is not on the end screen"
grep -q "sample 2 failed: its tube never reached the separation unit's sensor" screen-end.txt ||
    fail "sample 2's reason is not on the end screen"
grep -q "ok  5 Separation     sample 2/2" screen-end.txt || fail "the separation step's progress: $(grep Separation screen-end.txt)"
key F10
wait_for "fbrlmon-exit=0"
# the run log says the same, and the controller's log: no vacuum, no rinse
python3 - <<'PY' || fail "the run log does not say what the screen said"
import json
recs = [json.loads(l) for l in open("run.jsonl")]
s = [r for r in recs if r["type"] == "summary"][-1]
why = "its tube never reached the separation unit's sensor"
assert s["outcome"] == "failed", s
assert s["samples"] == [{"sample": 1, "outcome": "failed", "reason": why},
                        {"sample": 2, "outcome": "failed", "reason": why}], s
sim = [l.strip() for l in open("sim.log")]
assert "OUTPUT 5" not in sim and "OUTPUT 2" not in sim, "the vacuum or the wash pump ran"
PY
[ $fails -eq 0 ] && echo "console_outcome: all checks passed"
exit $((fails > 0))
