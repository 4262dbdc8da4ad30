#!/bin/sh
# SPDX-License-Identifier: MIT
# cm3_size.sh REPORT FLASH_CEILING
#
# The firmware's size report (ports/cortex-m3/size-report.awk) against its budgets, so that
# the image cannot grow unnoticed: RAM must be within its 64 KB budget (the linker already
# refuses more). Flash must be within its 128 KB budget; while it is over (docs/firmware.md,
# section 4), it must at least stay under FLASH_CEILING, the figure of this version with a
# little room, which is lowered as the image shrinks.
report=$1 ceiling=$2
[ $# -eq 2 ] || { echo "usage: cm3_size.sh REPORT FLASH_CEILING"; exit 2; }
[ -s "$report" ] || { echo "FAIL: no size report $report (build the fbrl_cm3 target)"; exit 1; }
flash=$(sed -n 's/^flash \([0-9]*\) bytes.*: \([A-Za-z]*\) (.*/\1 \2/p' "$report")
ram=$(sed -n 's/^RAM \([0-9]*\) bytes.*: \([A-Za-z]*\) (.*/\1 \2/p' "$report")
# shellcheck disable=SC2086 # the two figures and their verdicts, as four words
set -- $flash $ram
[ $# -eq 4 ] || { echo "FAIL: the size report has no flash and RAM verdicts"; exit 1; }
fails=0
if [ "$4" != within ]; then
    echo "FAIL: RAM $3 bytes, over its budget"
    fails=1
fi
if [ "$2" = within ]; then
    echo "flash $1 bytes: within its budget"
elif [ "$1" -gt "$ceiling" ]; then
    echo "FAIL: flash $1 bytes, over its budget and past this version's ceiling of $ceiling"
    fails=1
else
    echo "flash $1 bytes: over its budget, under the ceiling of $ceiling"
fi
[ $fails = 0 ] && echo "ok: RAM $3 bytes within its budget"
exit $fails
