# SPDX-License-Identifier: MIT
# QEMU tests of the bare-metal port (ports/pc-bare): boot the image with COM1 on a pty
# and push data through its interrupt-driven echo from the host, over the project's
# own POSIX backend with XON/XOFF, checking every byte. Needs qemu-system-i386 (TCG;
# no KVM). Each takes a few seconds.
if(TARGET fbrl_pcbare)
  find_program(FBRL_QEMU_I386 qemu-system-i386)
  if(FBRL_QEMU_I386)
    add_executable(pcbare_echo ${CMAKE_CURRENT_SOURCE_DIR}/qemu/pcbare_echo.c)
    target_compile_definitions(pcbare_echo PRIVATE _POSIX_C_SOURCE=200809L)
    target_link_libraries(pcbare_echo PRIVATE fbrl_static)
    add_dependencies(pcbare_echo fbrl_pcbare)
    get_property(pcbare_image TARGET fbrl_pcbare PROPERTY FBRL_IMAGE)
    # 16550, trigger 14, 115200: the main case.
    add_test(NAME qemu_pcbare_echo COMMAND pcbare_echo ${FBRL_QEMU_I386} ${pcbare_image} 131072)
    # A consumer that stalls 200 ms per 16 KiB: the image must send XOFF, the host
    # must obey, and the handler's headroom rule must hold the rest back losslessly.
    add_test(NAME qemu_pcbare_flow COMMAND pcbare_echo ${FBRL_QEMU_I386} ${pcbare_image} 65536 "stall=200")
    # The chip as a plain 8250 (no FIFO: one byte per interrupt) at 9600 baud.
    add_test(NAME qemu_pcbare_8250 COMMAND pcbare_echo ${FBRL_QEMU_I386} ${pcbare_image} 16384 "fifo=0 baud=9600")
    set_tests_properties(qemu_pcbare_echo qemu_pcbare_flow qemu_pcbare_8250 PROPERTIES LABELS qemu TIMEOUT 120)
  else()
    message(STATUS "qemu-system-i386 not found: qemu_pcbare_echo not added")
  endif()
endif()
