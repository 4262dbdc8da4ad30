#!/bin/sh
# SPDX-License-Identifier: MIT
# cm3_faults.sh QEMU IMAGE FBRLSIM WORKDIR [N] [SEED]
#
# The link fault test over the firmware's own UART: the Cortex-M3 image in QEMU drives a
# real fbrlsim (on a pty, as UART1) that drops 1 % and corrupts 1 % of the bytes in both
# directions (--faults). N RAPL lines are typed at the firmware's console (UART0), each
# through RAPL inside CATCH, and the firmware prints what its link said of each: ran
# (0), controller error (-321: ran, refused), may have run (-333), or did not run.
# fbrlsim's command log is the truth for what ran. Checked, in order:
#   - a line reported as ran ran exactly once (a line safe to repeat: at least once), a
#     line reported as not run never ran, a "may have run" line at most once: 0 run
#     twice, 0 run unreported;
#   - no line ran that was not sent: 0 altered. The line has no parity here (QEMU's
#     PL011 sees none from a pty), so one alteration no protocol can see is possible: a
#     bit flipped on the way in and the same bit flipped back in the echo (docs/link.md
#     3.6). Such a line (one bit from the one sent) is counted and shown, not failed; the
#     lines hold no '-', so a '-' turned into CR (the other one) cannot happen.
qemu=$1 image=$2 sim=$3 work=$4 n=${5:-150} seed=${6:-7}
[ $# -ge 4 ] || { echo "usage: cm3_faults.sh QEMU IMAGE FBRLSIM WORKDIR [N] [SEED]"; exit 2; }
rm -rf "$work" && mkdir -p "$work" || exit 2
. "$(dirname "$0")/cm3_lib.sh"
DEADLINE_S=100
RAN=0 REFUSED=-321 MAYBE=-333

# The commands: counters (V3=V3+17: not safe to repeat, so the link must never type one
# again once its CR may have taken effect), and lines safe to repeat (docs/link.md 3.9:
# the link may type those again and they may run more than once): assignments, points,
# speeds, outputs, moves, HERE, and a move to an undefined point (error 11). No two
# alike in a row, no '-' anywhere.
awk -v n="$n" -v seed="$seed" 'BEGIN {
    r = seed
    print "HOME"; print "POINT PA,14.0000,2.0000,9.0000,0.0000,0.0000,0.0000"
    print "POINT PB,13.0000,0.5000,11.0000,0.0000,0.0000,0.0000"
    for (k = 0; k < 10; k++) print "V" k "=0"
    for (i = 13; i < n; i++) {
        r = (r * 1103515245 + 12345) % 2147483648; kind = r % 100
        r = (r * 1103515245 + 12345) % 2147483648; k = r % 10
        r = (r * 1103515245 + 12345) % 2147483648; v = r % 1000000
        if (kind < 40) line = sprintf("V%d=V%d+%d", k, k, 1 + v % 997)
        else if (kind < 50) line = sprintf("V%d=%d.%04d", k, v / 10000, v % 10000)
        else if (kind < 55) line = sprintf("POINT Q%d,%d.%04d,%d.%04d,%d.%04d,0.0000,0.0000,0.0000", k,
                                           10 + k % 4, v % 10000, k % 3, v % 7919, 5 + k % 5, v % 4999)
        else if (kind < 65) line = sprintf("SPEED %d", 10 + v % 91)
        else if (kind < 75) line = sprintf("OUTPUT %d", 1 + v % 16)
        else if (kind < 88) line = (i % 2) ? "MOVE PA" : "MOVE PB"
        else if (kind < 95) line = sprintf("HERE H%d", k)
        else line = sprintf("MOVE NOPE%d", k)
        if (line == prev) { i--; continue }
        print line; prev = line
    }
}' >"$work/commands"

# What is typed: TRY runs one line through RAPL and prints "R code". The controller's
# line runs without flow control, as the host's 8N1 fault test: a corrupted byte could
# otherwise become an XOFF (0x33 '3' with bit 5 flipped is 0x13) and hold the line.
{
    echo 'FALSE XONXOFF'
    echo ': TRY ( c-addr u -- ) ['"'"'] RAPL CATCH DUP IF NIP NIP THEN ." R " . CR ;'
    sed 's/.*/S" &" TRY/' "$work/commands"
    echo "FW-STATS"
    echo "BYE"
} >"$work/typed"

"$sim" --time-scale 200 --log "$work/sim.log" --faults "drop=0.01,corrupt=0.01,seed=$seed" \
    >"$work/sim.out" 2>"$work/sim.err" &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
trap 'exit 1' INT TERM
i=0
while [ ! -s "$work/sim.out" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 "$work/sim.out")
case $port in
/dev/*) ;;
*) echo "FAIL: fbrlsim printed no device path: $(cat "$work/sim.out" "$work/sim.err")"; exit 1 ;;
esac

t0=$(date +%s)
run_fw "$qemu" "$image" "$port" "$work/typed" "$work/fw.out" "$DEADLINE_S"
st=$?
t1=$(date +%s)
kill $simpid 2>/dev/null
wait $simpid 2>/dev/null
trap - EXIT
if [ $st != 0 ]; then
    echo "FAIL: QEMU exited with status $st (124: not done within ${DEADLINE_S} s)"
    tail -5 "$work/fw.out"
    exit 1
fi

# (controller lines the link shows, damaged ones too, may share the output: keep the text)
tr -d '\000-\011\013-\037' <"$work/fw.out" | awk '/(^| )R -?[0-9]+ *$/ { print $NF }' >"$work/results"
# What the link sends by itself: NOHELP when it connects, W5 while a move runs (the
# robot words wait for the arm), STATUS when it must learn whether a line ran.
grep -v -e '^#' -e '^NOHELP$' -e '^W5$' -e '^STATUS$' "$work/sim.log" >"$work/ran"
awk -v ran="$RAN" -v refused="$REFUSED" -v maybe="$MAYBE" -v cmdfile="$work/commands" \
    -v resfile="$work/results" -v secs="$((t1 - t0))" '
function onebit(a, b,    i, x, y, d, diff) {
    if (length(a) != length(b)) return 0
    diff = 0
    for (i = 1; i <= length(a); i++) {
        x = ord[substr(a, i, 1)]; y = ord[substr(b, i, 1)]
        if (x == y) continue
        d = xor(x, y)
        if (d != 1 && d != 2 && d != 4 && d != 8 && d != 16 && d != 32 && d != 64 && d != 128) return 0
        diff++
    }
    return diff == 1
}
# The next identical command within reach, when only lines that may not have run (reported
# may-have-run or not run) stand between: a second identical line in the log may be its run
# rather than a repeat of this one (MOVE PA, V6=V6+5 may-have-run and not run, MOVE PA: two MOVE
# PA in a row, one each). That command must be able to have run. The log cannot tell that
# from a repeat of this one and a lost run of the next: the judge fails only what it proves.
function owed(i,    j) {
    for (j = i + 1; j < nc && j <= i + LOOKAHEAD; j++) {
        if (cmd[j] == cmd[i]) return res[j] == ran || res[j] == refused || res[j] == maybe
        if (res[j] == ran || res[j] == refused) return 0
    }
    return 0
}
function upcoming(p, i,    j) {
    for (j = i + 1; j < nc && j <= i + LOOKAHEAD; j++) if (log_[p] == cmd[j]) return 1
    return 0
}
function xor(a, b,    r, bit) {
    r = 0
    for (bit = 1; bit <= 128; bit *= 2) if ((a % (bit * 2) >= bit) != (b % (bit * 2) >= bit)) r += bit
    return r
}
BEGIN {
    LOOKAHEAD = 8
    for (c = 0; c < 256; c++) ord[sprintf("%c", c)] = c
    while ((getline l < cmdfile) > 0) cmd[nc++] = l
    while ((getline l < resfile) > 0) res[nr++] = l
}
{ log_[nl++] = $0 }
END {
    if (nr != nc) { printf "FAIL: %d commands sent, %d results printed\n", nc, nr; exit 1 }
    p = 0; twice = 0; unreported = 0; altered = 0; invisible = 0; ok = 0; refusedn = 0; maybes = 0; notrun = 0
    for (i = 0; i < nc; i++) {
        # a line that ran but is neither this command nor one of the next few (this one
        # may not have run): altered, or the 8N1 blind spot. A blind-spot line is a run of
        # this command, as the controller got it: the link saw the echo match, sent the CR
        # and reports what came back, so it counts as one of its runs.
        runs = 0
        while (p < nl && log_[p] != cmd[i] && !upcoming(p, i)) {
            if (onebit(log_[p], cmd[i])) { invisible++; runs++; print "8N1 blind spot: sent \"" cmd[i] "\", ran \"" log_[p] "\"" }
            else { altered++; print "ALTERED: ran \"" log_[p] "\" (sending \"" cmd[i] "\")" }
            p++
        }
        while (p < nl && log_[p] == cmd[i] && !(runs == 1 && owed(i))) { runs++; p++ }
        r = res[i]
        if (r == ran) ok++; else if (r == refused) refusedn++; else if (r == maybe) maybes++; else notrun++
        safe = cmd[i] !~ /^V[0-9]=V[0-9]\+/
        want_min = (r == ran || r == refused) ? 1 : 0
        want_max = (r == ran || r == refused || r == maybe) ? 1 : 0
        if (want_max && safe && runs > 1) { repeats++; runs = 1 }
        if (runs > want_max) { twice++; print "RUN " runs " TIMES: \"" cmd[i] "\" (reported " r ")" }
        else if (runs < want_min) { unreported++; print "NOT RUN: \"" cmd[i] "\" (reported " r ")" }
        if (!safe) counters++
    }
    while (p < nl) { altered++; print "ALTERED (after the last): \"" log_[p] "\""; p++ }
    printf "%d commands in %d s: %d ran, %d refused by the controller, %d may have run, %d not run; ", nc, secs, ok, refusedn, maybes, notrun
    printf "%d altered, %d run twice (%d counters), %d wrongly reported, %d in the 8N1 blind spot; ", altered, twice, counters, unreported, invisible
    printf "%d safe lines typed again by design\n", repeats
    exit (altered || twice || unreported) ? 1 : 0
}' "$work/ran"
