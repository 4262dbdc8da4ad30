#!/bin/sh
# SPDX-License-Identifier: MIT
# with_de.sh LOCDIR CMD [ARG...]
#
# Runs CMD with LC_ALL=de_DE.UTF-8 (decimal comma), the locale under which libfbrl once
# read "1.5E0" as an undefined word and printed "+14,5000". scripts/deps.sh generates the
# locale for the system; where it is missing this generates it into LOCDIR (LOCPATH) from
# the system's locale sources. Exit 77 (ctest: skipped) only if it truly cannot be made.
locdir=$1
shift
comma() { LC_ALL=de_DE.UTF-8 locale -k decimal_point 2>/dev/null | grep -q '^decimal_point=","$'; }
if ! comma; then
    if [ ! -d "$locdir/de_DE.UTF-8" ]; then
        mkdir -p "$locdir"
        localedef -i de_DE -f UTF-8 "$locdir/de_DE.UTF-8" >"$locdir/localedef.log" 2>&1 || true
    fi
    LOCPATH=$locdir
    export LOCPATH
    if ! comma; then
        echo "SKIP: the de_DE.UTF-8 locale cannot be generated here (localedef: $(tail -n 1 "$locdir/localedef.log" 2>/dev/null));"
        echo "      install the 'locales' package (scripts/deps.sh does it and generates de_DE.UTF-8)"
        exit 77
    fi
fi
LC_ALL=de_DE.UTF-8
export LC_ALL
exec "$@"
