# Parameter planes (paths relative to tests/).
set(IMPACTLAB_SCAN_TEST_SOURCES
  scan/scan_test.cpp
)
