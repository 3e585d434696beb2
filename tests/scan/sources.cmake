# Parameter planes (paths relative to tests/).
set(IMPACTLAB_SCAN_TEST_SOURCES
  scan/scan_test.cpp
  scan/scan_csv_test.cpp
)
