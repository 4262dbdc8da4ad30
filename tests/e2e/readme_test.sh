#!/bin/sh
# SPDX-License-Identifier: MIT
# readme_test.sh SRC BUILD FBRLMON FBRLSIM
#
# Runs what README.md tells a new user to run, reading it from README.md itself:
#   - the ```sh block's commands: ./scripts/run.sh (fbrlmon on the built-in emulator; the
#     Forth lines of the ```forth example block are typed into it) and ./scripts/test.sh
#     (the suite this test is part of: it must list the tests);
#   - every `./scripts/run.sh ARGS` in the text, with the same ARGS, from the source tree:
#     a --port PATH gets a real fbrlsim process on a pty in place of PATH (and the example
#     block as input); a plan runs unattended (standard input /dev/null);
#   - `./scripts/install.sh`: the install it performs, into a temporary prefix, must put
#     fbrlmon and fbrlsim on the PATH by name.
# The "install what is missing and build" part of the scripts is replaced by the binaries
# already built in BUILD; the fbrlmon invocations and the Forth lines are the README's.
# Checks: exit status 0, no error line, the example's location read back where it was
# defined, the plan's summary "prepared N of N samples" with every sample prepared.
src=$1 build=$2 mon=$3 sim=$4
case $mon in /*) ;; *) mon=$(pwd)/$mon ;; esac
case $sim in /*) ;; *) sim=$(pwd)/$sim ;; esac
readme=$src/README.md
tmp=$(mktemp -d)
simpid=
cleanup() { [ -n "$simpid" ] && kill "$simpid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
trap 'exit 1' INT TERM
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
# ok TEXT: says that a step passed, when it did (no failure since the step's `mark`)
mark() { marked=$fails; }
ok() { [ "$fails" = "$marked" ] && echo "ok: $*"; }
# the fenced block of kind $1 (```sh, ```forth), without the fences
block() { awk -v k="$1" '$0 == "```" k { on = 1; next } on && $0 == "```" { exit } on { print }' "$readme"; }

# ---- the example block
block forth >"$tmp/example.fth"
[ -s "$tmp/example.fth" ] || fail "README.md has no \`\`\`forth example block"
# where the example defines P (x y z before "P DEFINE-LOC"), to compare with Q read back there
set -- $(sed -n 's/.*CREATE-LOC P *\([-0-9.]*\) *\([-0-9.]*\) *\([-0-9.]*\) .* P DEFINE-LOC.*/\1 \2 \3/p' "$tmp/example.fth")
px=${1:-} py=${2:-} pz=${3:-}

# check_example NAME OUT ERR STATUS: the example block ran without error, Q is where P is
check_example() {
    [ "$4" = 0 ] || fail "$1: exit status $4"
    [ ! -s "$3" ] || fail "$1: error output: $(cat "$3")"
    if [ -n "$px" ]; then
        awk -v x="$px" -v y="$py" -v z="$pz" '
            $1 == "X" && $3 == "Y" && $5 == "Z" {
                if ($2 - x < 0.001 && x - $2 < 0.001 && $4 - y < 0.001 && y - $4 < 0.001 &&
                    $6 - z < 0.001 && z - $6 < 0.001) found = 1 }
            END { exit !found }' "$2" || fail "$1: Q DISPLAY-LOC does not show P's position $px $py $pz: $(cat "$2")"
    fi
}

# ---- the ```sh block: ./scripts/run.sh and ./scripts/test.sh
block sh | sed 's/#.*//' >"$tmp/commands"
n=0
while read -r cmd rest; do
    [ -n "$cmd" ] || continue
    n=$((n + 1))
    mark
    case $cmd in
    ./scripts/run.sh)
        [ -x "$src/scripts/run.sh" ] || fail "scripts/run.sh is not executable"
        (cd "$src" && eval "\"\$mon\" $rest" <"$tmp/example.fth" >"$tmp/run.out" 2>"$tmp/run.err")
        check_example "run.sh with the example block" "$tmp/run.out" "$tmp/run.err" $?
        ok "./scripts/run.sh $rest (example block on the built-in emulator)" ;;
    ./scripts/test.sh)
        [ -x "$src/scripts/test.sh" ] || fail "scripts/test.sh is not executable"
        grep -q ctest "$src/scripts/test.sh" || fail "scripts/test.sh does not run ctest"
        count=$(cd "$build" && ctest -N | sed -n 's/^Total Tests: //p')
        [ "${count:-0}" -gt 0 ] || fail "test.sh: ctest lists no tests"
        ok "./scripts/test.sh (ctest lists ${count:-0} tests)" ;;
    *) fail "unknown command in the README's sh block: $cmd $rest" ;;
    esac
done <"$tmp/commands"
[ $n = 2 ] || fail "the README's sh block should hold two commands, it holds $n"

# ---- `./scripts/run.sh ARGS` in the text
grep -o '`\./scripts/run\.sh [^`]*`' "$readme" | tr -d '`' | sed 's#^\./scripts/run\.sh ##' >"$tmp/runs"
[ -s "$tmp/runs" ] || fail "README.md shows no ./scripts/run.sh command with arguments"
i=0
while read -r args; do
    i=$((i + 1))
    mark
    case " $args " in
    *" --port "*)
        # a real controller's port: here a real fbrlsim process on a pty
        "$sim" --log "$tmp/sim$i.log" >"$tmp/sim$i.out" 2>"$tmp/sim$i.err" &
        simpid=$!
        k=0
        while [ ! -s "$tmp/sim$i.out" ] && [ $k -lt 300 ]; do sleep 0.1; k=$((k + 1)); done
        pty=$(head -n 1 "$tmp/sim$i.out")
        real=$(echo "$args" | sed 's/.*--port \([^ ]*\).*/\1/')
        args2=$(echo "$args" | sed "s#--port [^ ]*#--port $pty#")
        (cd "$src" && eval "\"\$mon\" $args2" <"$tmp/example.fth" >"$tmp/r$i.out" 2>"$tmp/r$i.err")
        check_example "run.sh $args" "$tmp/r$i.out" "$tmp/r$i.err" $?
        kill "$simpid" 2>/dev/null; wait "$simpid" 2>/dev/null; simpid=
        grep -q '^MOVE ' "$tmp/sim$i.log" || fail "run.sh $args: the emulator ran no MOVE"
        ok "./scripts/run.sh $args (fbrlsim on $pty in place of $real, example block)" ;;
    *)
        (cd "$src" && eval "\"\$mon\" $args" </dev/null >"$tmp/r$i.out" 2>"$tmp/r$i.err")
        st=$?
        [ $st = 0 ] || fail "run.sh $args: exit status $st"
        [ ! -s "$tmp/r$i.err" ] || fail "run.sh $args: error output: $(cat "$tmp/r$i.err")"
        if grep -q '^Calibration point' "$tmp/r$i.out"; then
            fail "run.sh $args: asks for calibration points in an unattended run"
        fi
        case $args in
        *sample_prep*)
            summary=$(grep '^prepared ' "$tmp/r$i.out")
            set -- $summary
            if [ "${2:-x}" != "${4:-y}" ] || [ "${2:-0}" = 0 ]; then
                fail "run.sh $args: '$summary' (want all samples prepared)"
                cat "$tmp/r$i.out"
            fi
            ok "./scripts/run.sh $args: $summary" ;;
        *) ok "./scripts/run.sh $args" ;;
        esac ;;
    esac
done <"$tmp/runs"

# ---- `./scripts/install.sh`: fbrlmon and fbrlsim on the PATH by name
mark
if grep -q '`\./scripts/install\.sh`' "$readme"; then
    [ -x "$src/scripts/install.sh" ] || fail "scripts/install.sh is not executable"
    grep -q 'cmake --install' "$src/scripts/install.sh" || fail "scripts/install.sh does not run cmake --install"
    cmake --install "$build" --prefix "$tmp/prefix" >/dev/null || fail "cmake --install failed"
    got=$(PATH="$tmp/prefix/bin:$PATH" fbrlmon --offline -e '6 7 * . BYE' 2>&1)
    [ "$got" = "42 " ] || fail "installed fbrlmon on the PATH printed '$got'"
    PATH="$tmp/prefix/bin:$PATH" fbrlsim --help >/dev/null 2>&1 || fail "installed fbrlsim --help failed"
    [ "$(PATH="$tmp/prefix/bin:$PATH" command -v fbrlsim)" = "$tmp/prefix/bin/fbrlsim" ] ||
        fail "fbrlsim is not found on the PATH after the install"
    ok "./scripts/install.sh (cmake --install; fbrlmon and fbrlsim found on PATH)"
else
    fail "README.md does not say how to put fbrlmon and fbrlsim on the PATH (./scripts/install.sh)"
fi

[ $fails = 0 ] && echo "README: every command and example ran as written"
exit $((fails != 0))
