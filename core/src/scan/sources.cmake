# Parameter planes (impactlab scan), paths relative to core/.
set(IMPACTLAB_SCAN_SOURCES
  src/scan/scan.cpp
  src/scan/scan_csv.cpp
  src/scan/scan_png.cpp
)
# Their MPI hand-out: the library impactlab_scan_cluster, built where MPI is found (core/CMakeLists.txt).
set(IMPACTLAB_SCAN_CLUSTER_SOURCES
  src/scan/cluster.cpp
)
