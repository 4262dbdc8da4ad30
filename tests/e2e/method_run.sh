#!/bin/sh
# SPDX-License-Identifier: MIT
# method_run.sh FBRLMON FBRLSIM WORKDIR SRCDIR
#
# Issue 27, item 1: a run's outcome tells the truth. The sample-prep method
# (examples/methods/sample_prep.fbrl) run by fbrlmon against a real fbrlsim, 2 samples:
#   - no tube ever on the separation unit: outcome failed, both samples failed with the
#     reason, exit status 4 (from a file and -e text, and from a pipe);
#   - a tube there (examples/tube_present.inputs): completed, exit status 0;
#   - the tube there for the first sample only (fbrlsim's control FIFO takes it away once
#     the first sample's vacuum pulse ended): partial, exit status 4.
# Each is checked against fbrlsim's command log (the vacuum valve opened once per sample
# that succeeded; the run log's commands are exactly the log's lines) and the run log file
# (its summary's samples, the human summary). Then the dry run of the same method: every
# WAIT-INPUT time-out listed with its step and sample, each sample's predicted outcome.
mon=$1 sim=$2 work=$3 src=$4
method=$src/examples/methods/sample_prep.fbrl
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
simpid=
trap '[ -n "$simpid" ] && kill $simpid 2>/dev/null' EXIT
trap 'exit 1' INT TERM
RUN='2 PARAM! #SAMPLES  1 PARAM! REACTION-MIN  SAMPLE-PREP RUN-METHOD'

# start_sim DIR SCALE [fbrlsim options]: fbrlsim on DIR/robot, its log DIR/sim.log
start_sim() {
    d=$1 scale=$2
    shift 2
    mkdir -p "$d"
    "$sim" --time-scale "$scale" --log "$d/sim.log" --link "$d/robot" "$@" >"$d/sim.out" 2>"$d/sim.err" &
    simpid=$!
    i=0
    while [ ! -e "$d/robot" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    [ -e "$d/robot" ] || { fail "fbrlsim did not start: $(cat "$d/sim.err")"; exit 1; }
}
stop_sim() { kill $simpid 2>/dev/null; wait $simpid 2>/dev/null; simpid=; }

# check DIR OUTCOME SAMPLE-OUTCOMES...: the run log and fbrlsim's log agree with the outcome
check() {
    python3 - "$@" <<'PY' || fail "$1: the run log or fbrlsim's log does not tell the outcome"
import json, sys
d, outcome, want = sys.argv[1], sys.argv[2], sys.argv[3:]
recs = [json.loads(l) for l in open(d + "/run.jsonl")]
sim = [l.rstrip("\n") for l in open(d + "/sim.log") if not l.startswith("#")]
summary = [r for r in recs if r["type"] == "summary"]
assert len(summary) == 1 and summary[0]["outcome"] == outcome, (summary, outcome)
got = [(s["sample"], s["outcome"]) for s in summary[0]["samples"]]
assert got == [(i + 1, o) for i, o in enumerate(want)], got
why = "its tube never reached the separation unit's sensor"
for s in summary[0]["samples"]:
    assert s["reason"] == (why if s["outcome"] == "failed" else ""), s
# the sample records as they came (a failed sample before one that succeeded later), the same
assert sorted((r["sample"], r["outcome"]) for r in recs if r["type"] == "sample") == got, recs
# the truth: the separation unit's vacuum valve (output 5) opened once per sample that
# succeeded, and every command the controller executed after the connect (NOHELP and the
# STATUS that reads the units, docs/link.md 1) is in the run log
assert sim.count("OUTPUT 5") == want.count("succeeded"), sim.count("OUTPUT 5")
cmds = [r["line"] for r in recs if r["type"] == "command" for _ in range(r.get("count", 1))]
assert sim[:2] == ["NOHELP", "STATUS"] and cmds == sim[2:], (len(cmds), len(sim))
assert any(r.get("count", 1) > 1 for r in recs if r["type"] == "command"), "no poll folded"
texts = [r["text"] for r in recs if r["type"] == "text"]
ok, failed = want.count("succeeded"), want.count("failed")
assert texts[0].startswith("SAMPLE-PREP: %s after " % outcome), texts
assert texts[1] == "2 samples: %d succeeded, %d failed, 0 skipped" % (ok, failed), texts
assert texts[2:2 + failed] == ["sample %d failed: %s" % (i + 1, why) for i, o in enumerate(want) if o == "failed"], texts
print("%s: %s %s, %d commands = fbrlsim's log" % (d, outcome, want, len(cmds)))
PY
}

# ---- no tube: failed, both samples failed, exit 4 (a file and -e text)
start_sim notube 100
(cd notube && "$mon" --port "$work/notube/robot" --run-log run.jsonl -e '100 CONSTANT TIME-SCALE' "$method" \
    -e "$RUN" </dev/null >out.txt 2>err.txt)
st=$?
stop_sim
[ $st = 4 ] || fail "no tube: exit status $st, want 4: $(cat notube/err.txt)"
grep -q "^prepared 0 of 2 samples" notube/out.txt || fail "no tube: the method's own summary: $(cat notube/out.txt)"
grep -q "SAMPLE-PREP: failed: 0 of 2 samples succeeded" notube/err.txt || fail "no tube: fbrlmon said: $(cat notube/err.txt)"
check notube failed failed failed

# ---- the same from a pipe: exit 4
start_sim pipe 100
(cd pipe && printf '100 CONSTANT TIME-SCALE\nINCLUDE %s\n%s\n' "$method" "$RUN" |
    "$mon" --port "$work/pipe/robot" --run-log run.jsonl >out.txt 2>err.txt)
st=$?
stop_sim
[ $st = 4 ] || fail "from a pipe: exit status $st, want 4: $(cat pipe/err.txt)"
check pipe failed failed failed

# ---- a tube there: completed, exit 0
start_sim tube 100 --inputs "$src/examples/tube_present.inputs"
(cd tube && "$mon" --port "$work/tube/robot" --run-log run.jsonl -e '100 CONSTANT TIME-SCALE' "$method" \
    -e "$RUN" </dev/null >out.txt 2>err.txt)
st=$?
stop_sim
[ $st = 0 ] || fail "with the tube: exit status $st, want 0: $(cat tube/err.txt)"
[ -s tube/err.txt ] && fail "with the tube: fbrlmon said something: $(cat tube/err.txt)"
check tube completed succeeded succeeded

# ---- the tube there for the first sample only: partial, exit 4. fbrlsim runs slowly here
# (motions 5 times faster than real) so the sensor goes off long before the second tube
# comes: the watcher takes it away once the first vacuum pulse is over (OUTPUT -5).
start_sim partial 5 --inputs "$src/examples/tube_present.inputs" --control "$work/partial/ctl"
(
    i=0
    while ! grep -qx 'OUTPUT -5' partial/sim.log 2>/dev/null && [ $i -lt 3000 ]; do sleep 0.02; i=$((i + 1)); done
    echo 'IN 3 0' >partial/ctl
) &
watcher=$!
(cd partial && "$mon" --port "$work/partial/robot" --run-log run.jsonl -e '100 CONSTANT TIME-SCALE' "$method" \
    -e "$RUN" </dev/null >out.txt 2>err.txt)
st=$?
wait $watcher
stop_sim
[ $st = 4 ] || fail "the first tube only: exit status $st, want 4: $(cat partial/err.txt)"
grep -q "SAMPLE-PREP: partial: 1 of 2 samples succeeded" partial/err.txt || fail "partial: fbrlmon said: $(cat partial/err.txt)"
check partial partial succeeded failed

# ---- the dry run: every WAIT-INPUT time-out with its step and sample; the predicted outcomes
"$mon" --dry-run --svg "$work/dry.svg" -e '60 CONSTANT TIME-SCALE' "$method" -e "$RUN" </dev/null >dry.out 2>dry.err
st=$?
[ $st = 4 ] || fail "dry run without a tube: exit status $st, want 4 (the run is predicted to fail)"
[ "$(grep -c 'time-out: WAIT-INPUT TUBE-ON-SEPARATOR on not seen within 0.500 s (Separation, sample [12])$' dry.out)" = 2 ] ||
    fail "the dry run does not list both time-outs: $(cat dry.out)"
grep -q '^commands [0-9]*, moves [0-9]*, errors 0, time-outs 2$' dry.out || fail "dry run counts: $(grep '^commands' dry.out)"
grep -q '^predicted run of SAMPLE-PREP: failed$' dry.out || fail "no predicted outcome: $(cat dry.out)"
grep -q "^  sample 2: failed: its tube never reached the separation unit's sensor$" dry.out || fail "no predicted sample outcome"
# each step's time for one run: the reaction waits its minute (1 s at TIME-SCALE 60) and moves
awk '/^  step Reaction  *1 x [0-9.]* s = / { found = $4 >= 1.0 } END { exit !found }' dry.out ||
    fail "the steps' predicted times: $(grep '  step' dry.out)"
"$mon" --dry-run --svg "$work/dry.svg" -e '60 CONSTANT TIME-SCALE' --sim-inputs "$src/examples/tube_present.inputs" \
    "$method" -e "$RUN" </dev/null >dry2.out 2>dry2.err
st=$?
[ $st = 0 ] || fail "dry run with the tube: exit status $st, want 0"
grep -q '^predicted run of SAMPLE-PREP: completed$' dry2.out || fail "with the tube: $(cat dry2.out)"
grep -q 'time-out:' dry2.out && fail "with the tube, a time-out is listed"
[ $fails -eq 0 ] && echo "method_run: all checks passed"
exit $((fails > 0))
