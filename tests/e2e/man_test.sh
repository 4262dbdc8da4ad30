#!/bin/sh
# SPDX-License-Identifier: MIT
# man_test.sh MANDIR PROGRAM... - the manual pages render with man -l (no groff
# warnings, NAME and SYNOPSIS there), and each program's page documents exactly the
# long options its --help lists (the two must not drift apart).
mandir=$1
shift
command -v man >/dev/null 2>&1 || { echo "man: man-db not installed: skipped"; exit 77; }
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }
for page in fbrlmon.1 fbrlsim.1 fbrl-dump.1 fbrl-users.1 fbrl-audit.1 fbrl-station.1 libfbrl.3; do
    f=$mandir/$page
    [ -f "$f" ] || { fail "$page was not built"; continue; }
    out=$(MANWIDTH=80 man --warnings -l -P cat "$f" 2>"$mandir/$page.err") || fail "man -l $page failed"
    [ -s "$mandir/$page.err" ] && fail "man -l $page warns: $(cat "$mandir/$page.err")"
    for section in NAME SYNOPSIS DESCRIPTION "SEE ALSO"; do
        printf '%s\n' "$out" | grep -q "^$section" || fail "$page has no $section"
    done
    name=${page%.*}
    printf '%s\n' "$out" | grep -q "^ *$name - " || fail "$page's NAME line does not start with '$name - '"
done
# long options: --help versus the page's OPTIONS
opts_help() { "$1" --help | grep -oE '^ +(-[a-zA-Z], )?--[a-z][a-z-]*' | grep -oE -- '--[a-z][a-z-]*' | sort -u; }
opts_man() { MANWIDTH=200 man -l -P cat "$1" 2>/dev/null | grep -oE '^ {7}(-[a-zA-Z], )?--[a-z][a-z-]*' |
    grep -oE -- '--[a-z][a-z-]*' | sort -u; }
for prog in "$@"; do
    name=$(basename "$prog")
    opts_help "$prog" >"$mandir/$name.help-opts"
    opts_man "$mandir/$name.1" >"$mandir/$name.man-opts"
    n=$(wc -l <"$mandir/$name.help-opts")
    [ "$n" -ge 3 ] || fail "$name --help lists only $n long options"
    if ! cmp -s "$mandir/$name.help-opts" "$mandir/$name.man-opts"; then
        fail "$name: --help and $name(1) list other options (< --help only, > man page only):"
        diff "$mandir/$name.help-opts" "$mandir/$name.man-opts" | grep '^[<>]'
    fi
    echo "man: $name: $n long options in --help and in $name(1)"
done
echo "man: 7 pages, $fails failures"
[ $fails = 0 ]
