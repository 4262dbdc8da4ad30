#!/bin/sh
# SPDX-License-Identifier: MIT
# abi_check.sh LIB BASELINE WORKDIR - the shared library's ABI against the committed
# baseline (abigail-tools: abidw, abidiff). An incompatible change (a removed or changed
# function, variable or type) fails; added functions are compatible and only reported.
# After a deliberate change: scripts/abi-baseline.sh BUILD_DIR (docs/abi.md).
# Exit 77 (skipped): no abigail-tools, no debug information, or another architecture.
lib=$1 base=$2 work=$3
command -v abidw >/dev/null 2>&1 && command -v abidiff >/dev/null 2>&1 || { echo "abi_check: abigail-tools not installed: skipped"; exit 77; }
[ -f "$base" ] || { echo "abi_check: no baseline $base"; exit 1; }
mkdir -p "$work" || exit 1
here=$(dirname "$0")
sh "$here/../../scripts/abi-baseline.sh" --dump "$lib" "$work/current.abi" || exit 1
arch() { sed -n "s/.*architecture='\([^']*\)'.*/\1/p" "$1" | head -1; }
if [ "$(arch "$base")" != "$(arch "$work/current.abi")" ]; then
    echo "abi_check: the baseline is for $(arch "$base"), this is $(arch "$work/current.abi"): skipped"
    exit 77
fi
grep -q "<function-decl" "$work/current.abi" || { echo "abi_check: no debug information in $lib: skipped"; exit 77; }
abidiff --no-show-locs "$base" "$work/current.abi" >"$work/diff.txt" 2>&1
st=$?
cat "$work/diff.txt"
# abidiff's status bits: 1 error, 2 usage, 4 ABI change, 8 incompatible ABI change
if [ $((st & 3)) -ne 0 ]; then
    echo "abi_check: abidiff failed (status $st)"
    exit 1
fi
if [ $((st & 8)) -ne 0 ]; then
    echo "abi_check: INCOMPATIBLE change against $base (status $st)"
    exit 1
fi
[ $((st & 4)) -ne 0 ] && echo "abi_check: compatible additions only (status $st)"
echo "abi_check: compatible with the baseline"
exit 0
