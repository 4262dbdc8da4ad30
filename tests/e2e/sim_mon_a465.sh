#!/bin/sh
# sim_mon_a465.sh FBRLMON FBRLSIM TMPDIR - fbrlmon drives a 6-axis A465 emulator
# through the same robot words as the A255: the built-in emulator (--sim-model a465)
# and an fbrlsim --model a465 process on a pty (--axes 6), whose command log is the
# truth for what ran. With the wrong axis count the position readout is refused.
mon=$1
sim=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
fails=0

fail() { fails=$((fails + 1)); echo "FAIL: $*"; echo "  stdout: $(cat out.txt)"; echo "  stderr: $(cat err.txt)"; }

cat >plan.fbrl <<'PLAN'
HOME READY
CREATE-LOC T1  16E0 4E0 14E0 10E0 -45E0 20E0 T1 DEFINE-LOC
T1 MOV
CREATE-LOC NOW  NOW ARM-HERE
NOW GETX F.  NOW GETY F.  NOW GETZ F.  NOW GETO F.  NOW GETA F.  NOW GETT F.
0E0 0.5E0 -1E0 0E0 0.2E0 0.3E0 MA FINISH
PLAN
want="16. 4. 14. 10. -45. 20. "

"$mon" --sim --sim-model a465 "$tmp/plan.fbrl" </dev/null >out.txt 2>err.txt
[ $? = 0 ] && [ "$(cat out.txt)" = "$want" ] || fail "built-in A465: the tool did not reach 16 4 14 yaw 10"

rm -f sim.log sim.out
"$sim" --model a465 --log "$tmp/sim.log" >sim.out 2>sim.err &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
i=0
while [ ! -s sim.out ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 sim.out)
case $port in
/dev/*) ;;
*) echo "FAIL: fbrlsim printed no device path: $(cat sim.out sim.err)"; exit 1 ;;
esac
"$mon" --port "$port" --axes 6 "$tmp/plan.fbrl" </dev/null >out.txt 2>err.txt
[ $? = 0 ] && [ "$(cat out.txt)" = "$want" ] || fail "--port to fbrlsim --model a465 with --axes 6"
grep -q '^MA 0,0.5,-1,0,0.2,0.3$' sim.log || fail "MA did not carry the sixth joint (log: $(cat sim.log))"
grep -q '^MOVE ' sim.log || fail "MOVE did not reach the emulator (log: $(cat sim.log))"
grep -q '^W2' sim.log || grep -q '^/031' sim.log || fail "no position readout in the log ($(cat sim.log))"
# five axes expected from a six-axis controller: the readout does not parse, and says so
"$mon" --port "$port" --axes 5 "$tmp/plan.fbrl" </dev/null >out.txt 2>err.txt
[ $? != 0 ] && grep -q 'ARM-HERE' err.txt || fail "--axes 5 on an A465 was not refused"
kill $simpid
wait $simpid 2>/dev/null
trap - EXIT
[ $fails = 0 ] && echo "sim_mon_a465: ok" && exit 0
exit 1
