# SPDX-License-Identifier: MIT
# The Python bindings (python/, label python): pytest against the built shared library and
# a real fbrlsim, and the Python sample-prep example, whose output must be exactly the C
# example's (examples/sample_prep_c.out.expected) and whose controller log the C example's
# with the four W5 readings the Python link makes before a motion or FINISH while the arm
# may move (python/examples/sample_prep.expected; docs/python.md). Needs a Python 3 with
# cffi and pytest (Debian: python3-cffi, python3-pytest); without one the tests are not
# added. Not in sanitizer builds: a sanitized library cannot be dlopen'ed by Python.
if(FBRL_SANITIZE STREQUAL "" AND TARGET fbrlsim)
  set(FBRL_PYTHON "")
  foreach(_py /usr/bin/python3 ${Python3_EXECUTABLE})
    execute_process(COMMAND ${_py} -c "import cffi, pytest" RESULT_VARIABLE _r OUTPUT_QUIET ERROR_QUIET)
    if(_r EQUAL 0)
      set(FBRL_PYTHON ${_py})
      break()
    endif()
  endforeach()
  if(FBRL_PYTHON)
    set(_py_env "PYTHONPATH=${PROJECT_SOURCE_DIR}/python" "PYTHONDONTWRITEBYTECODE=1"
      "FBRL_LIBRARY=$<TARGET_FILE:fbrl>" "FBRL_SIM=$<TARGET_FILE:fbrlsim>")
    if(TARGET fbrl-audit) # a method's version as fbrl-audit names it (test_release.py)
      list(APPEND _py_env "FBRL_AUDIT=$<TARGET_FILE:fbrl-audit>")
    endif()
    add_test(NAME python_bindings COMMAND ${FBRL_PYTHON} -m pytest -p no:cacheprovider -q
      --basetemp=${PROJECT_BINARY_DIR}/python-tests ${PROJECT_SOURCE_DIR}/python/tests)
    add_test(NAME python_sample_prep COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/e2e/plan_run.sh $<TARGET_FILE:fbrlsim>
      ${PROJECT_BINARY_DIR}/python-plan ${PROJECT_SOURCE_DIR}/examples/tube_present.inputs
      ${PROJECT_SOURCE_DIR}/python/examples/sample_prep.expected ${PROJECT_SOURCE_DIR}/examples/sample_prep_c.out.expected
      ${FBRL_PYTHON} ${PROJECT_SOURCE_DIR}/python/examples/sample_prep.py @PORT@)
    set_tests_properties(python_bindings python_sample_prep PROPERTIES LABELS python TIMEOUT 300
      ENVIRONMENT "${_py_env}")
    # fbrl-urdf's URDF against check_urdf (Debian: liburdfdom-tools) and the library's FK
    add_test(NAME urdf COMMAND ${FBRL_PYTHON} -m pytest -p no:cacheprovider -q
      --basetemp=${PROJECT_BINARY_DIR}/urdf-tests ${PROJECT_SOURCE_DIR}/tests/urdf)
    set_tests_properties(urdf PROPERTIES LABELS python TIMEOUT 300
      ENVIRONMENT "${_py_env};FBRL_URDF=$<TARGET_FILE:fbrl-urdf>")
  else()
    message(STATUS "python: no Python 3 with cffi and pytest (python3-cffi, python3-pytest): tests not added")
  endif()
endif()
