#!/bin/sh
# SPDX-License-Identifier: MIT
# mon_units.sh FBRLMON FBRLSIM TMPDIR - the robot words send inches; a controller that
# works in millimetres (METRIC, kept in fbrlsim's state file like a controller's memory)
# would take every length 25.4 times too short. Once the link knows (METRIC ran in the
# session, or a STATUS was read: ROBOT-STATUS), every word that sends a length or reads a
# position is refused with an error that says why and what to do, and fbrlsim's command
# log (the truth of what ran) shows that nothing of it was sent; after NOMETRIC the same
# words run.
mon=$1
sim=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }

rm -f sim.log sim.state
. "$(dirname "$0")/sim_pty.sh"
start_sim sim.log --state "$tmp/sim.state"
lines() { grep -vc '^#' sim.log; }
new_lines() { tail -n +$(($1 + 1)) sim.log | grep -v -e '^#' -e '^NOHELP$' -e '^W5$' -e '^STATUS$'; }

# ---- in one session: METRIC typed raw, then the words refuse; NOMETRIC, then they run
cat >switch.fbrl <<'PLAN'
HOME READY
CREATE-LOC T1  12E0 3E0 8E0 0E0 -90E0 0E0 T1 DEFINE-LOC
: FCLEAR BEGIN FDEPTH WHILE FDROP REPEAT ;
: T ( i*x xt -- ) CATCH >R BEGIN DEPTH WHILE DROP REPEAT FCLEAR R> . ;
RAPL METRIC
T1 ' MOV T  T1 2E0 ' APPROACH T  1E0 ' DEPART T  0E0 0E0 1E0 ' JOG T  T1 ' ARM-HERE T
RAPL NOMETRIC
T1 MOV FINISH  T1 ARM-HERE  T1 GETX F>S .
PLAN
before=$(lines)
"$mon" --port "$port" switch.fbrl </dev/null >switch.out 2>switch.err
want="-325 -325 -325 -325 -325 12 "
[ "$(tr -d '\n' <switch.out)" = "$want" ] || fail "refusals: got '$(tr -d '\n' <switch.out)' want '$want' ($(cat switch.err))"
sent=$(new_lines "$before" | tr '\n' '|')
case $sent in
"HOME|READY|METRIC|NOMETRIC|POINT "*"|MOVE "*) ;;
*) fail "between METRIC and NOMETRIC something reached the controller: $sent" ;;
esac

# ---- a controller left in millimetres by an earlier session: refused at connect (the
# link reads STATUS after NOHELP, docs/link.md 1), before any word is typed: fbrlmon says so
# and how to switch it; JOG and ARM-HERE are refused and nothing of them is sent; W2 shows
# the controller's block as it came and its WORLD line converted from millimetres
"$mon" --port "$port" -e 'RAPL METRIC' </dev/null >/dev/null 2>&1
grep -q '^UNITS METRIC' sim.state || fail "fbrlsim did not keep METRIC in its state file"
connect_msg="works in millimetres (STATUS: METRIC UNITS.) and fbrlmon's robot words send inches: they are refused until you switch it to inches (RAPL NOMETRIC)"
before=$(lines)
"$mon" --port "$port" -e 'JOG 0 0 -2' </dev/null >jog.out 2>jog.err
[ $? = 1 ] || fail "JOG to a controller in millimetres did not fail"
grep -q "$connect_msg" jog.err || fail "the connect did not refuse the units: $(cat jog.err)"
grep -q "JOG: the controller works in millimetres" jog.err || fail "JOG's message: $(cat jog.err)"
[ "$(tail -n +$((before + 1)) sim.log | grep -v '^#' | tr '\n' ' ')" = "NOHELP STATUS " ] ||
    fail "the connect was not NOHELP and STATUS, or JOG was sent: $(tail -n +$((before + 1)) sim.log)"
before=$(lines)
"$mon" --port "$port" -e 'CREATE-LOC T3  T3 ARM-HERE' </dev/null >here.out 2>here.err
[ $? = 1 ] || fail "ARM-HERE from a controller in millimetres did not fail"
grep -q "ARM-HERE: the controller works in millimetres" here.err || fail "ARM-HERE's message: $(cat here.err)"
sent=$(new_lines "$before")
[ -z "$sent" ] || fail "ARM-HERE read a position in millimetres: $sent"
"$mon" --port "$port" -e 'W2' </dev/null >w2.out 2>w2.err
grep -q '^WORLD  *+304.8000 +076.2000 +203.2000' w2.out || fail "W2's block (T1 in mm): $(cat w2.out)"
grep -q '^world: X +12.0000 Y +3.0000 Z +8.0000 in ' w2.out || fail "W2 labels millimetres as inches: $(cat w2.out)"
"$mon" --port "$port" -e 'RAPL NOMETRIC' </dev/null >/dev/null 2>nomet.err
grep -q "$connect_msg" nomet.err || fail "RAPL NOMETRIC's session was not told of the units"
"$mon" --port "$port" -e 'JOG 0 0 -2' </dev/null >jog2.out 2>jog2.err || fail "JOG after NOMETRIC: $(cat jog2.err)"
[ -s jog2.err ] && fail "a controller in inches was refused: $(cat jog2.err)"
grep -qx 'JOG 0,0,-2' sim.log || fail "JOG did not run in inches after NOMETRIC"

echo "mon_units: $fails failed"
[ $fails -eq 0 ]
