# impactlab fit: loader, effect laws, the loop on synthetic and shared data (paths relative to tests/).
set(IMPACTLAB_IDENTIFY_TEST_SOURCES
  identify/loader_test.cpp
  identify/effect_laws_test.cpp
  identify/loop_test.cpp
  identify/shared_data_test.cpp
  identify/audit_test.cpp
  identify/gate_test.cpp
  identify/stats_test.cpp
  identify/signal_test.cpp
  identify/least_squares_test.cpp
  identify/residual_test.cpp
  identify/add_effect_test.cpp
  identify/parsimony_test.cpp
  identify/mismatch_test.cpp
  identify/stops_test.cpp
  identify/features_test.cpp
)
