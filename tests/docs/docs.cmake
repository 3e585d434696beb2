# The user guide: every relative link and image of README.md and docs/ names a file (and heading) that exists.
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  add_test(NAME docs_links COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/docs/links.py ${PROJECT_SOURCE_DIR})
  set_tests_properties(docs_links PROPERTIES LABELS "docs")
endif()
