# Every third-party dependency of rodlab, each found quietly; a missing one stops configure
# with the Debian package that provides it. scripts/bootstrap.sh installs all of them.

function(rodlab_require_found found what debian_package)
  if(NOT ${found})
    message(FATAL_ERROR
      "rodlab: ${what} was not found.\n"
      "Install the Debian package '${debian_package}':\n"
      "    apt-get install ${debian_package}\n"
      "or run scripts/bootstrap.sh (what `make test` does), which installs every missing package.")
  endif()
endfunction()

find_package(Eigen3 3.4 QUIET NO_MODULE)
rodlab_require_found(Eigen3_FOUND "Eigen 3.4 (linear algebra)" libeigen3-dev)

find_package(fmt QUIET)
rodlab_require_found(fmt_FOUND "fmt (numbers in error messages)" libfmt-dev)

find_package(yaml-cpp QUIET)
rodlab_require_found(yaml-cpp_FOUND "yaml-cpp (scene files)" libyaml-cpp-dev)

find_package(nlohmann_json 3.10 QUIET)
rodlab_require_found(nlohmann_json_FOUND "nlohmann-json (result files)" nlohmann-json3-dev)

find_package(GSL QUIET)
rodlab_require_found(GSL_FOUND "GSL (special functions, quadrature)" libgsl-dev)

find_package(SUNDIALS 6 QUIET)
rodlab_require_found(SUNDIALS_FOUND "SUNDIALS 6 (KINSOL, IDA)" libsundials-dev)
if(NOT TARGET SUNDIALS::sunlinsolklu_shared)
  rodlab_require_found(FALSE "SUNDIALS built with KLU (SUNLinSol_KLU)" libsundials-dev)
endif()

find_path(KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
find_library(KLU_LIBRARY klu)
if(KLU_INCLUDE_DIR AND KLU_LIBRARY)
  set(KLU_FOUND TRUE)
endif()
rodlab_require_found(KLU_FOUND "SuiteSparse KLU (sparse Jacobians)" libsuitesparse-dev)
if(NOT TARGET rodlab::klu)
  add_library(rodlab::klu INTERFACE IMPORTED)
  target_include_directories(rodlab::klu INTERFACE ${KLU_INCLUDE_DIR})
  target_link_libraries(rodlab::klu INTERFACE ${KLU_LIBRARY})
endif()

# Bounded nonlinear least squares for control (inverse statics, NLSQ-MPC; solvers/control/):
# trust-region LM with parameter bounds and user Jacobians, which GSL's multifit lacks.
find_package(Ceres 2 QUIET)
rodlab_require_found(Ceres_FOUND "Ceres Solver 2 (bounded nonlinear least squares)" libceres-dev)

find_package(Threads REQUIRED)

if(RODLAB_BUILD_TESTS)
  find_package(Boost 1.74 QUIET COMPONENTS unit_test_framework)
  rodlab_require_found(Boost_FOUND "Boost.Test (unit tests)" libboost-test-dev)
endif()
if(RODLAB_BUILD_BENCH)
  find_package(benchmark QUIET)
  rodlab_require_found(benchmark_FOUND "Google Benchmark" libbenchmark-dev)
endif()

# Optional: MPI splits `rodlab study` across ranks (Debian's OpenMPI: libopenmpi-dev and
# openmpi-bin; scripts/bootstrap.sh installs them). Without it rodlab builds as usual and
# `rodlab study` under mpirun stops with a message saying so.
find_package(MPI QUIET COMPONENTS CXX)
if(MPI_CXX_FOUND)
  message(STATUS "rodlab: MPI found (${MPI_CXX_LIBRARY_VERSION_STRING}); rodlab study can run across ranks")
else()
  message(STATUS "rodlab: MPI not found (install libopenmpi-dev openmpi-bin); rodlab study runs in one process")
endif()

# The Python module (python/, issue #16): pybind11 for Debian's python3, the interpreter apt's
# python3-* packages (numpy, pytest) install into. Every library is then built position
# independent, as a shared module that links them needs.
if(RODLAB_BUILD_PYTHON)
  set(RODLAB_PYTHON_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "the python3 the module is for")
  set(PYTHON_EXECUTABLE ${RODLAB_PYTHON_EXECUTABLE})
  set(Python_EXECUTABLE ${RODLAB_PYTHON_EXECUTABLE})
  find_package(pybind11 2.10 CONFIG QUIET)
  rodlab_require_found(pybind11_FOUND "pybind11 (the Python module; or -DRODLAB_BUILD_PYTHON=OFF)"
                       pybind11-dev)
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  # -fPIC alone lets the compiler assume any global function may be replaced at load time, and
  # so not inline or clone it within its own file; rodlab's libraries are never interposed.
  add_compile_options(-fno-semantic-interposition)
endif()
