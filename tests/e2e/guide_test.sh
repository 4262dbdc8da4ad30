#!/bin/sh
# SPDX-License-Identifier: MIT
# guide_test.sh DOC BINDIR...
#
# Runs a documentation page's examples as written and checks the outputs it shows. The
# page marks its fenced blocks with an HTML comment on the line before the fence:
#   <!-- session -->      this ```forth block starts a new fbrlmon session (the built-in
#                         emulator, lines piped in); later unmarked ```forth blocks are typed
#                         into the same session
#   <!-- file: NAME -->   the block is written to the file NAME
#   <!-- run -->          the ```sh block is run by sh
#   <!-- output -->       every line of the block must be a whole line of the output of the
#                         session or run block before it
# Everything runs in one temporary directory, in page order, with the BINDIRs (fbrlmon's,
# fbrlsim's) first on the PATH, as after scripts/install.sh. A session or run must end with
# status 0 and print nothing on standard error.
doc=$1
shift
for d in "$@"; do PATH=$(cd "$d" && pwd):$PATH; done
export PATH
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' INT TERM
mkdir "$tmp/units" "$tmp/work"

# Split the page into units: u/N.kind (session | run | file), u/N.body, u/N.want, u/N.name
awk -v dir="$tmp/units" '
    /^<!-- session -->$/ { mark = "session"; next }
    /^<!-- run -->$/     { mark = "run"; next }
    /^<!-- output -->$/  { mark = "output"; next }
    /^<!-- file: .* -->$/ { mark = "file"; name = $3; next }
    /^```/ && !on {
        on = 1; lang = substr($0, 4)
        if (mark == "session" || mark == "run" || mark == "file") {
            n++; unit = dir "/" n; target = unit ".body"
            printf "%s\n", mark > (unit ".kind"); close(unit ".kind")
            if (mark == "file") { printf "%s\n", name > (unit ".name"); close(unit ".name") }
            printf "" > target
        } else if (mark == "output" && n) {
            target = dir "/" n ".want"
        } else if (lang == "forth" && n && kind_of[n] == "session") {
            target = dir "/" n ".body"           # typed into the open session
        } else {
            target = ""
        }
        if (mark == "session" || mark == "run" || mark == "file") kind_of[n] = mark
        mark = ""; next
    }
    /^```$/ && on { on = 0; if (target != "") close(target); target = ""; next }
    on && target != "" { print >> target; next }
    { if ($0 != "") mark = "" }
' "$doc"

fails=0 units=0
cd "$tmp/work" || exit 1
for kind in $(ls "$tmp/units" | sed -n 's/\.kind$//p' | sort -n); do
    u=$tmp/units/$kind
    units=$((units + 1))
    case $(cat "$u.kind") in
    session) fbrlmon <"$u.body" >"$u.out" 2>"$u.err"; st=$? ;;
    run) sh "$u.body" </dev/null >"$u.out" 2>"$u.err"; st=$? ;; # not the terminal ctest may run at
    file) cp "$u.body" "$(cat "$u.name")"; continue ;;
    esac
    what="$(cat "$u.kind") $kind ($(head -n 1 "$u.body"))"
    [ $st = 0 ] || { echo "FAIL: $what: exit status $st"; fails=$((fails + 1)); }
    [ ! -s "$u.err" ] || { echo "FAIL: $what: $(cat "$u.err")"; fails=$((fails + 1)); }
    if [ -f "$u.want" ]; then
        while IFS= read -r line; do
            grep -Fxq -- "$line" "$u.out" && continue
            echo "FAIL: $what: the page shows a line it did not print: '$line'"
            fails=$((fails + 1))
        done <"$u.want"
    fi
    if [ $fails != 0 ]; then
        echo "--- its output:"; cat "$u.out"
        break
    fi
    echo "ok: $what"
done
[ $units -gt 0 ] || { echo "FAIL: $doc has no marked examples"; exit 1; }
[ $fails = 0 ] && echo "$doc: $units examples ran as shown"
exit $((fails != 0))
