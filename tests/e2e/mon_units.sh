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

# ---- a controller left in millimetres by an earlier session: ROBOT-STATUS shows it and
# from then on a motion is refused with a message that says what to do
"$mon" --port "$port" -e 'RAPL METRIC' </dev/null >/dev/null 2>&1
grep -q '^UNITS METRIC' sim.state || fail "fbrlsim did not keep METRIC in its state file"
before=$(lines)
"$mon" --port "$port" -e 'ROBOT-STATUS' -e 'CREATE-LOC T2 12E0 3E0 8E0 0E0 -90E0 0E0 T2 DEFINE-LOC T2 MOV' \
    </dev/null >left.out 2>left.err
[ $? = 1 ] || fail "MOV to a controller in millimetres did not fail"
grep -q "METRIC UNITS." left.out || fail "ROBOT-STATUS did not show the units: $(cat left.out)"
grep -q "MOV: the controller works in millimetres (STATUS: METRIC UNITS.) and the robot words send inches: not sent; switch it to inches (RAPL NOMETRIC) first" left.err ||
    fail "message: $(cat left.err)"
sent=$(new_lines "$before")
[ -z "$sent" ] || fail "a motion reached a controller in millimetres: $sent"
"$mon" --port "$port" -e 'RAPL NOMETRIC' </dev/null >/dev/null 2>&1

echo "mon_units: $fails failed"
[ $fails -eq 0 ]
