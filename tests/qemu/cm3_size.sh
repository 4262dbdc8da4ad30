#!/bin/sh
# SPDX-License-Identifier: MIT
# cm3_size.sh REPORT
#
# The firmware's size report (ports/cortex-m3/size-report.awk) against its budgets, so that
# the image cannot grow past them unnoticed: flash within 192 KB of the LM3S6965's 256 KB,
# RAM within its 64 KB (docs/firmware.md, section 4). The dictionary's 16 KB at boot is
# checked by the QEMU tests (qemu_cm3_plan, qemu_cm3_cell), which boot the image.
report=$1
[ $# -eq 1 ] || { echo "usage: cm3_size.sh REPORT"; exit 2; }
[ -s "$report" ] || { echo "FAIL: no size report $report (build the fbrl_cm3 target)"; exit 1; }
flash=$(sed -n 's/^flash \([0-9]*\) bytes.*: \([A-Za-z]*\) (.*/\1 \2/p' "$report")
ram=$(sed -n 's/^RAM \([0-9]*\) bytes.*: \([A-Za-z]*\) (.*/\1 \2/p' "$report")
# shellcheck disable=SC2086 # the two figures and their verdicts, as four words
set -- $flash $ram
[ $# -eq 4 ] || { echo "FAIL: the size report has no flash and RAM verdicts"; exit 1; }
fails=0
[ "$2" = within ] || { echo "FAIL: flash $1 bytes, over its budget"; fails=1; }
[ "$4" = within ] || { echo "FAIL: RAM $3 bytes, over its budget"; fails=1; }
[ $fails = 0 ] && echo "ok: flash $1 bytes and RAM $3 bytes within their budgets"
exit $fails
