# Periodic orbits, continuation, Lyapunov exponents, basins (paths relative to tests/).
set(IMPACTLAB_ANALYSIS_TEST_SOURCES
  analysis/orbit_test.cpp
  analysis/continuation_test.cpp
  analysis/lyapunov_test.cpp
  analysis/basins_test.cpp
  analysis/curves_test.cpp
  analysis/grazing_test.cpp
)
