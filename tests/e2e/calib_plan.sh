#!/bin/sh
# SPDX-License-Identifier: MIT
# calib_plan.sh FBRLSIM FBRLMON EXAMPLES WORKDIR PLAN_RUN INPUTS
#
# The sample-preparation plan (EXAMPLES/sample_prep.fbrl) with its three locating pins
# re-taught at different heights, as a jog that is off by a hair leaves them, against a
# real fbrlsim (through plan_run.sh). The unperturbed run is the committed command log
# EXAMPLES/sample_prep.expected (plan_sample_prep checks it). Every POINT the jogged run
# sends must have the same place in the log and a roll within 0.1 degree of the
# unperturbed one (issue 9: a 0.0001 in jog used to turn 24 of 57 POINTs by 180 degrees).
sim=$1 mon=$2 ex=$3 work=$4 run=$5 inputs=$6
fails=0
rm -rf "$work" && mkdir -p "$work" || exit 2

# jogged: pin heights (the JOG's z) for pin 1, 2, 3
for case in "a -0.4499 -0.4501 -0.4500" "b -0.4500 -0.4499 -0.4502" "c -0.4497 -0.4500 -0.4499"; do
    set -- $case
    name=$1 z1=$2 z2=$3 z3=$4
    dir=$work/$name
    mkdir -p "$dir"
    cp "$ex/asps_cell.fbrl" "$ex/asps_cell_objects.fbrl" "$dir/"
    awk -v z1="$z1" -v z2="$z2" -v z3="$z3" '
        /^JOG / { n++; $4 = (n == 1 ? z1 : n == 2 ? z2 : z3) }
        { print }' "$ex/sample_prep.fbrl" >"$dir/sample_prep.fbrl"
    [ "$(grep -c '^JOG ' "$dir/sample_prep.fbrl")" = 3 ] || { echo "FAIL: the plan no longer has 3 JOG lines"; exit 1; }
    FBRL_REGEN=1 sh "$run" "$sim" "$dir/run" "$inputs" "$dir/log.txt" - \
        "$mon" -e "600 CONSTANT TIME-SCALE" --port @PORT@ "$dir/sample_prep.fbrl" >"$dir/run.out" 2>&1 ||
        { echo "FAIL: case $name: the plan did not run:"; cat "$dir/run.out"; fails=1; continue; }
    grep '^POINT ' "$ex/sample_prep.expected" >"$dir/want"
    grep '^POINT ' "$dir/log.txt" >"$dir/got"
    # POINT name,x,y,z,yaw,pitch,roll
    if ! awk -F, -v name="$name" -v z="$z1 $z2 $z3" '
        function wrap(d) { while (d > 180) d -= 360; while (d <= -180) d += 360; return d }
        function abs(d) { return d < 0 ? -d : d }
        NR == FNR { want[FNR] = $0; roll[FNR] = $7; n = FNR; next }
        { got++; if (!(got in want)) { print "FAIL: case " name ": more POINTs than the unperturbed run"; bad = 1; next }
          split(want[got], w, ","); if ($1 != w[1]) { print "FAIL: POINT " got " names " $1 ", unperturbed " w[1]; bad = 1 }
          d = abs(wrap($7 - roll[got])); if (d > worst) worst = d
          if (d > 0.1) { print "FAIL: case " name ": POINT " got " roll " $7 ", unperturbed " roll[got]; bad = 1 }
          if (roll[got] != 0) mapped++ }
        END { if (got != n) { print "FAIL: case " name ": " got " POINTs, unperturbed " n; bad = 1 }
              printf "case %s (pin heights %s): %d POINTs (%d with a mapped roll), largest roll change %.4f deg (bound 0.1)\n", name, z, got, mapped, worst
              exit bad }' "$dir/want" "$dir/got"; then
        fails=1
    fi
done
[ $fails = 0 ] && echo "ok: jogged pins change no POINT's roll by more than 0.1 degree"
exit $fails
