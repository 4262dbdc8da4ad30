# SPDX-License-Identifier: MIT
# sim_pty.sh - sourced by e2e shell tests that drive a real fbrlsim on a pty:
# start_sim LOG [fbrlsim options] starts a fresh emulator logging to $tmp/LOG and sets
# $port to its pty; stop_sim ends it. The caller sets $sim (fbrlsim) and $tmp (its folder,
# the current directory).
simpid=
start_sim() {
    log=$1
    shift
    rm -f sim.out # a stale path from an emulator that was killed must not be read
    "$sim" --log "$tmp/$log" "$@" >sim.out 2>sim.err &
    simpid=$!
    i=0
    while [ ! -s sim.out ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
    port=$(head -n 1 sim.out)
    case $port in
    /dev/*) ;;
    *) echo "FAIL: fbrlsim printed no device path: $(cat sim.out sim.err)"; exit 1 ;;
    esac
}
stop_sim() { kill "$simpid" 2>/dev/null; wait "$simpid" 2>/dev/null; rm -f sim.out; }
trap 'kill $simpid 2>/dev/null' EXIT
