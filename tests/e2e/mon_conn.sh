#!/bin/sh
# SPDX-License-Identifier: MIT
# mon_conn.sh FBRLMON FBRLSIM TMPDIR - fbrlmon's controller connection: --port to a
# real fbrlsim process on a pty (its log proves the handshake reached it), line
# settings, a controller in ACI mode, the built-in emulator (--sim, the default),
# --offline, --list-ports, and the failures: bad values (status 2), ports that cannot open (status 3).
mon=$1
sim=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
fails=0
count=0

fail() { fails=$((fails + 1)); echo "FAIL: $*"; echo "  stdout: $(cat out.txt)"; echo "  stderr: $(cat err.txt)"; }

# expect NAME STATUS STDOUT ARG... (stdin is empty)
expect() {
    name=$1 want_st=$2 want_out=$3
    shift 3
    count=$((count + 1))
    "$mon" "$@" </dev/null >out.txt 2>err.txt
    st=$?
    if [ "$st" != "$want_st" ] || { [ "$want_out" != "*" ] && [ "$(cat out.txt)" != "$want_out" ]; }; then
        fail "$name: status $st (want $want_st)"
    fi
}

# A real emulator process on a pty, logging every command it executes.
rm -f sim.log sim.out
"$sim" --log "$tmp/sim.log" >sim.out 2>sim.err &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
i=0
while [ ! -s sim.out ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
port=$(head -n 1 sim.out)
case $port in
/dev/*) ;;
*) echo "FAIL: fbrlsim printed no device path: $(cat sim.out sim.err)"; exit 1 ;;
esac

expect "--port to fbrlsim" 0 "3 " --port "$port" -e '1 2 + .'
grep -q '^NOHELP' sim.log || fail "the handshake did not reach the emulator (log: $(cat sim.log))"
n1=$(grep -c '^NOHELP' sim.log)
expect "--port with line settings" 0 "4 " --port "$port" --baud 2400 --data-bits 7 --parity even \
    --stop-bits 2 --flow none -e '4 .'
[ "$(grep -c '^NOHELP' sim.log)" -gt "$n1" ] || fail "second handshake missing from the log"
expect "--port with --parity O" 0 "5 " --port "$port" --parity O -e '5 .'

# A plan moving the arm through robot words: the emulator executes the RAPL
# commands (its log) and the position read back lands in a host location.
cat >plan.fbrl <<'PLAN'
HOME READY
CREATE-LOC T1  12E0 3E0 8E0 0E0 -90E0 0E0 T1 DEFINE-LOC
T1 MOV
CREATE-LOC NOW  NOW ARM-HERE  NOW GETX F>S .  NOW GETY F>S .  NOW GETZ F>S .
PLAN
expect "robot words over --port" 0 "12 3 8 " --port "$port" "$tmp/plan.fbrl"
grep -q '^MOVE FBRLT1' sim.log || fail "MOVE did not reach the emulator (log: $(cat sim.log))"

# RECONNECT inside a logged run: the session's modes are sent again (docs/link.md 1,
# "Modes") and the run log says so in a note, beside the lines as commands
rm -f modes.jsonl modes.jsonl.head # a run log is a chain with its head file (docs/compliance.md)
cat >modes.fbrl <<'PLAN'
RUN-LOG modes.jsonl
: FAST ( -- ) 30 SPEED  40 SPEED ;
METHOD MODES  a speed, then a reconnect
' FAST STEP Fast  the speed
' RECONNECT STEP Again  a reconnect
END-METHOD
MODES RUN-METHOD
PLAN
before=$(grep -vc '^#' sim.log)
expect "RECONNECT in a logged run" 0 "*" --port "$port" "$tmp/modes.fbrl"
grep -q "^the session's modes sent again: SPEED 40$" out.txt || fail "RECONNECT did not say it sent SPEED 40"
[ "$(tail -n +$((before + 1)) sim.log | grep -v '^#' | tr '\n' ' ')" = "NOHELP STATUS STATUS SPEED 30 SPEED 40 NOHELP STATUS SPEED 40 STATUS STATUS " ] ||
    fail "the controller's log: $(tail -n +$((before + 1)) sim.log | tr '\n' ' ')"
python3 - <<'PY' || fail "the run log: $(cat modes.jsonl)"
import json
recs = [json.loads(l) for l in open("modes.jsonl")]
notes = [r for r in recs if r["type"] == "note" and r["event"] == "modes-resent"]
assert len(notes) == 1 and notes[0]["text"] == "SPEED 40", notes
cmds = [r["line"] for r in recs if r["type"] == "command"]
# the run's STATUS (the controller's version), the step, the reconnect: handshake, the
# mode sent again, then the state it tells (STATUS read twice, as every value read)
assert cmds == ["STATUS", "SPEED 30", "SPEED 40", "NOHELP", "STATUS", "SPEED 40", "STATUS", "STATUS"], cmds
PY

# A stable name as udev makes it (/dev/serial/by-id/...): a symlink to the emulator's pty.
mkdir -p by-id
byid=$tmp/by-id/usb-FTDI_FT232R_USB_UART_A12345-if00-port0
ln -sf "$port" "$byid"
n1=$(grep -c '^HOME' sim.log)
expect "--port /dev/serial/by-id/... (a symlink)" 0 "7 " --port "$byid" -e 'HOME 7 .'
[ "$(grep -c '^HOME' sim.log)" -gt "$n1" ] || fail "HOME over the by-id name did not reach the emulator"
kill $simpid
wait $simpid 2>/dev/null

# The same over TCP (a serial server): fbrlsim --tcp 0 prints tcp:127.0.0.1:PORT.
rm -f tcp.log tcp.out
"$sim" --tcp 0 --log "$tmp/tcp.log" >tcp.out 2>tcp.err &
tcppid=$!
trap 'kill $simpid $tcppid 2>/dev/null' EXIT
i=0
while [ ! -s tcp.out ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
tcpport=$(head -n 1 tcp.out)
case $tcpport in
tcp:*)
    expect "--port tcp:HOST:PORT" 0 "10 " --port "$tcpport" -e '10 .'
    grep -q '^NOHELP' tcp.log || fail "the handshake did not reach the emulator over TCP" ;;
*) fail "fbrlsim --tcp printed no address: $(cat tcp.out tcp.err)" ;;
esac
kill $tcppid
wait $tcppid 2>/dev/null

# A controller that powers up in ACI mode (fbrlsim --aci) echoes nothing typed: fbrlmon
# switches it to terminal mode by itself (docs/link.md) and says so; the switch is in the
# emulator's log before the handshake, and the robot words work.
rm -f aci.log aci.out
"$sim" --aci --log "$tmp/aci.log" >aci.out 2>aci.err &
acipid=$!
trap 'kill $simpid $tcppid $acipid 2>/dev/null' EXIT
i=0
while [ ! -s aci.out ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
aciport=$(head -n 1 aci.out)
expect "--port to a controller in ACI mode" 0 "12 " --port "$aciport" -e 'HOME READY 12 .'
[ "$(sed -n 1p aci.log)" = "# ACI: TERMINAL MODE" ] && [ "$(sed -n 2p aci.log)" = NOHELP ] &&
    grep -qx READY aci.log || fail "ACI: want the switch, then NOHELP, then the commands (log: $(cat aci.log))"
kill $acipid
wait $acipid 2>/dev/null

expect "--port that does not exist" 3 "" --port "$tmp/no-such-port" -e '1 .'
grep -q 'cannot open' err.txt || fail "no 'cannot open' message"
: >plainfile
expect "--port that is not a terminal" 3 "" --port "$tmp/plainfile" -e '1 .'
grep -q 'not a terminal' err.txt || fail "no 'not a terminal' message"
expect "--port tcp: without a server" 3 "" --port tcp:127.0.0.1:1 -e '1 .'

expect "--baud not a number" 2 "" --baud fast
expect "--baud missing" 2 "" --baud
expect "--data-bits 9" 2 "" --data-bits 9
expect "--stop-bits 3" 2 "" --stop-bits 3
expect "--parity x" 2 "" --parity x
expect "--flow rts" 2 "" --flow rts
expect "--port missing" 2 "" --port

if "$mon" --help | grep -q -- '--sim '; then
    expect "--sim" 0 "6 " --sim -e '6 .'
    expect "robot words on the built-in emulator" 0 "12 3 8 " --sim "$tmp/plan.fbrl"
    expect "emulator is the default" 0 "7 " -e '7 .'
    expect "--sim-state keeps the emulator's memory" 0 "8 " --sim --sim-state "$tmp/sim.state" -e '8 .'
    [ -s "$tmp/sim.state" ] || fail "--sim-state: no state file written"
    printf '# input 3 on from the start\n0 IN 3 1\n' >"$tmp/sim.inputs"
    expect "--sim-inputs sets the emulator's inputs" 0 "-1 0 " --sim-inputs "$tmp/sim.inputs" \
        -e '3 INPUT-DEVICE T3  4 INPUT-DEVICE T4  T3 INPUT? . T4 INPUT? .'
    expect "--sim-inputs: a missing file stops fbrlmon" 3 "" --sim-inputs "$tmp/no-such.inputs" -e '1 .'
    grep -q 'cannot start the emulator' err.txt || fail "--sim-inputs missing: want 'cannot start the emulator'"
fi
expect "--offline" 0 "9 " --offline -e '9 .'
expect "robot words offline: one clear error" 1 "" --offline -e 'HOME'
grep -q '^-e:1: error: no controller connected' err.txt && [ "$(wc -l <err.txt)" = 1 ] ||
    fail "offline HOME: want one 'no controller connected' line"
count=$((count + 1))
"$mon" --list-ports >out.txt 2>err.txt
st=$?
if [ $st != 0 ] && ! { [ $st = 3 ] && grep -q 'without libserialport' err.txt; }; then
    fail "--list-ports: status $st"
fi

# --list-ports in fake sysfs and /dev trees: an FTDI adapter with its by-id name, VID:PID,
# product and serial number; a CDC-ACM board; no absent 8250 UART, no console
fake=$tmp/fake
rm -rf "$fake"
mkdir -p "$fake/sys/devices/usb1/1-1/1-1:1.0/ttyUSB0" "$fake/sys/devices/usb1/1-2/1-2:1.0" \
    "$fake/sys/class/tty/ttyUSB0" "$fake/sys/class/tty/ttyACM0" "$fake/sys/class/tty/ttyS3" \
    "$fake/sys/class/tty/tty1" "$fake/dev/serial/by-id"
printf '0403\n' >"$fake/sys/devices/usb1/1-1/idVendor"
printf '6001\n' >"$fake/sys/devices/usb1/1-1/idProduct"
printf 'FT232R USB UART\n' >"$fake/sys/devices/usb1/1-1/product"
printf 'A12345\n' >"$fake/sys/devices/usb1/1-1/serial"
printf '2341\n' >"$fake/sys/devices/usb1/1-2/idVendor"
printf '0043\n' >"$fake/sys/devices/usb1/1-2/idProduct"
printf '0\n' >"$fake/sys/class/tty/ttyS3/type"
ln -s "$fake/sys/devices/usb1/1-1/1-1:1.0/ttyUSB0" "$fake/sys/class/tty/ttyUSB0/device"
ln -s "$fake/sys/devices/usb1/1-2/1-2:1.0" "$fake/sys/class/tty/ttyACM0/device"
ln -s "$fake/sys/devices/usb1" "$fake/sys/class/tty/ttyS3/device"
: >"$fake/dev/ttyUSB0"
: >"$fake/dev/ttyACM0"
ln -s ../../ttyUSB0 "$fake/dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A12345-if00-port0"
count=$((count + 1))
FBRLMON_SYSFS_ROOT=$fake/sys FBRLMON_DEV_ROOT=$fake/dev "$mon" --list-ports >out.txt 2>err.txt
st=$?
want1="$fake/dev/ttyACM0  [USB 2341:0043]"
want2="$fake/dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A12345-if00-port0  ($fake/dev/ttyUSB0)  FT232R USB UART  [USB 0403:6001]  serial A12345"
if [ $st != 0 ] || [ "$(sed -n 1p out.txt)" != "$want1" ] || [ "$(sed -n 2p out.txt)" != "$want2" ] ||
    [ "$(wc -l <out.txt)" != 2 ]; then
    fail "--list-ports in fake trees: status $st; want lines '$want1' and '$want2'"
fi

echo "mon_conn: $count runs, $fails failed"
[ "$fails" = 0 ]
