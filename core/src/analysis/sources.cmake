# Periodic orbits, continuation, Lyapunov exponents and basins; paths relative to core/.
set(IMPACTLAB_ANALYSIS_SOURCES
  src/analysis/tangent.cpp
  src/analysis/orbit.cpp
  src/analysis/continuation.cpp
  src/analysis/continuation_impacting.cpp
  src/analysis/continuation_contact.cpp
  src/analysis/continuation_periods.cpp
  src/analysis/branch_curves.cpp
  src/analysis/lyapunov.cpp
  src/analysis/basins.cpp
  src/analysis/curves.cpp
  src/analysis/impacting.cpp
  src/analysis/plane_doubling.cpp
)
