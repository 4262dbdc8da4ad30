#!/bin/sh
# SPDX-License-Identifier: MIT
# svg_test.sh FBRLMON PYTHON SRC WORKDIR - the work cell's picture read as a person reads it
# (docs/workcell.md, "The picture"): svg_check.py parses the SVG and checks the frame, the
# labels, the scale bar, the legend, the racks and a refused motion against the cell files
# and the dry run's own report. Two pictures: tests/e2e/cell/picture.fbrl (a small, crowded
# cell with two racks and a move into a post) and the dry run of examples/sample_prep.fbrl.
mon=$1 py=$2 src=$3 work=$4
rm -rf "$work" && mkdir -p "$work/tmp" && cd "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

plan=$src/tests/e2e/cell/picture.fbrl
TMPDIR=$work/tmp "$mon" --dry-run --svg "$work/picture.svg" "$plan" >"$work/picture.out" 2>&1 </dev/null ||
    fail "the dry run of picture.fbrl failed: $(cat "$work/picture.out")"
# the obstacle the guard named, from the dry run's report (what the picture must name)
hit=$(sed -n 's/^refused: MOV: would hit \([A-Z-]*\) .*/\1/p' "$work/picture.out")
[ "$hit" = POST ] || fail "the dry run refused no move into POST: $(cat "$work/picture.out")"
"$py" "$src/tests/e2e/svg_check.py" "$work/picture.svg" "$plan" --refused "${hit:-POST}" ||
    fail "picture.fbrl's picture"

ex=$src/examples
TMPDIR=$work/tmp "$mon" --dry-run --svg "$work/sample_prep.svg" -e '600 CONSTANT TIME-SCALE' \
    --sim-inputs "$ex/tube_present.inputs" "$ex/sample_prep.fbrl" >"$work/sample_prep.out" 2>&1 </dev/null ||
    fail "the dry run of sample_prep.fbrl failed: $(cat "$work/sample_prep.out")"
"$py" "$src/tests/e2e/svg_check.py" "$work/sample_prep.svg" "$ex/asps_cell.fbrl" "$ex/asps_cell_objects.fbrl" ||
    fail "sample_prep.fbrl's picture"

[ "$fails" = 0 ] && echo "svg_test: ok" && exit 0
echo "svg_test: $fails failures"
exit 1
