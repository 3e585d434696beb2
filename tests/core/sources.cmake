# Core unit tests (paths relative to tests/).
set(IMPACTLAB_CORE_TEST_SOURCES
  core/forces_test.cpp
  core/drive_test.cpp
  core/params_test.cpp
  core/params_json_test.cpp
  core/simulator_test.cpp
  core/integrator_order_test.cpp
  core/energy_test.cpp
  core/equilibria_test.cpp
  core/impact_test.cpp
  core/sweep_test.cpp
  core/section_phase_test.cpp
  core/plot_test.cpp
  core/raster_test.cpp
  core/input_file_test.cpp
  core/atomic_file_test.cpp
)
