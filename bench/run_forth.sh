#!/bin/sh
# run_forth.sh - time the standard-Forth benchmarks in bench/forth/ in fbrlmon,
# pforth and gforth, and print a table of best-of-N times and ratios.
#
#   bench/run_forth.sh [BUILD_DIR]     (default: build; env RUNS=3, GEN_DEFS=10000)
#
# Every benchmark prints a checksum; the runner compares the systems' answers so
# a fast wrong result does not count. Times include process start-up (a few ms).
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=${1:-$root/build}
runs=${RUNS:-3}
fbrlmon=$build/apps/fbrlmon
[ -x "$fbrlmon" ] || { echo "run_forth.sh: $fbrlmon not built" >&2; exit 2; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/fbrlbench.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM
"$here/forth/gen_source.sh" "${GEN_DEFS:-10000}" > "$tmp/compile.fs"

# run SYSTEM FILE: evaluate FILE in SYSTEM with no terminal input; stdout only.
# (gforth gets an absolute path: it would otherwise prefer its own library
# files of the same name.)
run() {
    case $1 in
    fbrlmon) "$fbrlmon" --offline "$2" </dev/null ;;
    pforth)  pforth -q "$2" </dev/null ;;
    gforth)  gforth "$2" -e bye </dev/null ;;
    esac
}

now_ns() { date +%s%N; }

# best SYSTEM FILE: best wall time of $runs runs in ms (3 decimals); sets $out.
best() {
    b=
    i=0
    while [ "$i" -lt "$runs" ]; do
        t0=$(now_ns)
        out=$(run "$1" "$2" 2>"$tmp/err") || { echo "FAILED"; return; }
        t1=$(now_ns)
        dt=$((t1 - t0))
        if [ -z "$b" ] || [ "$dt" -lt "$b" ]; then b=$dt; fi
        i=$((i + 1))
    done
    echo "$b"
}

systems=fbrlmon
for s in pforth gforth; do
    command -v "$s" >/dev/null 2>&1 && systems="$systems $s"
done

printf '%-10s' benchmark
for s in $systems; do printf ' %12s' "$s ms"; done
for s in $systems; do [ "$s" = fbrlmon ] || printf ' %15s' "fbrlmon/$s"; done
printf '  %s\n' answer
slow=
for f in "$here"/forth/*.fs "$tmp/compile.fs"; do
    name=$(basename "$f" .fs)
    line=$(printf '%-10s' "$name")
    ratios=
    answer=
    agree=yes
    fbrl_ns=
    for s in $systems; do
        ns=$(best "$s" "$f")
        o=$(run "$s" "$f" 2>/dev/null | tr -s ' \n' ' ' | sed 's/ *$//')
        if [ "$s" = fbrlmon ]; then answer=$o; fi
        [ "$o" = "$answer" ] || agree="NO ($s: $o)"
        if [ "$ns" = FAILED ]; then
            line="$line $(printf ' %12s' FAILED)"
            [ "$s" = fbrlmon ] && fbrl_ns=
            continue
        fi
        line="$line $(printf ' %12s' "$(awk -v n="$ns" 'BEGIN{printf "%.1f", n/1e6}')")"
        if [ "$s" = fbrlmon ]; then
            fbrl_ns=$ns
        elif [ -n "$fbrl_ns" ]; then
            r=$(awk -v a="$fbrl_ns" -v b="$ns" 'BEGIN{printf "%.2f", a/b}')
            ratios="$ratios $(printf ' %15s' "$r")"
            if [ "$s" = pforth ] && awk -v r="$r" 'BEGIN{exit !(r >= 1)}'; then
                slow="$slow $name(x$r)"
            fi
        else
            ratios="$ratios $(printf ' %15s' -)"
        fi
    done
    if [ "$agree" = yes ]; then
        printf '%s%s  %s\n' "$line" "$ratios" "$answer"
    else
        printf '%s%s  %s  MISMATCH: %s\n' "$line" "$ratios" "$answer" "$agree"
    fi
done
echo "(best of $runs runs, wall time incl. start-up; ratio < 1 means fbrlmon is faster)"
if [ -n "$slow" ]; then
    echo "fbrlmon is not faster than pforth on:$slow"
fi
