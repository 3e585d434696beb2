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

# The Poincare map through --state-json: period and clusters after a preset change, settling, chaos
# (gui_poincare.sh says what it checks). Skipped (exit 77) without xvfb-run or python3.
add_test(NAME gui_poincare
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_poincare.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_poincare)
set_tests_properties(gui_poincare PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# The Poincare section at a chosen phase (--phi0, --then-phi0) against the CLI's, and its session key
# (gui_phase.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_phase
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_phase.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_phase)
  set_tests_properties(gui_phase PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")
endif()

# The Poincare map's period label on both sides of the first period doubling, from rest and after a live
# omega change (gui_doubling.sh says what it checks).
add_test(NAME gui_doubling
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_doubling.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_doubling)
set_tests_properties(gui_doubling PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 400 LABELS "gui")

# The GUI's continued branches are the CLI's: the same special points through --state-json and points.csv.
if(TARGET impactlab)
  add_test(NAME gui_continuation
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_continuation.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_continuation)
  set_tests_properties(gui_continuation PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "gui")
endif()

# The Poincare view's label beside every bifurcation of A1G's, A1H's and A3C's continuation agrees with the
# core's orbit and Lyapunov exponent from the GUI's own section point (gui_bifurcations.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_bifurcations
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_bifurcations.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_bifurcations)
  set_tests_properties(gui_bifurcations PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900 LABELS "gui")
endif()

# The period label waits for a slowly dying alternation just below the first doubling, and never says
# period 1 just above it; a ramp says omega moves (gui_label_wait.sh says what it checks).
add_test(NAME gui_label_wait
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_label_wait.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_label_wait)
set_tests_properties(gui_label_wait PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 400 LABELS "gui")

# Legends and labels never cover the data; the diagram stays drawn with the analysis tiles open and at
# scale 2 (gui_legends.sh says what it checks).
add_test(NAME gui_legends
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_legends.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_legends)
set_tests_properties(gui_legends PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 400 LABELS "gui")

# Defects a teacher meets: --save-session keeps --model, bad session numbers and duplicate keys refused.
add_test(NAME gui_teacher
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_teacher.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_teacher)
set_tests_properties(gui_teacher PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# The live omega ramp and the energy bar through --state-json (gui_ramp.sh says what it checks).
add_test(NAME gui_ramp
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_ramp.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_ramp)
set_tests_properties(gui_ramp PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# Bad flags: a clear message and exit code 2 (no display needed).
add_test(NAME gui_bad_flag
         COMMAND sh -c "\"$0\" --no-such-flag; test $? -eq 2" $<TARGET_FILE:impactlab-gui>)
add_test(NAME gui_bad_value
         COMMAND sh -c "\"$0\" --omega fast; test $? -eq 2" $<TARGET_FILE:impactlab-gui>)
# --preset beyond the model's list, --state-json without --frames, and a missing
# --data file in a headless run: each names the flag and exits 2 before any window opens.
add_test(NAME gui_bad_preset
         COMMAND sh -c "\"$0\" --model A3H --preset 9 --frames 2 2>&1 | grep -q -- '--preset'; test $? -eq 0 && \"$0\" --model A3H --preset 9 --frames 2; test $? -eq 2"
                 $<TARGET_FILE:impactlab-gui>)
add_test(NAME gui_state_json_needs_frames
         COMMAND sh -c "\"$0\" --state-json /tmp/impactlab-never.json 2>&1 | grep -q -- '--state-json needs --frames'; test $? -eq 0 && \"$0\" --state-json /tmp/impactlab-never.json; test $? -eq 2"
                 $<TARGET_FILE:impactlab-gui>)
add_test(NAME gui_missing_data
         COMMAND sh -c "\"$0\" --data /nonexistent/run.csv --frames 10 2>&1 | grep -q -- '--data: cannot read'; test $? -eq 0 && \"$0\" --data /nonexistent/run.csv --frames 10; test $? -eq 2"
                 $<TARGET_FILE:impactlab-gui>)
set_tests_properties(gui_bad_flag gui_bad_value gui_bad_preset gui_state_json_needs_frames gui_missing_data
                     PROPERTIES LABELS "gui")

# A short soak (the README reports the long one): 20 s at 100x switching through every version every 3 s;
# fails if the resident memory grows by more than 16 MB after the first quarter.
add_test(NAME gui_soak_short
         COMMAND sh -c "command -v xvfb-run >/dev/null || exit 77; xvfb-run -a -s '-screen 0 1280x800x24' \"$0\" --soak 20"
                 $<TARGET_FILE:impactlab-gui>)
set_tests_properties(gui_soak_short PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS "gui")

# The analysis views: --plane, --continuation and --basins under Xvfb, and a bad plane file
# named with its line (gui_analysis.sh says what it checks). Skipped (exit 77) without xvfb-run.
add_test(NAME gui_analysis
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_analysis.sh $<TARGET_FILE:impactlab-gui>
                 $<TARGET_FILE:impactlab_png_check> ${CMAKE_CURRENT_BINARY_DIR}/gui_analysis)
set_tests_properties(gui_analysis PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "gui")

# Session files and clip export: save and load through --save-session / --session, bad files
# refused naming file, key and problem, a clip's PNG frames (gui_session.sh says what it checks).
add_test(NAME gui_session
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_session.sh $<TARGET_FILE:impactlab-gui>
                 $<TARGET_FILE:impactlab_png_check> ${CMAKE_CURRENT_BINARY_DIR}/gui_session)
set_tests_properties(gui_session PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# The layout: tiles at UI scale 2, hide and maximise, presentation mode and the
# rig's magnification through --state-json, bad layout flags (gui_layout.sh says what it checks).
add_test(NAME gui_layout
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_layout.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_layout)
set_tests_properties(gui_layout PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# The companion cart, the grazing monitor and the mouse's state: a twin parts in chaos and
# not on period 1, a ghost under A1G parts from A1C, the monitor's gap and impact velocity, --set-state
# beyond the bumper, the shared contact label, bad flags (gui_companion.sh says what it checks).
add_test(NAME gui_companion
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_companion.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_companion)
set_tests_properties(gui_companion PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")

# The bifurcation panel: range, progressive fill, the box, the stale note, via
# --state-json (gui_diagram.sh says what it checks). Skipped (exit 77) without xvfb-run or python3.
add_test(NAME gui_diagram
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_diagram.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_diagram)
set_tests_properties(gui_diagram PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")

# The Parameters panel: --param changes the running model (the cart comes to rest without the
# unbalance), the values are reported back, bad values and keys exit 2 (gui_params.sh says what it checks).
add_test(NAME gui_params
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_params.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_params)
set_tests_properties(gui_params PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# The time strip's traces: --strip chooses one or two of x, v, E, F, drive, each on its own axis
# (gui_strip.sh says what it checks).
add_test(NAME gui_strip
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_strip.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_strip)
set_tests_properties(gui_strip PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# "What to try": each demonstration sets up what it says; the guide and the status bar's details
# (gui_guide.sh says what it checks).
add_test(NAME gui_guide
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_guide.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_guide)
set_tests_properties(gui_guide PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")

# The Poincare clicker: each click starts an orbit kept in its own colour; A1G's coexisting
# period-1 orbit and chaos at 13 rad/s mapped by two clicks (gui_clicker.sh says what it checks).
add_test(NAME gui_clicker
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_clicker.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_clicker)
set_tests_properties(gui_clicker PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# The parameter plane as a tile, and the core's continued doubling over it agreeing with the CLI's
# (gui_plane.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_plane
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_plane.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_plane)
  set_tests_properties(gui_plane PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")
  # The grazing and fold curves over the plane agreeing with the CLI's (gui_plane_curves.sh says how).
  add_test(NAME gui_plane_curves
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_plane_curves.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_plane_curves)
  set_tests_properties(gui_plane_curves PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")
endif()

# Continuation from the running orbit (A1G's period-1 window at 14.5 rad/s) agrees with the CLI's from the same
# point (gui_continue_here.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_continue_here
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_continue_here.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_continue_here)
  set_tests_properties(gui_continue_here PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "gui")
endif()

# Session files keep the edited parameters, the strip's traces and the clicker's orbits
# (gui_session_desk.sh says what it checks).
add_test(NAME gui_session_desk
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_session_desk.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_session_desk)
set_tests_properties(gui_session_desk PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")

# Basins over a box (--basins-box, a right-drag) are the CLI's over --x-range and --v-range
# (gui_basins_box.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_basins_box
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_basins_box.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_basins_box)
  set_tests_properties(gui_basins_box PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "gui")
endif()

# The bifurcation diagram over v as well as x, fitted to the CLI's section points of the same sweep
# (gui_diagram_v.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_diagram_v
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_diagram_v.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_diagram_v)
  set_tests_properties(gui_diagram_v PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")
endif()

# The bifurcation diagram over xI, equal to the CLI's sweep, and its y range holding the continued branches
# (gui_diagram_over.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_diagram_over
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_diagram_over.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_diagram_over)
  set_tests_properties(gui_diagram_over PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240 LABELS "gui")
endif()

# --model FILE.json read by the core's parser as the CLI reads it (gui_model_json.sh says what it checks).
if(TARGET impactlab)
  add_test(NAME gui_model_json
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_model_json.sh $<TARGET_FILE:impactlab-gui>
                   $<TARGET_FILE:impactlab> ${CMAKE_CURRENT_BINARY_DIR}/gui_model_json)
  set_tests_properties(gui_model_json PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS "gui")
endif()

# The session window's file browser (gui_browser.sh says what it checks).
add_test(NAME gui_browser
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/app/gui_browser.sh $<TARGET_FILE:impactlab-gui>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui_browser)
set_tests_properties(gui_browser PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS "gui")
