#!/bin/sh
# SPDX-License-Identifier: MIT
# run_forth.sh - FBRL's Forth engine (fbrlmon) beside gforth-fast, gforth and
# pforth: start-up time and peak memory, then the standard-Forth benchmarks in
# bench/forth/ with best-of-N times, each ratio the median of N rounds (the systems
# in turn), and the ratios' geometric mean.
#
#   bench/run_forth.sh [BUILD_DIR]   (default: build; env RUNS=5, STARTS=20, GEN_DEFS=10000)
#
# Every benchmark prints a checksum; the runner compares the systems' answers so
# a fast wrong result does not count. gforth's own siev, bubble, matrix and fib
# (gf-*, from Debian's gforth package when installed) run beside bench/forth/.
# Benchmark times are wall times of the whole process (start-up included; it is
# printed first, and is a few ms). The geometric mean covers the compute-bound
# programs, not the compile benchmark. Run it on an
# idle machine: other load shows up as noise.
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=${1:-$root/build}
runs=${RUNS:-5}
starts=${STARTS:-20}
fbrlmon=$build/apps/fbrlmon
[ -x "$fbrlmon" ] || { echo "run_forth.sh: $fbrlmon not built" >&2; exit 2; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/fbrlbench.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM
"$here/forth/gen_source.sh" "${GEN_DEFS:-10000}" > "$tmp/compile.fs"
: > "$tmp/empty.fs"

# gforth's own benchmarks (siev, bubble, matrix, fib; GPL, shipped by Debian's gforth
# package, so run from there, not copied): each loaded, its `main` run, then a check line
# printed, so the systems' answers can be compared. gf-NAME.fs in $tmp; none without gforth.
gfdir=$(ls /usr/share/gforth/*/siev.fs 2>/dev/null | sort | tail -n 1)
gfdir=${gfdir%siev.fs}
gforth_own=
gfbench() { # NAME CHECK
    [ -n "$gfdir" ] && [ -f "$gfdir$1.fs" ] || return 0
    printf 'include %s\nmain\n%s\n' "$gfdir$1.fs" "$2" > "$tmp/gf-$1.fs"
    gforth_own="$gforth_own $tmp/gf-$1.fs"
}
gfbench siev 'primes . cr'
gfbench bubble 'list @ . list elements 1- cells + @ . cr'
gfbench matrix 'imr @ . imr mat-size 1- cells + @ . cr'
gfbench fib '20 fib . cr'

# run SYSTEM FILE: evaluate FILE in SYSTEM with no terminal input; stdout only.
# (gforth gets an absolute path: it would otherwise prefer its own library
# files of the same name.)
run() {
    case $1 in
    fbrlmon) "$fbrlmon" --offline "$2" </dev/null ;;
    fbrlmon-sim) "$fbrlmon" "$2" </dev/null ;;
    pforth)  pforth -q "$2" </dev/null ;;
    gforth|gforth-fast) "$1" "$2" -e bye </dev/null ;;
    esac
}

now_ns() { date +%s%N; }

# timed SYSTEM FILE: the wall time of one run in ns, or FAILED.
timed() {
    t0=$(now_ns)
    run "$1" "$2" >/dev/null 2>"$tmp/err" || { echo FAILED; return; }
    t1=$(now_ns)
    echo $((t1 - t0))
}

# startup SYSTEM: ms per run of the empty program, best of 3 batches of $starts.
startup() {
    b=
    for batch in 1 2 3; do
        t0=$(now_ns)
        i=0
        while [ "$i" -lt "$starts" ]; do
            run "$1" "$tmp/empty.fs" >/dev/null 2>&1
            i=$((i + 1))
        done
        t1=$(now_ns)
        dt=$(( (t1 - t0) / starts ))
        if [ -z "$b" ] || [ "$dt" -lt "$b" ]; then b=$dt; fi
    done
    awk -v n="$b" 'BEGIN{printf "%.2f", n/1e6}'
}

# peak SYSTEM: maximum resident set size in MB of the empty program, the median of $peaks
# runs and their range: where the kernel places a program (ASLR) moves which 64 KB windows
# its code faults in, so one run can be 0.2 MB off its neighbour.
peaks=9
peak() {
    if [ -x /usr/bin/time ]; then
        : >"$tmp/rsses"
        i=0
        while [ "$i" -lt "$peaks" ]; do
            case $1 in
            fbrlmon) /usr/bin/time -f '%M' -o "$tmp/rss" "$fbrlmon" --offline "$tmp/empty.fs" </dev/null >/dev/null 2>&1 ;;
            fbrlmon-sim) /usr/bin/time -f '%M' -o "$tmp/rss" "$fbrlmon" "$tmp/empty.fs" </dev/null >/dev/null 2>&1 ;;
            pforth) /usr/bin/time -f '%M' -o "$tmp/rss" pforth -q "$tmp/empty.fs" </dev/null >/dev/null 2>&1 ;;
            *) /usr/bin/time -f '%M' -o "$tmp/rss" "$1" -e bye </dev/null >/dev/null 2>&1 ;;
            esac
            tail -n 1 "$tmp/rss" >>"$tmp/rsses"
            i=$((i + 1))
        done
        sort -n "$tmp/rsses" | awk '{ v[NR] = $1 } END {
            printf "%.2f (%.2f-%.2f)", v[int((NR + 1) / 2)] / 1024, v[1] / 1024, v[NR] / 1024 }'
    else
        printf -
    fi
}

others=
for s in gforth-fast gforth pforth; do
    command -v "$s" >/dev/null 2>&1 && others="$others $s"
done
[ -n "$others" ] || echo "(no gforth-fast, gforth or pforth installed: ./scripts/deps.sh gforth pforth)"

echo "start-up (empty program, best of 3 x $starts runs) and peak memory (max RSS, median of $peaks):"
printf '  %-22s %10s %18s\n' system "ms" "MB (min-max)"
for s in fbrlmon fbrlmon-sim $others; do
    case $s in
    fbrlmon) label="fbrlmon --offline" ;;
    fbrlmon-sim) label="fbrlmon (emulator)" ;;
    *) label=$s ;;
    esac
    printf '  %-22s %10s %18s\n' "$label" "$(startup "$s")" "$(peak "$s")"
done
echo

systems="fbrlmon$others"
printf '%-10s' benchmark
for s in $systems; do printf ' %12s' "$s"; done
for s in $others; do printf ' %14s' "/$s"; done
printf '  %s\n' answer
slow=
logsum=
nlog=0
for f in "$here"/forth/*.fs $gforth_own "$tmp/compile.fs"; do
    name=$(basename "$f" .fs)
    line=$(printf '%-10s' "$name")
    ratios=
    answer=
    agree=yes
    fbrl_ok=
    # the systems in turn, $runs rounds (A B C A B C ...): a drift of the machine's speed
    # reaches every system alike, and each round gives fbrlmon's time against each other's
    ran=
    for s in $systems; do
        case $name:$s in
        gf-*:pforth) ;; # pforth reports each include on stdout: no answer to compare, not asked for
        *) ran="$ran $s"; : > "$tmp/ns.$s" ;;
        esac
    done
    i=0
    while [ "$i" -lt "$runs" ]; do
        for s in $ran; do timed "$s" "$f" >> "$tmp/ns.$s"; done
        i=$((i + 1))
    done
    for s in $systems; do
        case " $ran " in
        *" $s "*) ;;
        *) line="$line $(printf ' %12s' -)"; ratios="$ratios $(printf ' %14s' -)"; continue ;;
        esac
        o=$(run "$s" "$f" 2>/dev/null | tr -s ' \n' ' ' | sed 's/ *$//')
        if [ "$s" = fbrlmon ]; then answer=$o; fi
        [ "$o" = "$answer" ] || agree="NO ($s: $o)"
        if grep -q FAILED "$tmp/ns.$s"; then
            line="$line $(printf ' %12s' FAILED)"
            [ "$s" = fbrlmon ] && fbrl_ok=
            [ "$s" = fbrlmon ] || ratios="$ratios $(printf ' %14s' -)"
            continue
        fi
        line="$line $(printf ' %12s' "$(sort -n "$tmp/ns.$s" | awk 'NR == 1 {printf "%.1f", $1/1e6}')")"
        if [ "$s" = fbrlmon ]; then
            fbrl_ok=yes
        elif [ -n "$fbrl_ok" ]; then
            # the median of the rounds' ratios
            r=$(paste "$tmp/ns.fbrlmon" "$tmp/ns.$s" | awk '{print $1/$2}' | sort -g |
                awk '{v[NR] = $1} END {printf "%.2f", NR % 2 ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}')
            ratios="$ratios $(printf ' %14s' "$r")"
            if [ "$name" != compile ] && [ "$agree" = yes ]; then
                logsum="$logsum $s:$r"
            fi
            if [ "$s" = pforth ] && awk -v r="$r" 'BEGIN{exit !(r >= 1)}'; then
                slow="$slow $name(x$r)"
            fi
        else
            ratios="$ratios $(printf ' %14s' -)"
        fi
    done
    if [ "$agree" = yes ]; then
        printf '%s%s  %s\n' "$line" "$ratios" "$answer"
    else
        printf '%s%s  %s  MISMATCH: %s\n' "$line" "$ratios" "$answer" "$agree"
    fi
done
# geometric mean of fbrlmon/SYSTEM over the compute-bound benchmarks
printf '%-10s' geomean
for s in $systems; do printf ' %12s' ""; done
for s in $others; do
    g=$(printf '%s\n' $logsum | awk -F: -v s="$s" '$1 == s { l += log($2); n++ } END { if (n) printf "%.2f", exp(l / n); else printf "-" }')
    printf ' %14s' "$g"
done
printf '  %s\n' "(compute benchmarks; ratio < 1: fbrlmon is faster)"
echo "(times: ms, best of $runs runs, wall time incl. start-up; ratios: the median of $runs rounds' ratios, the systems run in turn)"
if [ -n "$slow" ]; then
    echo "fbrlmon is not faster than pforth on:$slow"
fi
