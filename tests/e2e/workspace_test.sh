#!/bin/sh
# SPDX-License-Identifier: MIT
# workspace_test.sh FBRLMON FBRLSIM TMPDIR - a session's work survives (docs/workspace.md).
#  1. One fbrlmon process on a real fbrlsim: teaches P by jogging (ARM-HERE), has the
#     controller's own pendant teach PEN001 (TEACH mode and the pendant button on fbrlsim's
#     control FIFO), imports it by name without moving the arm (the log shows LISTL only),
#     calibrates a moved block (CALIBRATE, WITH-CAL, MAP-ON), makes a RECTMAT and a device,
#     saves the workspace, then moves to P, PEN001 and a rack place and switches the valve.
#  2. A second fbrlmon process on a fresh fbrlsim loads the workspace (--workspace) and
#     does the same: fbrlsim's command logs (the truth of what ran) show the same targets
#     and outputs, and W2 the same arm positions.
#  3. A corrupt and a truncated copy are refused with a clear error: the session's P keeps
#     its value and no word of the file appears; a non-workspace data file is not replaced.
mon=$1
sim=$2
tmp=$3
rm -rf "$tmp"
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }
pids=""
trap 'for p in $pids; do kill $p 2>/dev/null; done' EXIT

# wait_for FILE TEXT: until FILE holds TEXT (at most 30 s)
wait_for() {
    i=0
    while ! grep -q "$2" "$1" 2>/dev/null; do
        i=$((i + 1))
        [ $i -gt 300 ] && { fail "timed out waiting for '$2' in $1"; return 1; }
        sleep 0.1
    done
    return 0
}

# start_sim NAME: fbrlsim with a log, a state file and a control FIFO; sets $port
start_sim() {
    "$sim" --log "$tmp/$1.log" --state "$tmp/$1.state" --control "$tmp/$1.ctl" >"$1.out" 2>"$1.err" &
    pids="$pids $!"
    wait_for "$1.out" /dev/ || exit 1
    port=$(head -n 1 "$1.out")
}

# ---- 1. teach, import, calibrate, save, move ----
start_sim a
mkfifo in1
"$mon" --port "$port" <in1 >out1 2>err1 &
monpid=$!
pids="$pids $monpid"
exec 3>in1
cat >&3 <<'PLAN'
HOME READY 50 SPEED
CREATE-LOC S  14E0 0E0 8E0 0E0 -90E0 0E0 S DEFINE-LOC  S MOV
CREATE-LOC P  2E0 -1E0 -1E0 JOG P ARM-HERE
0E0 3E0 1E0 JOG FINISH RAPL TEACH PEN
PLAN
wait_for a.log '^TEACH PEN'          # (fbrlmon's piped output is written at its end)
echo TEACH >a.ctl                    # the pendant's button: stores PEN001 on the controller
wait_for a.state PEN001
cat >&3 <<'PLAN'
RAPL NOTEACH
READY FINISH RAPL TYPE IMPORT
IMPORT-LOC PEN001
RAPL TYPE IMPORTED
CREATE-CAL C1 CREATE-CAL C2 CREATE-CAL-STRU CS CREATE-LOC T
10E0 0E0 5E0 0E0 -90E0 0E0 T DEFINE-LOC C1 1 T SET-CAL  11E0 0.5E0 5E0 0E0 -90E0 0E0 T DEFINE-LOC C2 1 T SET-CAL
14E0 0E0 5E0 0E0 -90E0 0E0 T DEFINE-LOC C1 2 T SET-CAL  15E0 0.5E0 5E0 0E0 -90E0 0E0 T DEFINE-LOC C2 2 T SET-CAL
10E0 4E0 5E0 0E0 -90E0 0E0 T DEFINE-LOC C1 3 T SET-CAL  11E0 4.5E0 5E0 0E0 -90E0 0E0 T DEFINE-LOC C2 3 T SET-CAL
C2 C1 CS CALIBRATE  CS WITH-CAL MAP-ON
P 1E0 0.5E0 0E0 RECTMAT RACK  5 OUTPUT-DEVICE VALVE
SAVE-WORKSPACE ws.ws
RAPL TYPE MARK
P MOV FINISH W2  PEN001 MOV FINISH W2  CREATE-LOC Q 2 1 0 Q RACK Q MOV FINISH W2  VALVE ON
BYE
PLAN
exec 3>&-
wait $monpid
st=$?
[ $st -eq 0 ] || fail "session 1 ended with status $st: $(cat err1)"
grep -q "saved 4 locations, 1 matrix, 3 calibrations, 1 device to ws.ws" out1 || fail "session 1 save: $(cat out1)"
# the import asked the controller, it did not move the arm
imp=$(sed -n '/^TYPE IMPORT$/,/^TYPE IMPORTED$/p' a.log)
echo "$imp" | grep -q '^LISTL PEN001$' || fail "IMPORT-LOC did not list PEN001: $imp"
echo "$imp" | grep -Eq '^(MOVE|POINT|JOG|READY|SET)' && fail "IMPORT-LOC talked motion: $imp"

# ---- 2. a second process loads it and goes to the same places ----
start_sim b
"$mon" --port "$port" --workspace ws.ws -e 'HOME READY 50 SPEED RAPL TYPE MARK
P MOV FINISH W2  PEN001 MOV FINISH W2  CREATE-LOC Q 2 1 0 Q RACK Q MOV FINISH W2  VALVE ON' </dev/null >out2 2>err2
st=$?
[ $st -eq 0 ] || fail "session 2 ended with status $st: $(cat err2)"
# (which of the two scratch points a move uses depends on the moves before: not compared)
after() { sed -n '/^TYPE MARK$/,$p' "$1" | grep -E '^(POINT|MOVE|OUTPUT)' | sed 's/FBRLT[12]/FBRLT_/'; }
after a.log >a.moves
after b.log >b.moves
[ "$(wc -l <a.moves)" -ge 7 ] || fail "session 1 log has too few motion lines: $(cat a.moves)"
cmp -s a.moves b.moves || fail "the two sessions sent different targets:
$(diff a.moves b.moves)"
grep WORLD out1 | tail -n 3 >a.world
grep WORLD out2 >b.world
[ "$(wc -l <a.world)" -eq 3 ] && cmp -s a.world b.world || fail "W2 differs:
$(cat a.world)
--
$(cat b.world)"

# ---- 3. damaged files change nothing ----
size=$(wc -c <ws.ws)
head -c $((size - 5)) ws.ws >short.ws
# flip one byte in the middle of the records
dd if=ws.ws of=bad.ws bs=1 count=$((size / 2)) 2>/dev/null
printf '\377' >>bad.ws
dd if=ws.ws bs=1 skip=$((size / 2 + 1)) 2>/dev/null >>bad.ws
for f in short.ws bad.ws; do
    "$mon" --offline -e "CREATE-LOC P 1E0 2E0 3E0 4E0 5E0 6E0 P DEFINE-LOC
LOAD-WORKSPACE $f" -e 'P DISPLAY-LOC ' -e "' RACK" </dev/null >out3 2>err3
    grep -q "error: LOAD-WORKSPACE $f: .*; nothing loaded" err3 || fail "$f not refused clearly: $(cat err3)"
    grep -q "X    +1.0000 Y    +2.0000 Z    +3.0000 in  O   +4.000 A   +5.000 T   +6.000" out3 ||
        fail "$f: P changed: $(cat out3)"
    grep -q "undefined word RACK" err3 || fail "$f: RACK appeared: $(cat err3)"
done
grep -q "truncated" err3 2>/dev/null || true
"$mon" --offline --workspace short.ws -e '1 .' </dev/null >out4 2>err4
[ $? -eq 3 ] && grep -q "fbrlmon: --workspace short.ws: .*nothing loaded" err4 || fail "--workspace short.ws: $(cat err4)"
# a data file of another kind is never replaced by SAVE-WORKSPACE
"$mon" --offline -e 'CREATE-FILE data.dat OPEN-FILE H data.dat VARIABLE V 7 V ! V INTEGER H WRITE-FILE H CLOSE-FILE DROP' </dev/null
cp data.dat data.orig
"$mon" --offline -e 'CREATE-LOC A SAVE-WORKSPACE data.dat' </dev/null >out5 2>err5
grep -q "not a workspace: not replaced" err5 && cmp -s data.dat data.orig || fail "SAVE-WORKSPACE over a data file: $(cat err5)"

[ $fails -eq 0 ] && echo "workspace: two sessions, $(wc -l <a.moves) motion lines alike; damaged files refused"
exit $((fails != 0))
