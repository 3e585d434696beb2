# Parameter planes (impactlab scan), paths relative to core/.
set(IMPACTLAB_SCAN_SOURCES
  src/scan/scan.cpp
  src/scan/scan_csv.cpp
  src/scan/scan_png.cpp
)
