#!/bin/sh
# SPDX-License-Identifier: MIT
# xarm_sync.sh FBRLSIM XARM_CLIENT WORKDIR - the York Xarm client (tests/e2e/xarm_client.c)
# against fbrlsim on a pty, as it would open a serial port: every one of its 23 commands must
# read its own reply (fbrlsim sends nothing that nobody typed for).
sim=$1 client=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
"$sim" --time-scale 50 --log sim.log >sim.out 2>sim.err &
simpid=$!
trap 'kill $simpid 2>/dev/null' EXIT
i=0
while [ ! -s sim.out ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
"$client" "$(head -n 1 sim.out)"
