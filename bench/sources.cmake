# The benchmark target and its two peers (run on demand; nothing is registered with CTest).
#   bench         impactlab's CF diagrams of the five paper versions and the EF ramp, timed
#   bench_cvode   the A1C / A1H CF diagrams with SUNDIALS CVODE (BDF + root-finding), vs impactlab
#   bench_odeint  the same with Boost.Odeint rosenbrock4 dense output, vs impactlab
add_executable(bench ${CMAKE_CURRENT_SOURCE_DIR}/bench.cpp)
target_link_libraries(bench PRIVATE impactlab::core impactlab_options)

# SUNDIALS 6 (Debian libsundials-dev): no CMake package config there, so the libraries are found one by one.
find_path(IMPACTLAB_CVODE_INCLUDE_DIR cvode/cvode.h)
find_library(IMPACTLAB_SUNDIALS_CVODE sundials_cvode)
find_library(IMPACTLAB_SUNDIALS_NVECSERIAL sundials_nvecserial)
find_library(IMPACTLAB_SUNDIALS_SUNLINSOLDENSE sundials_sunlinsoldense)
find_library(IMPACTLAB_SUNDIALS_SUNMATRIXDENSE sundials_sunmatrixdense)
if(IMPACTLAB_CVODE_INCLUDE_DIR AND IMPACTLAB_SUNDIALS_CVODE AND IMPACTLAB_SUNDIALS_NVECSERIAL
   AND IMPACTLAB_SUNDIALS_SUNLINSOLDENSE AND IMPACTLAB_SUNDIALS_SUNMATRIXDENSE)
  add_executable(bench_cvode ${CMAKE_CURRENT_SOURCE_DIR}/bench_cvode.cpp)
  target_include_directories(bench_cvode SYSTEM PRIVATE ${IMPACTLAB_CVODE_INCLUDE_DIR})
  target_link_libraries(bench_cvode PRIVATE impactlab::core impactlab_options
                        ${IMPACTLAB_SUNDIALS_CVODE} ${IMPACTLAB_SUNDIALS_SUNLINSOLDENSE}
                        ${IMPACTLAB_SUNDIALS_SUNMATRIXDENSE} ${IMPACTLAB_SUNDIALS_NVECSERIAL})
else()
  message(STATUS "bench_cvode: SUNDIALS CVODE not found (libsundials-dev), target not built")
endif()

# Boost.Odeint is header-only (libboost-dev).
find_path(IMPACTLAB_ODEINT_INCLUDE_DIR boost/numeric/odeint.hpp)
if(IMPACTLAB_ODEINT_INCLUDE_DIR)
  # The odeint part is C++17: Boost 1.74's uBLAS (rosenbrock4's matrices) calls std::allocator::construct,
  # removed in C++20. It includes only peer_model.hpp, never impactlab's headers.
  add_library(bench_odeint_backend OBJECT ${CMAKE_CURRENT_SOURCE_DIR}/bench_odeint_backend.cpp)
  set_target_properties(bench_odeint_backend PROPERTIES CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON)
  target_include_directories(bench_odeint_backend SYSTEM PRIVATE ${IMPACTLAB_ODEINT_INCLUDE_DIR})
  target_link_libraries(bench_odeint_backend PRIVATE impactlab_options)
  add_executable(bench_odeint ${CMAKE_CURRENT_SOURCE_DIR}/bench_odeint.cpp)
  target_link_libraries(bench_odeint PRIVATE bench_odeint_backend impactlab::core impactlab_options)
else()
  message(STATUS "bench_odeint: Boost.Odeint not found (libboost-dev), target not built")
endif()
