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
    add_test(NAME notebook
             COMMAND ${IMPACTLAB_PYTHON_EXECUTABLE} -m nbconvert --to notebook --execute
                     --ExecutePreprocessor.timeout=900 --output-dir ${PROJECT_BINARY_DIR}/examples
                     ${PROJECT_SOURCE_DIR}/examples/tour.ipynb)
    set_tests_properties(notebook PROPERTIES LABELS "python" TIMEOUT 1200
                         ENVIRONMENT "PYTHONPATH=${PROJECT_BINARY_DIR}/python;IMPACTLAB_SHARED=${PROJECT_SOURCE_DIR}/../shared")
  else()
    message(STATUS "examples/tour.ipynb: not run (needs python3-nbconvert, python3-ipykernel, python3-matplotlib)")
  endif()
endif()
