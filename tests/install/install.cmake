# The desktop install (packaging/install.cmake): into a temporary prefix, both programs run from another
# directory (install_test.sh). Included by tests/CMakeLists.txt with the app.
add_test(NAME install
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/install/install_test.sh ${PROJECT_BINARY_DIR}
                 $<TARGET_FILE:impactlab_png_check> ${CMAKE_CURRENT_BINARY_DIR}/install_test)
set_tests_properties(install PROPERTIES TIMEOUT 300 LABELS "install")
