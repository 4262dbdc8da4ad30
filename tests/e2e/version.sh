#!/bin/sh
# SPDX-License-Identifier: MIT
# version.sh VERSION PROGRAM... - every program answers --version (and -V) with
# "NAME (libfbrl) VERSION", VERSION being CMake's project version, and exits 0; and its
# --help fits an 80-column terminal.
want=$1
shift
fails=0
for prog in "$@"; do
    name=$(basename "$prog")
    for opt in --version -V; do
        out=$("$prog" "$opt" 2>&1)
        st=$?
        if [ "$st" != 0 ] || [ "$out" != "$name (libfbrl) $want" ]; then
            echo "FAIL: $name $opt: status $st, output '$out' (want '$name (libfbrl) $want')"
            fails=$((fails + 1))
        fi
    done
    wide=$("$prog" --help 2>&1 | awk 'length($0) > 80')
    if [ -n "$wide" ]; then
        echo "FAIL: $name --help is wider than 80 columns: $wide"
        fails=$((fails + 1))
    fi
done
echo "version: $# programs, $fails failed"
[ "$fails" = 0 ]
