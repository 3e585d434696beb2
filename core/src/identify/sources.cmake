# impactlab fit: measured data, residual, effect selection, report (paths relative to core/).
set(IMPACTLAB_IDENTIFY_SOURCES
  src/identify/gzip.cpp
  src/identify/loader.cpp
  src/identify/signal.cpp
  src/identify/impacts.cpp
  src/identify/stats.cpp
  src/identify/residual.cpp
  src/identify/catalogue.cpp
  src/identify/shooting.cpp
  src/identify/fit.cpp
  src/identify/report.cpp
  src/identify/synth.cpp
  src/identify/recovery.cpp
  src/identify/wells.cpp
  src/identify/least_squares.cpp
)
