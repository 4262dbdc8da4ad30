# SPDX-License-Identifier: MIT
# The work cell's guard against a real fbrlsim that knows the same cell (docs/workcell.md):
# a move into the table, into a box, through a keep-out zone in a straight line, and a joint
# move whose ends are clear but whose path is not: refused before any byte of the motion is
# sent (fbrlsim's command log), and with the guard off stopped by fbrlsim's 190-COLLISION at
# the point of contact (label e2e).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME cell_guard_e2e COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell_test.sh $<TARGET_FILE:fbrlmon>
    $<TARGET_FILE:fbrlsim> ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell ${PROJECT_BINARY_DIR}/e2e-cell)
  set_tests_properties(cell_guard_e2e PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
  # The A465 (--arm a465) in the ASPS cell against fbrlsim --model a465 --cell: the move into
  # the heating block refused before a byte is sent, the clear moves run; unguarded, fbrlsim
  # stops it with 190 (its stamped log is the truth).
  add_test(NAME cell_a465_e2e COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell_a465.sh $<TARGET_FILE:fbrlmon>
    $<TARGET_FILE:fbrlsim> ${PROJECT_SOURCE_DIR}/examples ${CMAKE_CURRENT_SOURCE_DIR}/e2e/cell
    ${PROJECT_BINARY_DIR}/e2e-cell-a465)
  set_tests_properties(cell_a465_e2e PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()

# fbrlmon --dry-run of the sample-preparation plan: under 10 s, its report and picture
# (label e2e); against a real-time run of the same plan within 2 % (label slow, a minute).
if(TARGET fbrlmon AND TARGET fbrlsim)
  add_test(NAME dry_run_e2e COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/dry_run.sh $<TARGET_FILE:fbrlmon>
    ${PROJECT_SOURCE_DIR}/examples ${PROJECT_BINARY_DIR}/e2e-dry)
  add_test(NAME dry_run_vs_real COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/dry_run.sh $<TARGET_FILE:fbrlmon>
    ${PROJECT_SOURCE_DIR}/examples ${PROJECT_BINARY_DIR}/e2e-dry-real real)
  set_tests_properties(dry_run_e2e PROPERTIES LABELS e2e TIMEOUT 120
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
  set_tests_properties(dry_run_vs_real PROPERTIES LABELS "e2e;slow" TIMEOUT 300
    ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/e2e/mon_lsan.supp")
endif()
