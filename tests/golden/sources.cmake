# Results pinned by hash (paths relative to tests/): regenerate with IMPACTLAB_UPDATE_GOLDEN=1 (golden_test.cpp).
set(IMPACTLAB_GOLDEN_TEST_SOURCES
  golden/golden_test.cpp
)
