#!/bin/sh
# SPDX-License-Identifier: MIT
# recover_session.sh FBRLMON FBRLSIM TMPDIR - corrective actions (docs/debugging.md) against
# fbrlsim on a pty, its inputs and control channel, its command log the truth for what ran:
#  1. a tube missing at sample 2 of 3, the operator answers Skip: samples 1 and 3 are
#     prepared, sample 2 is reported skipped, and its moves never ran;
#  2. a pick-up that finds nothing once (fbrlsim's gripper closes on nothing until the
#     control channel puts an object there): retried after a recovery word, then it works;
#  3. the controller goes away in the middle of the plan: a safe stop whose message says
#     where, and no command ran twice.
mon=$1
sim=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
rm -f ./*.log ./*.out ./*.err ctl
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }

. "$(dirname "$0")/sim_pty.sh"

cat >plan.fbrl <<'PLAN'
\ plan.fbrl - three samples; each tube has its own presence sensor (input n: tube n)
CREATE-LOC T-1  10.8E0 -2E0 4E0 0E0 -90E0 0E0 T-1 DEFINE-LOC
CREATE-LOC T-2  11.6E0 -2E0 4E0 0E0 -90E0 0E0 T-2 DEFINE-LOC
CREATE-LOC T-3  12.4E0 -2E0 4E0 0E0 -90E0 0E0 T-3 DEFINE-LOC
CREATE-LOC STATION  14E0 3E0 5E0 0E0 -90E0 0E0 STATION DEFINE-LOC
1 INPUT-DEVICE SENSOR-1  2 INPUT-DEVICE SENSOR-2  3 INPUT-DEVICE SENSOR-3
VARIABLE SAMPLE
: TUBE ( -- loc ) SAMPLE @ CASE 1 OF T-1 ENDOF 2 OF T-2 ENDOF T-3 SWAP ENDCASE ;
: SENSOR ( -- dev ) SAMPLE @ CASE 1 OF SENSOR-1 ENDOF 2 OF SENSOR-2 ENDOF SENSOR-3 SWAP ENDCASE ;
: LOAD-TUBE ( -- ) SENSOR INPUT? 0= IF FAILURE PART-MISSING THEN ;
: GRIPPED? ( -- flag ) S" GW" WGRIP S" GW" RAPL-REAL@ 0.1E0 F> ;
: PICK-UP ( -- ) TUBE MOV FINISH  40 0E0 GRIP  GRIPPED? 0= IF FAILURE GRIP-EMPTY THEN ;
: LET-GO ( -- ) 30 1.5E0 GRIP  TUBE 2E0 APPROACH FINISH ;
: DELIVER ( -- ) STATION MOV FINISH  30 1.5E0 GRIP ;
: ONE-SAMPLE ( -- ) ['] LOAD-TUBE ATTEMPT  ['] PICK-UP ATTEMPT  ['] DELIVER ATTEMPT ;
ON-FAILURE LOAD-TUBE PART-MISSING ASK
ON-FAILURE PICK-UP GRIP-EMPTY RUN LET-GO 1
ON-FAILURE PICK-UP GRIP-EMPTY ASK
ON-FAILURE * COMM-LOST STOP
: RUN-ALL ( -- ) 4 1 DO I SAMPLE !
   ['] ONE-SAMPLE RUN-SAMPLE IF ." prepared " ELSE ." skipped " THEN I . CR LOOP ;
PLAN

# 1. a missing tube at sample 2; the operator skips it
printf '0 IN 1 1\n0 IN 3 1\n' >tubes.inputs
start_sim skip.log --inputs "$tmp/tubes.inputs" --control "$tmp/ctl"
echo 'OBJECT 0.5' >ctl
printf 'HOME READY\nRUN-ALL\nS\n' | "$mon" --port "$port" plan.fbrl >skip.out 2>skip.err ||
    fail "the run with a skipped sample failed: $(cat skip.err)"
stop_sim
grep -qx 'prepared 1 ' skip.out && grep -qx 'skipped 2 ' skip.out && grep -qx 'prepared 3 ' skip.out ||
    fail "samples 1 and 3 prepared, 2 skipped: $(cat skip.out)"
grep -q '^LOAD-TUBE failed (sample 2): a sensor says the part is missing\.' skip.out ||
    fail "the operator was not asked in plain words: $(cat skip.out)"
grep -q '^recovery: LOAD-TUBE (sample 2): PART-MISSING (.*): ask: skip the sample' skip.out ||
    fail "the skip is not reported"
[ "$(grep -c '^POINT FBRLT[0-9]*,10.8,' skip.log)" = 1 ] && [ "$(grep -c '^POINT FBRLT[0-9]*,11.6,' skip.log)" = 0 ] &&
    [ "$(grep -c '^POINT FBRLT[0-9]*,12.4,' skip.log)" = 1 ] ||
    fail "tube 2 was moved to, or tube 1 or 3 not exactly once: $(grep '^POINT' skip.log)"

# 2. the gripper closes on nothing once, then the control channel puts a tube there
start_sim grip.log --control "$tmp/ctl"
echo 'OBJECT 0' >ctl
( i=0; while [ "$(grep -c '^GW=GRIPPER' grip.log 2>/dev/null)" -lt 1 ] && [ $i -lt 300 ]; do sleep 0.05; i=$((i + 1)); done
  echo 'OBJECT 0.5' >ctl ) &
watcher=$!
printf "HOME READY\n1 SAMPLE !\n' PICK-UP ATTEMPT .\" picked\" CR\n" |
    "$mon" --port "$port" plan.fbrl >grip.out 2>grip.err || fail "the retried pick-up failed: $(cat grip.err)"
wait $watcher
stop_sim
grep -q '^recovery: PICK-UP: GRIP-EMPTY (the gripper closed on nothing): run LET-GO, retry 1 of 1' grip.out ||
    fail "no retry after LET-GO: $(cat grip.out)"
grep -qx 'picked' grip.out || fail "the pick-up did not succeed on the retry: $(cat grip.out) $(cat grip.err)"
[ "$(grep -c '^GW=GRIPPER' grip.log)" = 2 ] || fail "the gripper was not checked exactly twice: $(grep GW grip.log)"

# 3. the controller goes away during sample 2: a safe stop that says where
printf '0 IN 1 1\n0 IN 2 1\n0 IN 3 1\n' >all.inputs
start_sim lost.log --inputs "$tmp/all.inputs" --control "$tmp/ctl"
echo 'OBJECT 0.5' >ctl
( i=0; while [ "$(grep -c '^MOVE' lost.log 2>/dev/null)" -lt 3 ] && [ $i -lt 300 ]; do sleep 0.05; i=$((i + 1)); done
  kill "$simpid" ) &
watcher=$!
printf 'HOME READY\nRUN-ALL\n' | "$mon" --port "$port" plan.fbrl >lost.out 2>lost.err
st=$?
wait $watcher
wait "$simpid" 2>/dev/null
[ $st = 1 ] || fail "a lost controller did not end the plan with an error (status $st)"
grep -q 'stopped safely: [A-Z-]* failed at sample 2: COMM-LOST' lost.err ||
    fail "the safe stop does not say where: $(cat lost.err) $(cat lost.out)"
grep -q '^recovery: [A-Z-]* (sample 2): COMM-LOST' lost.out || fail "the lost controller is not reported"
# what ran is the beginning of what an undisturbed run sends: nothing twice, nothing else
start_sim full.log --inputs "$tmp/all.inputs" --control "$tmp/ctl"
echo 'OBJECT 0.5' >ctl
printf 'HOME READY\nRUN-ALL\n' | "$mon" --port "$port" plan.fbrl >full.out 2>full.err || fail "undisturbed run: $(cat full.err)"
stop_sim
# (W5 is asked as often as a motion takes, STATUS when a prompt comes after the link's echo
# timeout on a busy host)
grep -v -e '^W5$' -e '^STATUS$' lost.log >lost.cmds
grep -v -e '^W5$' -e '^STATUS$' full.log >full.cmds
n=$(wc -l <lost.cmds)
head -n "$n" full.cmds >full.head
[ "$n" -gt 5 ] && cmp -s lost.cmds full.head || fail "the lost run's log is not the start of an undisturbed run's: $(diff lost.cmds full.head)"

[ $fails = 0 ] && echo "recover_session: ok" && exit 0
exit 1
