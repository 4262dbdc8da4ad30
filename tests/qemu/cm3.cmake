# SPDX-License-Identifier: MIT
# QEMU tests of the Cortex-M3 firmware (ports/cortex-m3): the image boots in
# qemu-system-arm's lm3s6965evb with the console (UART0) on the test's stdio and the
# controller's line (UART1) on a real fbrlsim's pty. About 10-20 s each.
#   qemu_cm3_plan:   the sample-preparation plan typed at the console; fbrlsim's command
#                    log must equal the log of the same plan run by fbrlmon on the host.
#   qemu_cm3_faults: the link fault test (1 % drops, 1 % corrupted bytes both ways) over
#                    the firmware's UART: 0 altered, 0 run twice, every result true.
#   qemu_cm3_cell:   the work cell's guard on the firmware: the ASPS cell typed at the
#                    console, a move into the heating block refused before a byte is sent
#                    and a clear one run, against fbrlsim --cell's log.
# They run wherever qemu-system-arm, the cross toolchain (the fbrl_cm3 target) and mkfifo
# exist; -DFBRL_CM3_QEMU_TESTS=OFF leaves them out.
# cm3_size (label unit, no QEMU): the image's size report against the budgets (192 KB flash,
# 64 KB RAM).
if(TARGET fbrl_cm3)
  get_property(cm3_image TARGET fbrl_cm3 PROPERTY FBRL_IMAGE)
  get_filename_component(cm3_dir ${cm3_image} DIRECTORY)
  add_test(NAME cm3_size COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/qemu/cm3_size.sh ${cm3_dir}/size-report.txt)
  set_tests_properties(cm3_size PROPERTIES LABELS unit TIMEOUT 10)
endif()
option(FBRL_CM3_QEMU_TESTS "run the Cortex-M3 firmware under QEMU (label qemu)" ON)
if(NOT FBRL_CM3_QEMU_TESTS)
  message(STATUS "cortex-m3: the QEMU tests are off (FBRL_CM3_QEMU_TESTS=OFF)")
elseif(TARGET fbrl_cm3 AND TARGET fbrlsim AND TARGET fbrlmon)
  find_program(FBRL_QEMU_ARM qemu-system-arm)
  find_program(FBRL_MKFIFO mkfifo)
  if(FBRL_QEMU_ARM AND FBRL_MKFIFO)
    get_property(cm3_image TARGET fbrl_cm3 PROPERTY FBRL_IMAGE)
    add_test(NAME qemu_cm3_plan COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/qemu/cm3_plan.sh ${FBRL_QEMU_ARM}
      ${cm3_image} $<TARGET_FILE:fbrlsim> $<TARGET_FILE:fbrlmon> ${PROJECT_SOURCE_DIR}/examples
      ${PROJECT_BINARY_DIR}/qemu-cm3/plan)
    add_test(NAME qemu_cm3_faults COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/qemu/cm3_faults.sh ${FBRL_QEMU_ARM}
      ${cm3_image} $<TARGET_FILE:fbrlsim> ${PROJECT_BINARY_DIR}/qemu-cm3/faults 200 7)
    add_test(NAME qemu_cm3_cell COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/qemu/cm3_cell.sh ${FBRL_QEMU_ARM}
      ${cm3_image} $<TARGET_FILE:fbrlsim> ${PROJECT_SOURCE_DIR}/examples ${PROJECT_BINARY_DIR}/qemu-cm3/cell)
    # fbrlmon's known leak suppressions for sanitizer builds (as in plan.cmake)
    set_tests_properties(qemu_cm3_plan qemu_cm3_faults qemu_cm3_cell PROPERTIES LABELS qemu TIMEOUT 120
      ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
  else()
    message(STATUS "qemu-system-arm not found: the Cortex-M3 firmware tests are not added")
  endif()
endif()
