# SPDX-License-Identifier: MIT
# cm3_lib.sh - shared by the Cortex-M3 firmware tests (cm3_plan.sh, cm3_faults.sh).

# run_fw QEMU IMAGE PORT TYPED OUT DEADLINE_S: boot the image with UART0 on stdio and UART1
# on PORT, type the file TYPED at the console once the firmware has greeted (as a person
# would: a byte sent before the UART is enabled is not received, on the chip as under
# QEMU), and wait for QEMU to exit (the text ends with BYE: a reset, which -no-reboot
# turns into an exit). Returns QEMU's status, 124 past the deadline.
run_fw() {
    _fifo=$5.in
    rm -f "$_fifo" && mkfifo "$_fifo" || return 2
    timeout "$6" "$1" -M lm3s6965evb -kernel "$2" -display none -monitor none -no-reboot \
        -serial stdio -serial "$3" <"$_fifo" >"$5" 2>"$5.err" &
    _qpid=$!
    exec 9>"$_fifo"
    _i=0
    while ! grep -a -q 'the controller on UART1' "$5" 2>/dev/null && [ $_i -lt 300 ]; do
        kill -0 $_qpid 2>/dev/null || break
        sleep 0.1
        _i=$((_i + 1))
    done
    cat "$4" >&9
    exec 9>&-
    wait $_qpid
    _st=$?
    rm -f "$_fifo"
    return $_st
}
