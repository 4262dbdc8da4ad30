#!/bin/sh
# SPDX-License-Identifier: MIT
# abi-baseline.sh BUILD_DIR - write the shared library's ABI as the committed baseline
# abi/libfbrl.abi (after a deliberate, reviewed change; docs/abi.md).
# abi-baseline.sh --dump LIB OUT - the same representation of LIB into OUT (abi_check).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
if [ "$1" = "--dump" ]; then
    lib=$2 out=$3
else
    lib=$1/libfbrl.so out=$here/abi/libfbrl.abi
    mkdir -p "$here/abi"
fi
# Only the public headers' types; no paths or line numbers, so the file does not
# depend on where the tree was built.
abidw --no-corpus-path --no-comp-dir-path --no-show-locs --drop-private-types \
    --headers-dir "$here/include/fbrl" --headers-dir "$(dirname "$lib")/include/fbrl" \
    --out-file "$out.tmp" "$lib"
sed "s|path='$here/|path='|" "$out.tmp" >"$out"
rm -f "$out.tmp"
