# QEMU test of the bare-metal port (ports/pc-bare): boot the image with COM1 on a pty
# and push 128 KiB through its interrupt-driven echo from the host, over the
# project's own POSIX backend with XON/XOFF. Needs qemu-system-i386 (TCG; no KVM).
if(TARGET fbrl_pcbare)
  find_program(FBRL_QEMU_I386 qemu-system-i386)
  if(FBRL_QEMU_I386)
    add_executable(pcbare_echo ${CMAKE_CURRENT_SOURCE_DIR}/qemu/pcbare_echo.c)
    target_compile_definitions(pcbare_echo PRIVATE _POSIX_C_SOURCE=200809L)
    target_link_libraries(pcbare_echo PRIVATE fbrl_static)
    add_dependencies(pcbare_echo fbrl_pcbare)
    get_property(pcbare_image TARGET fbrl_pcbare PROPERTY FBRL_IMAGE)
    add_test(NAME qemu_pcbare_echo COMMAND pcbare_echo ${FBRL_QEMU_I386} ${pcbare_image} 131072)
    set_tests_properties(qemu_pcbare_echo PROPERTIES LABELS qemu TIMEOUT 120)
  else()
    message(STATUS "qemu-system-i386 not found: qemu_pcbare_echo not added")
  endif()
endif()
