#!/bin/sh
# mon_input.sh FBRLMON WORKDIR - input fbrlmon cannot read to an end is refused or bounded
# (issue 20 item 4): /dev/zero and a FIFO with no writer, as a plan FILE and through
# INCLUDED, are refused with a clear message; stdin with no line end and a file with an
# over-long line stop at the limit and name the line. Each case must end within a second
# (measured; each run is also killed after 10 s so a hang fails instead of blocking).
mon=$1 work=$2
rm -rf "$work" && mkdir -p "$work" || exit 2
cd "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
now_ms() { date +%s%3N; }

# run NAME EXPECTED-STATUS PATTERN [STDIN] -- ARGS: fbrlmon's stderr must match PATTERN
run() {
    name=$1 want=$2 pat=$3 in=$4
    shift 4
    t0=$(now_ms)
    timeout 10 "$mon" --offline "$@" <"$in" >"$name.out" 2>"$name.err"
    st=$?
    ms=$(($(now_ms) - t0))
    [ $st = 124 ] && { fail "$name: still reading after 10 s"; return; }
    [ $st = "$want" ] || fail "$name: exit status $st, expected $want"
    [ -z "$pat" ] || grep -q -- "$pat" "$name.err" || fail "$name: no message matching '$pat' (stderr: $(head -c 300 "$name.err"))"
    [ "$ms" -lt 1000 ] || fail "$name: took $ms ms (bound 1000)"
    echo "$name: $ms ms, status $st: $(head -n 2 "$name.err" | tr '\n' ' ')"
}

mkfifo fifo || exit 2
printf '1 2 + .\n' >ok.fs
awk 'BEGIN { printf "1 .\n2 .\n"; for (i = 0; i < 100000; i++) printf "x"; printf "\n3 .\n" }' >long.fs
printf '1 .\n2 .\n%s' "$(head -c 3000 /dev/zero | tr '\0' 'y')" >noend.fs

run dev_zero_file 1 'cannot open /dev/zero: not a regular file' /dev/null /dev/zero
run dev_zero_included 1 '-e:1: error: cannot open /dev/zero: not a regular file.* in INCLUDED' /dev/null \
    -e 'S" /dev/zero" INCLUDED'
run fifo_file 1 "cannot open $work/fifo: not a regular file" /dev/null "$work/fifo"
run fifo_included 1 'cannot open fifo: not a regular file.* in INCLUDED' /dev/null -e 'S" fifo" INCLUDED'
run directory 1 'cannot open .: not a regular file' /dev/null .
run long_line 1 'long.fs:3: error: input line too long' /dev/null long.fs
grep -q '^1 2 $' long_line.out || fail "long_line: lines 1 and 2 should run before the long line (got: $(cat long_line.out))"
grep -q '3' long_line.out && fail "long_line: line 4 ran after the long line stopped the file"
run no_line_end 1 'noend.fs:3: error: input line too long' /dev/null noend.fs
run stdin_zero 1 'stdin:1: error: input stopped: line 1 has no end within 1048576 bytes' /dev/zero
# a regular plan still runs
run regular 0 '' /dev/null ok.fs
grep -q '^3 $' regular.out || fail "regular: ok.fs printed '$(cat regular.out)'"

[ $fails = 0 ] && echo "ok: every endless or blocking input refused or bounded within a second"
[ $fails = 0 ]
