# Headless tests of the visualiser's GL-free parts (paths relative to tests/): the SPSC ring buffer, the
# simulation engine's command handling and the UI's backlog of refused commands, the history and its CSV
# export, the options, the presets, the measured-data panel's worker and effect-subset mapping, the plots'
# CPU rasterizer, the Poincare map's settle detector, and the plots' fits (view_fit). They build into
# impactlab_tests, which links the app's own GL-free library (impactlab_gui_core, app/gui/CMakeLists.txt)
# rather than compiling its sources again. The test files include those headers by relative path
# ("../../app/gui/..."), so this list needs no directory-wide include or link settings.
set(IMPACTLAB_APP_TEST_SOURCES
  app/ring_buffer_test.cpp
  app/sim_commands_test.cpp
  app/command_link_test.cpp
  app/gui_parts_test.cpp
  app/data_job_test.cpp
  app/plot_raster_test.cpp
  app/poincare_map_test.cpp
  app/view_fit_test.cpp
  app/analysis_gui_test.cpp
  app/lyapunov_live_test.cpp
  app/bifurcation_job_test.cpp
  app/companion_test.cpp
  app/replay_test.cpp
  app/session_test.cpp
  app/energy_bar_test.cpp
  app/omega_ramp_test.cpp
  app/layout_test.cpp
  app/input_files_test.cpp
  app/param_edit_test.cpp
  app/file_list_test.cpp
  app/program_assets_test.cpp
)
