# SPDX-License-Identifier: MIT
# fbrl-station (label station, docs/sila.md): its feature definitions and protobuf files against
# the standard's (station_fdl), pytest against fbrlsim for every command, property and error
# (station, station_methods), several stations found by discovery and driven at once (station_many), and a
# client the project did not write, Node's @grpc/grpc-js from the lock file in
# tests/station/node, installed into the build tree by npm ci (station_node_deps, then
# station_node). Not in sanitizer builds: Python cannot load a sanitized library (the runtime
# must come first in the process), as for the Python bindings' tests.
if(FBRL_SANITIZE STREQUAL "" AND TARGET station)
  execute_process(COMMAND ${FBRL_STATION_PYTHON} -c "import pytest, lxml" RESULT_VARIABLE _r OUTPUT_QUIET ERROR_QUIET)
  if(NOT _r EQUAL 0)
    message(STATUS "station: no pytest or lxml for ${FBRL_STATION_PYTHON} (python3-pytest, python3-lxml): tests not added")
    return()
  endif()
  set(_st ${PROJECT_SOURCE_DIR}/tests/station)
  set(_st_env "PYTHONPATH=${PROJECT_SOURCE_DIR}/python" "PYTHONDONTWRITEBYTECODE=1" "FBRL_LIBRARY=$<TARGET_FILE:fbrl>"
    "FBRL_SIM=$<TARGET_FILE:fbrlsim>" "FBRL_STATION_GEN=${FBRL_STATION_BUILD}/gen"
    "FBRL_STATION=${PROJECT_BINARY_DIR}/apps/fbrl-station" "FBRL_STATION_PROTO=${FBRL_STATION_BUILD}/proto")
  set(_pytest ${FBRL_STATION_PYTHON} -m pytest -p no:cacheprovider -q)
  file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/station-tests)  # pytest makes each --basetemp, not its parent
  add_test(NAME station_fdl COMMAND ${_pytest} --basetemp=${PROJECT_BINARY_DIR}/station-tests/fdl ${_st}/test_fdl.py)
  add_test(NAME station COMMAND ${_pytest} --basetemp=${PROJECT_BINARY_DIR}/station-tests/main
    ${_st}/test_arm.py ${_st}/test_core.py)
  add_test(NAME station_methods COMMAND ${_pytest} --basetemp=${PROJECT_BINARY_DIR}/station-tests/methods
    ${_st}/test_methods.py)
  add_test(NAME station_many COMMAND ${_pytest} --basetemp=${PROJECT_BINARY_DIR}/station-tests/many
    ${_st}/test_many.py)
  set_tests_properties(station_fdl station station_methods station_many PROPERTIES LABELS station TIMEOUT 600
    ENVIRONMENT "${_st_env}")

  # the page (--http) in Debian's chromium, headless with software WebGL (label browser too)
  find_program(FBRL_CHROMIUM chromium)
  execute_process(COMMAND ${FBRL_STATION_PYTHON} -c "import aiohttp, websocket, PIL" RESULT_VARIABLE _r OUTPUT_QUIET ERROR_QUIET)
  if(FBRL_CHROMIUM AND _r EQUAL 0 AND EXISTS /usr/share/javascript/three/build/three.min.js)
    add_test(NAME station_page COMMAND ${_pytest} --basetemp=${PROJECT_BINARY_DIR}/station-tests/page
      ${_st}/test_page.py)
    set_tests_properties(station_page PROPERTIES LABELS "station;browser" TIMEOUT 600
      ENVIRONMENT "${_st_env};FBRL_CHROMIUM=${FBRL_CHROMIUM};FBRL_PAGE_SHOTS=${PROJECT_BINARY_DIR}/station-tests/page-shots")
  else()
    message(STATUS "station: chromium, libjs-three or python3-aiohttp/-websocket/-pil missing: the page's browser test not added")
  endif()

  # the page beyond loopback (--http on this machine's address, --lab): HTTPS/WSS and the lab's users
  execute_process(COMMAND ${FBRL_STATION_PYTHON} -c "import aiohttp, websocket" RESULT_VARIABLE _r OUTPUT_QUIET ERROR_QUIET)
  if(_r EQUAL 0 AND TARGET fbrl-users)
    add_test(NAME station_login COMMAND ${_pytest} --basetemp=${PROJECT_BINARY_DIR}/station-tests/login
      ${_st}/test_login.py)
    set_tests_properties(station_login PROPERTIES LABELS station TIMEOUT 600
      ENVIRONMENT "${_st_env};FBRL_USERS=$<TARGET_FILE:fbrl-users>")
  else()
    message(STATUS "station: python3-aiohttp/-websocket or fbrl-users missing: the page's sign-in test not added")
  endif()

  find_program(FBRL_NODE node)
  find_program(FBRL_NPM npm)
  if(FBRL_NODE AND FBRL_NPM)
    set(_node_dir ${FBRL_STATION_BUILD}/node)
    add_test(NAME station_node_deps COMMAND sh -c "mkdir -p '${_node_dir}' && cp '${_st}/node/package.json' \
'${_st}/node/package-lock.json' '${_node_dir}/' && cd '${_node_dir}' && \
'${FBRL_NPM}' ci --ignore-scripts --no-audit --no-fund")
    set_tests_properties(station_node_deps PROPERTIES LABELS station TIMEOUT 600 FIXTURES_SETUP station_node)
    add_test(NAME station_node COMMAND ${FBRL_NODE} ${_st}/node/station_test.js)
    set_tests_properties(station_node PROPERTIES LABELS station TIMEOUT 600 FIXTURES_REQUIRED station_node
      ENVIRONMENT "${_st_env};NODE_PATH=${_node_dir}/node_modules;FBRL_STATION_TESTS=${PROJECT_BINARY_DIR}/station-tests/node")
  else()
    message(STATUS "station: node or npm missing (Debian: nodejs, npm): the Node client test not added")
  endif()
endif()
