# SPDX-License-Identifier: MIT
# Manual pages (man -l renders them; each program's page lists exactly its --help options)
# and bash completion (label e2e).
if(TARGET fbrlmon AND TARGET fbrlsim)
  if(TARGET man)
    set(_station_prog "")
    if(TARGET station)  # fbrl-station's launcher (apps/station.cmake)
      set(_station_prog ${PROJECT_BINARY_DIR}/apps/fbrl-station)
    endif()
    add_test(NAME man_pages COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/man_test.sh ${PROJECT_BINARY_DIR}/man
      $<TARGET_FILE:fbrlmon> $<TARGET_FILE:fbrlsim> $<TARGET_FILE:fbrl-dump> ${_station_prog})
    set_tests_properties(man_pages PROPERTIES LABELS e2e TIMEOUT 60 SKIP_RETURN_CODE 77)
  endif()
  add_test(NAME bash_completion COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/completion_test.sh
    ${PROJECT_SOURCE_DIR}/completions/fbrl.bash $<TARGET_FILE_DIR:fbrlmon> $<TARGET_FILE_DIR:fbrlsim>)
  set_tests_properties(bash_completion PROPERTIES LABELS e2e TIMEOUT 60 SKIP_RETURN_CODE 77)
endif()
