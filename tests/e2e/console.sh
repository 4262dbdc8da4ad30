#!/bin/sh
# SPDX-License-Identifier: MIT
# console.sh FBRLMON FBRLSIM WORKDIR SRCDIR
#
# The operator console (issue 16, "must show"): fbrlmon --console on an 80x24 tmux terminal
# against a real fbrlsim process (the tube sensor on, --log). The sample-prep method is
# chosen from examples/methods; bad parameters are refused in the form with the allowed
# range and nothing runs; 3 samples: start, pause (after the current step: the controller
# gets nothing while paused), resume, abort (the arm ends at READY, the safe place, and
# every output off, in fbrlsim's log); run again to the end. The run log parses line by
# line as JSON and its commands are exactly fbrlsim's log. The panes are saved as
# screen-*.txt (docs/console.md shows them).
mon=$1 sim=$2 work=$3 src=$4
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "SKIP: no python3"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=console
sim_scale=50
sim_args="--inputs $src/examples/tube_present.inputs"
# the method library: a copy (the composer writes a method file into it)
mkdir -p lib/methods && cp "$src"/examples/methods/*.fbrl lib/methods/ && cp "$src/examples/asps_cell.fbrl" "$src/examples/asps_cell_objects.fbrl" lib/ || exit 1
# a method whose corrective action asks the operator (ON-FAILURE ... ASK)
cat >lib/methods/tube_check.fbrl <<'EOF2'
: CHECK ( -- ) FAILURE PART-MISSING ;
ON-FAILURE CHECK PART-MISSING ASK
: ONE ( -- ) ['] CHECK ATTEMPT ;
: TRY ( i -- ) DROP ['] ONE RUN-SAMPLE IF ." tube there" ELSE ." tube skipped" THEN CR ;
METHOD TUBE-CHECK  asks when a tube is missing
1 3 1 SAMPLES-PARAM #TUBES tubes  tubes
' TRY SAMPLE-STEP Check  is the tube there?
END-METHOD
EOF2
# the lab: its users sign in (docs/compliance.md); tester is a programmer, Drafts may run
users="$(dirname "$mon")/fbrl-users"
printf 'admin pass 1\n' | "$users" --lab "$work/lab" setup admin >/dev/null || exit 1
printf 'admin pass 1\ntester pass\n' | "$users" --lab "$work/lab" --as admin add tester programmer >/dev/null || exit 1
printf 'admin pass 1\n' | "$users" --lab "$work/lab" --as admin set allow_drafts 1 >/dev/null || exit 1
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 80 -y 24 \
    "'$mon' --port '$work/robot' --console --methods '$work/lib/methods' --run-log '$work/run.jsonl' \
     --lab '$work/lab' -e '60 CONSTANT TIME-SCALE'; echo fbrlmon-exit=\$?; sleep 600"
key() { tmux -L "$sock" send-keys -t said "$@"; }
shot() { tmux -L "$sock" capture-pane -p -t said >"screen-$1.txt"; }
lines() { grep -vc '^#' sim.log; }

# ---- signing in, then down to the operator's level
wait_for "sign in: name:" || exit 1
key -l tester; key Enter; key -l "tester pass"; key Enter
wait_for "signed in: tester (programmer)" || exit 1
key F9; key 1
wait_for "level: operator"
# ---- the library, the form
wait_for "SAMPLE-PREP      ASPS sample preparation" || exit 1
shot library
key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
wait_for "#SAMPLES       [3" || exit 1

# ---- bad input is refused with the allowed range, and nothing runs
before=$(lines)
key -l abc; key F5
wait_for "refused: #SAMPLES: 'abc' is not a whole number: enter 1..24 tubes"
key -l 99; key F5
wait_for "refused: #SAMPLES: 99 is outside the allowed range 1..24 tubes"
shot refused
key BSpace BSpace; key F5
wait_for "refused: #SAMPLES is empty: enter a whole number 1..24 tubes"
key -l 0; key F5
wait_for "refused: #SAMPLES: 0 is outside the allowed range 1..24 tubes"
[ "$(lines)" = "$before" ] || fail "a refused form sent commands: $(lines) lines, were $before"
grep -q '"type":"header"' run.jsonl && fail "a refused form wrote a run log"

# ---- 3 samples, a 1-minute reaction (1 s with TIME-SCALE 60); start
key -l 3; key Down Down Down; key -l 1
wait_for "REACTION-MIN   [1 "
shot form
key F5
wait_long "RUNNING" 10
# ---- pause while the reagent goes in: it takes effect after the current step
wait_long "->  3 Reagent" 20
key F6
wait_long "PAUSED" 20 || exit 1
sleep 0.5
shot paused
paused_at=$(lines)
sleep 1.5
[ "$(lines)" = "$paused_at" ] || fail "the controller got commands while paused"
grep -q "paused before step [3-7]" screen-paused.txt || fail "the pause is not at a step's end"
key F7
wait_long "RUNNING" 10
# ---- abort: asked once more, then the safe stop and the safe place
key F8
wait_for "Abort the run? y or F8 = abort"
key y
wait_long "ABORTED" 20 || exit 1
wait_long "Arm (safe place)" 10
shot aborted
# the truth: fbrlsim's log after the abort's HALT ends with READY (the method's ON-ABORT)
tail_after_halt=$(awk '/^HALT$/{n=NR} {l[NR]=$0} END{for(i=n;i<=NR;i++) print l[i]}' sim.log)
echo "$tail_after_halt" | grep -qx HALT || fail "no HALT after the abort"
[ "$(echo "$tail_after_halt" | grep -E '^(MOVE|MOVES|APPRO|APPROS|DEPART|DEPARTS|READY|HOME|JOG|JOINT)' | tail -1)" = READY ] ||
    fail "the last motion after the abort is not READY: $tail_after_halt"
# every output off: each OUTPUT line of the log replayed
python3 - <<'PY' || fail "an output is left on after the abort"
on = set()
for l in open("sim.log"):
    l = l.strip()
    if l.startswith("OUTPUT "):
        for n in l[7:].split(","):
            n = int(n)
            (on.add if n > 0 else on.discard)(abs(n))
raise SystemExit(1 if on else 0)
PY
# READY, independently: upper arm up (10 in above a 10 in shoulder), forearm and tool level
# (10 + 2 in): X 12, Z 20 (DESIGN 6)
grep -q "X  12.00 Y   0.00 Z  20.00" screen-aborted.txt || fail "the arm is not shown at READY (X 12 Y 0 Z 20)"
grep -q "Separation\|Reaction\|Rinse\|Reagent" screen-aborted.txt || fail "no step on the aborted screen"

# ---- run again, to the end
key F5
wait_long "RUNNING" 10
wait_long "DONE" 60 || exit 1
wait_for "prepared 3 of 3 samples; used: buffer 6 ml, reagent 300 ul, wash 9 ml"
shot done
grep -q "Reagent, sample 2: user interrupt" screen-done.txt && fail "the aborted run's error is still shown"

# ---- levels: up as far as the signed-in user's role allows; the programmer's Forth line
key F11
sleep 0.3
tmux -L "$sock" capture-pane -p -t said | grep -q "^ok> " && fail "an operator got the Forth line"
key F9; key 3
wait_for "level: programmer"
key F11
key -l "6 7 * ."; key Enter
wait_for " 42 "
shot programmer
key Escape

# ---- a method developer composes a method from SAMPLE-PREP's steps, saves it, runs it
key F3
wait_for "Parameters of SAMPLE-PREP"
key F4
wait_for "Compose a method from the steps of SAMPLE-PREP"
key Enter; key Down; key Enter; key Down Down Down Down Down; key Enter
wait_for " 3. Summary"
shot compose
key F5; key -l "quick-prep"; key Enter
wait_for "saved QUICK-PREP as quick_prep.fbrl in the library"
grep -qx "SAMPLE-PREP USE-PARAMS" lib/methods/quick_prep.fbrl || fail "the composed file does not share the parameters"
key Enter
wait_for "Parameters of QUICK-PREP"
key -l 2; key F5
wait_long "QUICK-PREP completed" 30 || exit 1
shot composed-run
# ---- the work-cell view: the cell file's places and devices by name
key F6
wait_for "Work cell:"
tmux -L "$sock" capture-pane -p -t said | grep -q "^ A1  *place X  10.00 Y  -2.00 Z   3.00  pitch -90.0 roll   0.0" ||
    fail "the work cell does not show A1 as the cell file defines it"
tmux -L "$sock" capture-pane -p -t said | grep -q "^ BUFFER-PUMP  *device controller output 1" ||
    fail "the work cell does not show BUFFER-PUMP on output 1"
shot cell
# ---- TEACH a place from the work cell: SPOT (row 11), one jog X+ (0.1 in), Enter stores
key Down Down Down Down Down Down Down Down Down Down
teach_from=$(lines)
key t
teach_jog
wait_for "TEACH SPOT done"
teach_to=$(lines)
# where the composed run left the arm (X 6 Y -8 Z 7, its last W2) plus the jog
tmux -L "$sock" capture-pane -p -t said | grep -q "^ SPOT  *place X   6.10 Y  -8.00 Z   7.00  pitch -90.0" ||
    fail "TEACH did not store the jogged position into SPOT"
shot teach
key Escape
# ---- a corrective action asks the operator in the console; S skips the sample
key F2
wait_for "TUBE-CHECK"
key Down Down; key Enter
wait_for "Parameters of TUBE-CHECK"
key F5
wait_long "R retry, S skip this sample, A abort" 10
shot ask
key s
wait_long "TUBE-CHECK failed: 0 of 1 samples succeeded (0 failed, 1 skipped)" 10
wait_for "tube skipped"
wait_for "sample 1 skipped: CHECK failed (PART-MISSING): the operator skipped the sample"
key F9; key 1
wait_for "level: operator"
key F2; key F4
wait_for "composing a method needs the developer level"
key F6
wait_for "the work-cell view needs the developer level"
key F10
wait_for "fbrlmon-exit=0"

# ---- the run log: JSON line by line, its commands are fbrlsim's log
python3 - "$work/run.jsonl" "$work/sim.log" "$teach_from" "$teach_to" <<'PY' || fail "the run log does not match"
import json, sys
recs = [json.loads(l) for l in open(sys.argv[1])]
sim = [l.rstrip("\n") for l in open(sys.argv[2]) if not l.startswith("#")]
heads = [r for r in recs if r["type"] == "header"]
sums = [r for r in recs if r["type"] == "summary"]
assert len(heads) == 4 and len(sums) == 4, (len(heads), len(sums))
# the skipped tube was the run's only sample: none succeeded, the run failed
assert [s["outcome"] for s in sums] == ["aborted", "completed", "completed", "failed"], sums
assert [x["outcome"] for x in sums[1]["samples"]] == ["succeeded"] * 3, sums[1]
assert sums[3]["samples"] == [{"sample": 1, "outcome": "skipped",
                               "reason": "CHECK failed (PART-MISSING): the operator skipped the sample"}], sums[3]
# the aborted run: the sample it worked on failed, the others were not done
assert [x["outcome"] for x in sums[0]["samples"]].count("failed") == 1, sums[0]
assert all(x["reason"] for x in sums[0]["samples"]), sums[0]
asked = [r for r in recs[[i for i, r in enumerate(recs) if r["type"] == "header"][3]:] if r["type"] == "note"]
assert [r["event"] for r in asked] == ["question", "answer", "recovery"], asked
assert asked[1]["operator"] == "tester" and asked[1]["text"] == "skip the sample", asked
assert "PART-MISSING" in asked[2]["text"], asked
# the composed method: its own name, SAMPLE-PREP's parameters, the three steps picked
assert heads[2]["method"] == "QUICK-PREP" and heads[2]["source"].endswith("quick_prep.fbrl"), heads[2]
third = recs[[i for i, r in enumerate(recs) if r["type"] == "header"][2]:[i for i, r in enumerate(recs) if r["type"] == "header"][3]]
assert [(r["step"], r.get("sample")) for r in third if r["type"] == "step_end"] == \
    [("Recalibrate", None), ("Buffer", 1), ("Buffer", 2), ("Summary", None)], third
assert {x["name"]: x["value"] for x in heads[2]["parameters"]}["#SAMPLES"] == 2
heads = heads[:2]
for h in heads:
    p = {x["name"]: x["value"] for x in h["parameters"]}
    assert p["#SAMPLES"] == 3 and p["REACTION-MIN"] == 1, p
    assert h["method"] == "SAMPLE-PREP" and h["operator"] == "tester", h
    assert h["program"].startswith("fbrlmon ") and h["source"].endswith("sample_prep.fbrl"), h
    assert h["controller"].startswith("RAPL-II Version 2.60 A255 Robot") and "; controller on " in h["controller"], h
# a poll repeated while the controller is waited for is one record, with its count
cmds = [r["line"] for r in recs if r["type"] == "command" for _ in range(r.get("count", 1))]
assert any(r.get("count", 1) > 1 and r["line"] == "W5" for r in recs if r["type"] == "command"), "no W5 folded"
assert all(r["status"] == "ran" for r in recs if r["type"] == "command")
# everything the controller executed after the connection's handshake (NOHELP, STATUS for
# the units) was part of a run, but for TEACH (outside any run)
t0, t1 = int(sys.argv[3]), int(sys.argv[4])
assert "JOG 0.1,0,0" in sim[t0:t1], sim[t0:t1]
assert sim[:2] == ["NOHELP", "STATUS"] and cmds == sim[2:t0] + sim[t1:], (len(cmds), len(sim))
# the complete run: every step of every sample started and ended ok, in order
last = recs[[i for i, r in enumerate(recs) if r["type"] == "header"][1]:[i for i, r in enumerate(recs) if r["type"] == "header"][2]]
ends = [(r["step"], r.get("sample")) for r in last if r["type"] == "step_end" and r["status"] == "ok"]
assert len(ends) == 3 + 4 * 3, ends
assert ends[0] == ("Recalibrate", None) and ends[-1] == ("Summary", None), ends
first = recs[:[i for i, r in enumerate(recs) if r["type"] == "header"][1]]
assert any(r["type"] == "error" and "interrupt" in r["message"] for r in first), "no error record for the abort"
assert any(r["type"] == "note" and r["event"] == "safe-stop" for r in first)
# who paused, resumed and aborted: the operator, by name
notes = [(r["event"], r.get("operator")) for r in first if r["type"] == "note"]
assert ("pause", "tester") in notes and ("resume", "tester") in notes and ("abort", "tester") in notes, notes
# device actions and timed waits, planned against actual (a pulse cannot be shorter than
# planned unless aborted; WAIT-INPUT's plan is its time limit)
dev = [r for r in last if r["type"] == "device"]
assert sum(1 for r in dev if r["device"] == "BUFFER-PUMP" and r["action"] == "dispense 2 ml") == 3, dev
assert sum(1 for r in dev if r["device"] == "SYRINGE-1" and r["action"] == "pulse") == 6, dev
assert all(r["actual_ms"] >= r["planned_ms"] - 1 for r in dev if r.get("planned_ms") is not None), dev
waits = [r for r in last if r["type"] == "wait"]
assert [r["wait"] for r in waits].count("WAIT-INPUT TUBE-ON-SEPARATOR on: seen") == 3, waits
assert any(r["wait"] == "WAIT-UNTIL" and r["actual_ms"] >= r["planned_ms"] - 1 for r in waits), waits
texts = [r["text"] for r in last if r["type"] == "text"]
assert texts and texts[0].startswith("SAMPLE-PREP: completed after"), texts
print("run log: %d records, %d commands = fbrlsim's log" % (len(recs), len(cmds)))
PY
# ---- fbrlmon without the console: RUN-LOG in a plan, RUN-METHOD; a log that cannot be
# written is refused where it is asked for (file:line)
cat >plan.fbrl <<'PLAN'
RUN-LOG plan.jsonl
: UP ( -- ) READY ;
: GRIPS ( i -- ) DROP 30 1.5E0 GRIP ;
: CHECK ( -- ) FAILURE PART-MISSING ;
ON-FAILURE CHECK PART-MISSING SKIP
: ONE ( -- ) ['] CHECK ATTEMPT ;
: TRY ( i -- ) DROP ['] ONE RUN-SAMPLE DROP ;
METHOD TINY  two steps
1 3 2 SAMPLES-PARAM N tubes  tubes
' UP STEP Up  to READY
' GRIPS SAMPLE-STEP Grip  the gripper
' TRY SAMPLE-STEP Try  a part missing: skipped by the corrective action
END-METHOD
TINY RUN-METHOD
RUN-LOG /nonexistent/dir/x.jsonl
PLAN
before=$(lines)
"$mon" --port "$work/robot" plan.fbrl >plan.out 2>plan.err
st=$?
[ $st = 4 ] || fail "fbrlmon plan.fbrl: exit status $st (want 4: the run's two samples were skipped)"
grep -q "^plan.fbrl:15: error: RUN-LOG: /nonexistent/dir/x.jsonl: No such file or directory" plan.err ||
    fail "RUN-LOG's refusal: $(cat plan.err)"
tail -n +$((before + 1)) sim.log | grep -v '^#' >plan.all
[ "$(head -n 2 plan.all | tr '\n' ' ')" = "NOHELP STATUS " ] || fail "no connect handshake: $(head -n 2 plan.all)"
tail -n +3 plan.all >plan.sim
python3 - <<'PY' || fail "RUN-LOG's log does not match"
import json
recs = [json.loads(l) for l in open("plan.jsonl")]
cmds = [r["line"] for r in recs if r["type"] == "command" for _ in range(r.get("count", 1))]
sim = [l.rstrip("\n") for l in open("plan.sim")]
assert cmds == sim and "READY" in cmds and cmds.count("GRIP 1.5,30") == 2, (cmds, sim)
summary = [r for r in recs if r["type"] == "summary"][-1]
assert summary["outcome"] == "failed", summary  # no sample succeeded: both were skipped
assert [x["outcome"] for x in summary["samples"]] == ["skipped", "skipped"], summary
texts = [r["text"] for r in recs if r["type"] == "text"]
assert "2 samples: 0 succeeded, 0 failed, 2 skipped" in texts, texts
# the corrective action (ON-FAILURE ... SKIP) is in the log: an error with the action, a note
rec = [r for r in recs if r["type"] == "note" and r["event"] == "recovery"]
assert len(rec) == 2 and rec[0]["text"].startswith("CHECK, sample 1: PART-MISSING"), rec
assert all(r["text"].endswith(": skip the sample") for r in rec), rec
assert sum(1 for r in recs if r["type"] == "error" and r["advice"] == "skip the sample") == 2
PY

[ $fails -eq 0 ] && echo "console: all checks passed"
exit $((fails > 0))
