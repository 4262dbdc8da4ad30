#!/bin/sh
# SPDX-License-Identifier: MIT
# debug_session.sh FBRLMON FBRLSIM TMPDIR - finding and fixing a plan (docs/debugging.md),
# driven as a person would, against fbrlsim on a pty whose command log is the truth:
#  1. an error three words deep in a file: the backtrace names each word and its line;
#  2. a breakpoint, two steps, a W2 at the stop and continue: the plan then ends with the
#     same command log as an uninterrupted run (less the W2 typed at the stop);
#  3. EDIT with EDITOR a script that changes a definition: the new one runs, and a
#     location taught before the edit is still there;
#  4. bad use gets one clear error each.
mon=$1
sim=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
rm -f ./*.log ./*.out ./*.err trace.txt
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }

. "$(dirname "$0")/sim_pty.sh"

cat >plan.fbrl <<'PLAN'
\ plan.fbrl - two moves, each word on its own lines
CREATE-LOC T1  14E0 2E0 8E0 0E0 -90E0 0E0 T1 DEFINE-LOC
CREATE-LOC T2  12E0 -3E0 6E0 0E0 -90E0 0E0 T2 DEFINE-LOC
CREATE-LOC FAR  99E0 0E0 8E0 0E0 -90E0 0E0 FAR DEFINE-LOC
: GO ( loc -- ) MOV FINISH ;
: TO-T1 T1 GO ;
: TO-T2 T2 GO ;
: SHUTTLE ( -- )
   TO-T1
   TO-T2 ;
: REACH-OUT ( -- ) 7 FAR GO ;
: PICK-UP ( -- )
   REACH-OUT ;
: RUN-ALL ( -- ) SHUTTLE PICK-UP ;
PLAN

# 1. the backtrace of a controller error three words deep
start_sim bt.log
printf 'HOME READY\nRUN-ALL\n' | "$mon" --port "$port" plan.fbrl >bt.out 2>bt.err
stop_sim
first=$(head -n 1 bt.err)
case $first in
*"plan.fbrl:5: error: "*" in GO") ;;
*) fail "backtrace: the error line does not name GO at plan.fbrl:5: $first" ;;
esac
grep -qx '  called by REACH-OUT (plan.fbrl:11)' bt.err || fail "backtrace: REACH-OUT line 11 missing: $(cat bt.err)"
grep -qx '  called by PICK-UP (plan.fbrl:13)' bt.err || fail "backtrace: PICK-UP line 13 (the call's line) missing"
grep -qx '  called by RUN-ALL (plan.fbrl:14)' bt.err || fail "backtrace: RUN-ALL line 14 missing"
grep -qx '  called from stdin:2' bt.err || fail "backtrace: where RUN-ALL was typed (stdin:2) is missing"
grep -qx '  data stack <1>: 7' bt.err || fail "backtrace: the data stack at the failure (7; MOV took the location) missing"
grep -q '^MOVE ' bt.log || fail "backtrace: SHUTTLE's moves did not run first ($(cat bt.log))"

# 2. a breakpoint, two steps, W2 at the stop, continue: the same command log
start_sim plain.log
printf 'HOME READY\nSHUTTLE\n' | "$mon" --port "$port" plan.fbrl >plain.out 2>plain.err ||
    fail "uninterrupted run failed: $(cat plain.err)"
stop_sim
start_sim stepped.log
printf 'HOME READY\nBREAK TO-T1\nSHUTTLE\ns\ns\nW2\n.S\nc\n' |
    "$mon" --port "$port" plan.fbrl >stepped.out 2>stepped.err || fail "stepped run failed: $(cat stepped.err)"
stop_sim
grep -q '^stop: TO-T1 (plan.fbrl:6), called by SHUTTLE at plan.fbrl:9' stepped.out ||
    fail "no stop at TO-T1 called from line 9: $(cat stepped.out)"
# a step visits each word of TO-T1 (T1 GO ;), as gforth's dbg does
grep -q '^stop: T1, in TO-T1 at plan.fbrl:6' stepped.out || fail "the step to T1 is missing: $(cat stepped.out)"
grep -q '^stop: GO (plan.fbrl:5), in TO-T1 at plan.fbrl:6' stepped.out || fail "the step to GO missing"
grep -q '^ *6 *: TO-T1 T1 GO ;' stepped.out || fail "the source line of the word is not shown"
[ "$(grep -c '^W2' stepped.log)" = 1 ] || fail "the W2 typed at the stop did not reach the controller once"
# W5 (is the motion over?) is asked as often as the motion takes, and STATUS when a prompt
# comes after the link's echo timeout on a busy host: not part of what ran
grep -v -e '^W[25]$' -e '^STATUS$' stepped.log >stepped.cmds
grep -v -e '^W5$' -e '^STATUS$' plain.log >plain.cmds
cmp -s plain.cmds stepped.cmds || fail "the stepped run's command log differs: $(diff plain.cmds stepped.cmds)"

# 2c. steps visit built-in words: a word made only of them stops before each, the failing
# one included; a FILE:LINE breakpoint stops on the line that fails (its first word), in a
# definition or interpreted; after UNBREAK ALL nothing stops, a step under way included
cp "$(cd "$(dirname "$0")" && pwd)/debug_built.fbrl" built.fbrl
printf 'BREAK MATH\nMATH\ns\ns\ns\ns\ns\n' | "$mon" --offline built.fbrl >built.out 2>built.err
for w in '6' '7 \*' '0' '/'; do
    grep -q "^stop: $w, in MATH at built.fbrl:2" built.out || fail "no step stop at $w in MATH: $(cat built.out)"
done
grep -q 'built.fbrl:2: error: division by zero in MATH' built.err || fail "MATH did not fail after the steps"
printf 'c\n' | "$mon" --offline -e 'BREAK built.fbrl:5' built.fbrl -e '7 SPLIT' >line.out 2>line.err
grep -q '^stop: SWAP, in SPLIT at built.fbrl:5' line.out || fail "BREAK FILE:LINE did not stop on the failing line: $(cat line.out)"
grep -q 'built.fbrl:5: error: division by zero in SPLIT' line.err || fail "SPLIT did not fail after the stop"
printf 'BREAK SPLIT\n9 SPLIT 2DROP\ns\nUNBREAK ALL\nc\n9 SPLIT\n: AGAIN-1 1 ;\nAGAIN-1 .\n' | "$mon" --offline built.fbrl >unbreak.out 2>unbreak.err
[ "$(grep -c '^stop: ' unbreak.out)" = 2 ] || fail "stops after the breakpoint was gone: $(cat unbreak.out)"

# 2b. the trace's commands are the controller's command log, each with the line that sent it
start_sim traced.log
printf 'TRACE-TO trace.txt\nTRACE-ON\nHOME READY\nSHUTTLE\nTRACE-OFF\n' |
    "$mon" --port "$port" plan.fbrl >traced.out 2>traced.err || fail "traced run failed: $(cat traced.err)"
stop_sim
sed -n 's/^trace: \(.*\)  (.*)$/\1/p' trace.txt >trace.cmds
n=$(wc -l <trace.cmds)
tail -n "$n" traced.log >traced.tail
[ "$n" -gt 4 ] && cmp -s trace.cmds traced.tail || fail "the trace's commands differ from the log: $(diff trace.cmds traced.tail)"
grep -q '^trace: MOVE .*(ran; plan.fbrl:5 in GO)$' trace.txt || fail "a MOVE is not traced to GO at plan.fbrl:5: $(cat trace.txt)"

# 3. EDIT: the new definition runs; a taught location survives the file's reload
cat >edit.fbrl <<'PLAN'
\ edit.fbrl
CREATE-LOC HOLD
: ANSWER ( -- n ) 41 ;
PLAN
cat >editor.sh <<'ED'
#!/bin/sh
# an editor: called as EDITOR +LINE FILE; changes ANSWER's value
echo "$1 $2" >"$(dirname "$2")/editor.args"
sed -i 's/ 41 / 42 /' "$2"
ED
chmod +x editor.sh
start_sim edit.log
printf 'HOME READY\n14E0 2E0 8E0 0E0 -90E0 0E0 T1 DEFINE-LOC T1 MOV FINISH\nHOLD ARM-HERE\nANSWER .\nEDIT ANSWER\nANSWER .\nHOLD GETX F. HOLD GETY F.\n' |
    EDITOR="$tmp/editor.sh" VISUAL= "$mon" --port "$port" edit.fbrl plan.fbrl >edit.out 2>edit.err ||
    fail "EDIT session failed: $(cat edit.err)"
stop_sim
[ "$(cat editor.args 2>/dev/null)" = "+3 edit.fbrl" ] || fail "the editor was not opened at edit.fbrl line 3: $(cat editor.args)"
grep -q '41 ' edit.out && grep -q '42 ' edit.out || fail "the edited definition did not run: $(cat edit.out)"
grep -q '14\. 2\. ' edit.out || fail "HOLD lost its taught place (14 2): $(cat edit.out)"

# 3b. EDIT a hundred times a file that makes three tasks: each load makes the same tasks
# again (five loads used to end in "no room for another task")
cat >tasks.fbrl <<'PLAN'
\ tasks.fbrl
TASK TA TASK TB TASK TC
: NAP ( -- ) 1 MS ;
' NAP TA START TA AWAIT
PLAN
i=0
: >edit100.in
while [ $i -lt 100 ]; do echo 'EDIT NAP' >>edit100.in; i=$((i + 1)); done
echo 'TASKS' >>edit100.in
EDITOR=true VISUAL= "$mon" --offline tasks.fbrl <edit100.in >edit100.out 2>edit100.err ||
    fail "100 EDITs: $(grep -m 1 'error' edit100.err)"
[ "$(grep -c 'loading .*tasks.fbrl again' edit100.out)" = 100 ] || fail "not 100 reloads: $(tail -n 3 edit100.out)"
[ "$(grep -c '^T[ABC]  ' edit100.out)" = 3 ] || fail "TASKS after 100 EDITs does not list three tasks: $(cat edit100.out | tail -n 6)"

# 3c. SAVE-DEFINITIONS keeps the definitions that compiled: one abandoned by an error on its
# second line is left out, and the file it writes loads without an error
rm -f saved.fbrl
printf ': GOOD ( -- n ) 1 ;\n: HALF ( -- n ) 2\n  NOSUCH ;\n: MULTI ( -- n )\n  3 ;\nSAVE-DEFINITIONS saved.fbrl\n' |
    "$mon" --offline >save.out 2>save.err
grep -q 'stdin:3: error: undefined word NOSUCH' save.err || fail "the abandoned definition's error: $(cat save.err)"
grep -q '^: GOOD' saved.fbrl && grep -q '^: MULTI' saved.fbrl || fail "SAVE-DEFINITIONS lost a definition: $(cat saved.fbrl)"
grep -q 'HALF' saved.fbrl && fail "SAVE-DEFINITIONS wrote the abandoned definition: $(cat saved.fbrl)"
"$mon" --offline saved.fbrl -e 'GOOD MULTI + .' </dev/null >load.out 2>load.err || fail "the saved file does not load: $(cat load.err)"
grep -q '^4 ' load.out || fail "the saved definitions do not run: $(cat load.out)"

# 4. bad use: one clear error each
printf 'BREAK NO-SUCH-WORD\nEDIT DUP\n: TYPED 1 ;\nEDIT TYPED\n' | "$mon" --offline >bad.out 2>bad.err
grep -q 'BREAK: NO-SUCH-WORD is not a word' bad.err || fail "BREAK of an unknown word: $(cat bad.err)"
grep -q 'EDIT: DUP has no source file (it is built in)' bad.err || fail "EDIT of a built-in word"
grep -q 'EDIT: TYPED has no source file (it was typed at the prompt)' bad.err || fail "EDIT of a typed word"
[ "$(grep -c 'error: ' bad.err)" = 3 ] || fail "bad use: not one error each: $(cat bad.err)"

[ $fails = 0 ] && echo "debug_session: ok" && exit 0
exit 1
