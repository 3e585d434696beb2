# The Python module against the CLI (pytest, tests/python/): built when python/ found pybind11 and NumPy.
if(TARGET impactlab_python)
  add_test(NAME python
           COMMAND ${IMPACTLAB_PYTHON_EXECUTABLE} -m pytest -q -p no:cacheprovider ${CMAKE_CURRENT_SOURCE_DIR}/python)
  set_tests_properties(python PROPERTIES LABELS "python" TIMEOUT 900
                       ENVIRONMENT "PYTHONPATH=${PROJECT_BINARY_DIR}/python;IMPACTLAB_CLI=$<TARGET_FILE:impactlab>;IMPACTLAB_SHARED=${PROJECT_SOURCE_DIR}/../shared")
endif()
# The notebook examples/tour.ipynb executed top to bottom (jupyter nbconvert; Debian's python3-nbconvert and
# python3-ipykernel), its figures kept in the executed copy build/examples/tour.ipynb.
if(TARGET impactlab_python)
  execute_process(COMMAND ${IMPACTLAB_PYTHON_EXECUTABLE} -c "import nbconvert, ipykernel, matplotlib"
                  RESULT_VARIABLE IMPACTLAB_NO_NBCONVERT OUTPUT_QUIET ERROR_QUIET)
  if(IMPACTLAB_NO_NBCONVERT EQUAL 0)
    # The tour fits a record of ../shared/data: a clone without it skips the notebook (77), saying so.
    set(IMPACTLAB_TOUR_RECORD ${PROJECT_SOURCE_DIR}/../shared/data/synthetic/s1_quadratic_damping.csv.gz)
    add_test(NAME notebook
             COMMAND bash -c "[ -e \"$0\" ] || { echo \"skipped, not passed: $0 is missing\"; exit 77; }; exec \"$@\""
                     ${IMPACTLAB_TOUR_RECORD}
                     ${IMPACTLAB_PYTHON_EXECUTABLE} -m nbconvert --to notebook --execute
                     --ExecutePreprocessor.timeout=900 --output-dir ${PROJECT_BINARY_DIR}/examples
                     ${PROJECT_SOURCE_DIR}/examples/tour.ipynb)
    set_tests_properties(notebook PROPERTIES LABELS "python" TIMEOUT 1200 SKIP_RETURN_CODE 77
                         ENVIRONMENT "PYTHONPATH=${PROJECT_BINARY_DIR}/python;IMPACTLAB_SHARED=${PROJECT_SOURCE_DIR}/../shared")
  else()
    message(STATUS "examples/tour.ipynb: not run (needs python3-nbconvert, python3-ipykernel, python3-matplotlib)")
  endif()
endif()
