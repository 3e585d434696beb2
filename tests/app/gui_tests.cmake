# Visualiser tests that need the app (included by tests/CMakeLists.txt only with IMPACTLAB_BUILD_APP=ON).
#
# gui_smoke: impactlab-gui under Xvfb with Mesa's software OpenGL renders 120 frames, switches the model
# once, saves a screenshot; the PNG must be a real picture and the simulation must have advanced.
# Skipped (exit 77) where xvfb-run is missing; CI installs it with: apt-get install xvfb xauth
# libgl1-mesa-dri.
find_package(PkgConfig REQUIRED)
pkg_check_modules(IMPACTLAB_APP_TEST_STB REQUIRED IMPORTED_TARGET stb)
add_executable(impactlab_png_check app/png_check.cpp)
target_link_libraries(impactlab_png_check PRIVATE PkgConfig::IMPACTLAB_APP_TEST_STB impactlab_options)

add_test(NAME gui_smoke
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_smoke.sh $<TARGET_FILE:impactlab-gui>
                 $<TARGET_FILE:impactlab_png_check> ${CMAKE_CURRENT_BINARY_DIR}/gui_smoke)
set_tests_properties(gui_smoke PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# Bad flags: a clear message and exit code 2 (no display needed).
add_test(NAME gui_bad_flag
         COMMAND sh -c "\"$0\" --no-such-flag; test $? -eq 2" $<TARGET_FILE:impactlab-gui>)
add_test(NAME gui_bad_value
         COMMAND sh -c "\"$0\" --omega fast; test $? -eq 2" $<TARGET_FILE:impactlab-gui>)
set_tests_properties(gui_bad_flag gui_bad_value PROPERTIES LABELS "gui")

# A short soak (the README reports the long one): 20 s at 100x switching through every version every 3 s;
# fails if the resident memory grows by more than 16 MB after the first quarter.
add_test(NAME gui_soak_short
         COMMAND sh -c "command -v xvfb-run >/dev/null || exit 77; xvfb-run -a -s '-screen 0 1280x800x24' \"$0\" --soak 20"
                 $<TARGET_FILE:impactlab-gui>)
set_tests_properties(gui_soak_short PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS "gui")
