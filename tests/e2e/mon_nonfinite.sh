#!/bin/sh
# SPDX-License-Identifier: MIT
# mon_nonfinite.sh FBRLMON FBRLSIM TMPDIR - IEEE arithmetic makes infinities and NaN, so
# the safety check sits at the controller boundary: a NaN or an infinity given to
# DEFINE-LOC, a motion word, a calibration or any word that sends a real is refused with
# an error naming the word and the value, and fbrlsim's command log (the truth of what
# ran) shows that nothing was sent; the same plan with finite values does reach it.
mon=$1
sim=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }

rm -f sim.log sim.out
"$sim" --log "$tmp/sim.log" >sim.out 2>sim.err &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
i=0
while [ ! -s sim.out ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 sim.out)
case $port in
/dev/*) ;;
*) echo "FAIL: fbrlsim printed no device path: $(cat sim.out sim.err)"; exit 1 ;;
esac

# Each refused word must leave the THROW code -303 (FBRL_ENONFINITE) and its reals.
cat >bad.fbrl <<'PLAN'
: NAN 0E0 0E0 F/ ;  : INF 1E0 0E0 F/ ;  : -INF -1E0 0E0 F/ ;
: FCLEAR BEGIN FDEPTH WHILE FDROP REPEAT ;
: T ( xt -- ) CATCH . FDEPTH . FCLEAR ;
CREATE-LOC T1  CREATE-LOC T2
NAN 3E0 8E0 0E0 -90E0 0E0 T1 ' DEFINE-LOC T
12E0 3E0 8E0 0E0 -90E0 INF T1 ' DEFINE-LOC T
12E0 3E0 8E0 0E0 -90E0 0E0 T2 DEFINE-LOC
T2 INF ' APPROACH T
-INF ' DEPART T
INF 0E0 0E0 ' JOG T
1E0 2E0 NAN 0E0 0E0 ' MA T
10 NAN ' GRIP T
NAN 0E0 0E0 0E0 ' BASE-OFFSET T
S" MYVAR" INF ' SET-RAPL-REAL T
NAN ' SEND-REAL T
CREATE-CAL-STRU S1  NAN S1 1 ' CAL-STRU! T
PLAN
"$mon" --port "$port" bad.fbrl </dev/null >bad.out 2>bad.err
want="-303 6 -303 6 -303 1 -303 1 -303 3 -303 5 -303 1 -303 4 -303 1 -303 1 -303 1 "
[ "$(tr -d '\n' <bad.out)" = "$want" ] || fail "refusals: got '$(tr -d '\n' <bad.out)' want '$want' ($(cat bad.err))"
# the connect's handshake: NOHELP, then STATUS (the controller's units)
sent=$(grep -v -x -e NOHELP -e STATUS sim.log)
[ -z "$sent" ] || fail "non-finite values reached the controller: $sent"
[ "$(tr '\n' ' ' <sim.log)" = "NOHELP STATUS " ] || fail "the emulator's log shows no handshake: the check proves nothing"

# The error names the word and the value.
"$mon" --port "$port" -e ': INF 1E0 0E0 F/ ; INF DEPART' </dev/null >msg.out 2>msg.err
grep -q 'DEPART refuses Inf' msg.out msg.err || fail "message does not name word and value: $(cat msg.out msg.err)"
"$mon" --port "$port" -e 'CREATE-LOC T3 0E0 0E0 F/ 3E0 8E0 0E0 -90E0 0E0 T3 DEFINE-LOC' </dev/null >msg.out 2>msg.err
grep -q 'DEFINE-LOC refuses NaN' msg.out msg.err || fail "DEFINE-LOC message: $(cat msg.out msg.err)"

# The same plan with finite values is sent (so the log would show a leak).
"$mon" --port "$port" -e 'HOME READY CREATE-LOC T2 12E0 3E0 8E0 0E0 -90E0 0E0 T2 DEFINE-LOC T2 1E0 APPROACH 2E0 DEPART' \
    </dev/null >ok.out 2>ok.err || fail "finite plan failed: $(cat ok.out ok.err)"
grep -q '^APPRO' sim.log || fail "finite APPROACH did not reach the emulator: $(cat sim.log)"
grep -q '^DEPART' sim.log || fail "finite DEPART did not reach the emulator: $(cat sim.log)"

kill $simpid
wait $simpid 2>/dev/null
[ $fails -eq 0 ] && echo "mon_nonfinite: all checks passed"
exit $((fails > 0))
