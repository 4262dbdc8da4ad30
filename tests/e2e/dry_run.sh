#!/bin/sh
# SPDX-License-Identifier: MIT
# dry_run.sh FBRLMON EXAMPLES WORKDIR [real] - fbrlmon --dry-run of examples/sample_prep.fbrl
# (docs/workcell.md): it finishes in under 10 s of wall time, reports what the plan did, and
# its picture renders (rsvg-convert) with the expected elements. With "real", the same plan
# also runs in real time on the built-in emulator and the dry run's simulated duration must
# be within 2 % of that run's wall time (label slow: about a minute).
mon=$1 ex=$2 work=$3 real=${4:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
now() { date +%s.%N; }

# its own TMPDIR: another dry run (dry_run_vs_real runs at the same time) has its own scratch
mkdir -p "$work/tmp"
t0=$(now)
TMPDIR=$work/tmp "$mon" --dry-run --svg "$work/plan.svg" --dry-run-json "$work/dry.jsonl" -e '600 CONSTANT TIME-SCALE' --sim-inputs "$ex/tube_present.inputs" \
    "$ex/sample_prep.fbrl" >"$work/dry.out" 2>"$work/dry.err" || fail "the dry run failed: $(cat "$work/dry.err")"
t1=$(now)
wall=$(echo "$t1 $t0" | awk '{ printf "%.3f", $1 - $2 }')
awk -v w="$wall" 'BEGIN { exit !(w < 10) }' || fail "the dry run took $wall s (at most 10)"
dur=$(sed -n 's/^simulated duration \([0-9.]*\) s.*/\1/p' "$work/dry.out")
[ -n "$dur" ] || fail "no simulated duration: $(cat "$work/dry.out")"
grep -q '^commands [0-9]*, moves 89, errors 0, time-outs 0$' "$work/dry.out" || fail "moves/errors: $(grep '^commands' "$work/dry.out")"
grep -q '^smallest clearance [0-9.]* in to [A-Z-]* at X ' "$work/dry.out" || fail "no smallest clearance"
# the plan's pulses: buffer pump (output 1) 2 per tube, syringe (6) 2 per tube, ...
n=$(grep -c ' output 1 pulse 0.05' "$work/dry.out")
[ "$n" = 6 ] || fail "$n buffer pump pulses, want 6"
n=$(grep -c ' output 6 pulse 0.15' "$work/dry.out")
[ "$n" = 6 ] || fail "$n syringe pulses, want 6"
n=$(grep -c ' wait 0.150 s$' "$work/dry.out")
[ "$n" = 6 ] || fail "$n waits of the syringe's 150 ms, want 6"
grep -q '^run time 5[0-9] s$' "$work/dry.out" || fail "the plan's own run time (TIME-OF-DAY) is not the simulated one"
[ -z "$(ls "$work" | grep -v -e '^dry\.' -e '^plan\.svg$' -e '^tmp$')" ] || fail "the dry run left files: $(ls "$work")"
[ -z "$(ls -A "$work/tmp")" ] || fail "the scratch directory was left: $(ls -A "$work/tmp")"

# the path motion by motion (--dry-run-json): every line JSON, its smallest clearance the report's
python3 - "$work/dry.jsonl" "$work/dry.out" <<'PY' || fail "--dry-run-json does not agree with the report"
import json, re, sys
segs = [json.loads(line) for line in open(sys.argv[1])]
report = open(sys.argv[2]).read()
m = re.search(r"^smallest clearance ([0-9.]+) in to (\S+) ", report, re.M)
low = min((s for s in segs if s["sent"]), key=lambda s: s["clearance"])
ok = segs and all(s["sent"] for s in segs) and abs(low["clearance"] - float(m.group(1))) < 5e-4 \
    and low["near"] == m.group(2) and all(len(s["points"]) == (2 if s["line"] else 9) for s in segs)
print("dry-run-json: %d motions, smallest clearance %.4f in to %s" % (len(segs), low["clearance"], low["near"]))
sys.exit(0 if ok else 1)
PY
"$mon" --dry-run-json "$work/x.jsonl" -e '1 .' >"$work/json.out" 2>&1
[ $? = 2 ] && grep -q 'needs --dry-run' "$work/json.out" || fail "--dry-run-json without --dry-run: $(cat "$work/json.out")"

# the picture
svg=$work/plan.svg
[ -s "$svg" ] || fail "no picture"
for want in '<g id="top">' '<g id="side">' '<title>HEATING-BLOCK-BODY</title>' '<title>SEPARATION-UNIT</title>' \
    'class="keepout"' 'class="cylinder"' 'class="table"' '<title>A1</title>' '<title>SEPARATOR</title>' \
    'class="matrix"' '<polyline class="path"' 'class="closest"' '>closest 0.5500 in (HEATING-BLOCK-BODY)<'; do
    grep -qF "$want" "$svg" || fail "the picture lacks $want"
done
if command -v rsvg-convert >/dev/null 2>&1; then
    rsvg-convert -o "$work/plan.png" "$svg" 2>"$work/rsvg.err" || fail "rsvg-convert: $(cat "$work/rsvg.err")"
    [ -s "$work/plan.png" ] || fail "rsvg-convert made no picture"
else
    echo "rsvg-convert is not installed (librsvg2-bin): rendering not checked"
fi

# the plan's own files: written in a scratch directory and removed, unless --keep-files
echo 'CREATE-FILE made.dat' >"$work/files.fbrl"
"$mon" --dry-run --svg "$work/files.svg" "$work/files.fbrl" >"$work/files.out" 2>&1 || fail "files: $(cat "$work/files.out")"
[ -e "$work/made.dat" ] && fail "the dry run wrote the plan's file made.dat"
"$mon" --dry-run --keep-files --svg "$work/files.svg" "$work/files.fbrl" >"$work/files.out" 2>&1 || fail "files: $(cat "$work/files.out")"
[ -e "$work/made.dat" ] || fail "--keep-files: the plan's file made.dat was not written"

if [ "$real" = real ]; then
    t0=$(now)
    "$mon" -e '600 CONSTANT TIME-SCALE' --sim-inputs "$ex/tube_present.inputs" "$ex/sample_prep.fbrl" \
        >"$work/real.out" 2>"$work/real.err" || fail "the real-time run failed: $(cat "$work/real.err")"
    t1=$(now)
    realwall=$(echo "$t1 $t0" | awk '{ printf "%.3f", $1 - $2 }')
    ratio=$(echo "$dur $realwall" | awk '{ printf "%.4f", $1 / $2 }')
    echo "dry run: simulated $dur s in $wall s; real-time run: $realwall s; ratio $ratio"
    awk -v r="$ratio" 'BEGIN { exit !(r >= 0.98 && r <= 1.02) }' || fail "simulated $dur s, real $realwall s: not within 2 %"
else
    echo "dry run: simulated $dur s in $wall s"
fi
exit $fails
