# Third-party libraries, all from Debian bookworm packages (scripts/install-deps.sh).
# CGAL ships Find modules that shadow others: OpenMesh and Eigen are found in CONFIG mode.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(OpenMesh REQUIRED CONFIG)
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL 5.5 REQUIRED)
find_package(TBB REQUIRED CONFIG)
find_package(nlohmann_json 3 REQUIRED CONFIG)
# Highway (Debian libhwy-dev), headers only: the SIMD kernels (the screen's first two stages, the
# screening surface), compiled for several x86 targets and picked at run time
# (core/detail/simd_dispatch.hpp); its library is not linked, as it calibrates a timer when loaded.
find_path(SURFCOMP_HWY_INCLUDE hwy/highway.h REQUIRED)
find_package(Boost 1.74 REQUIRED COMPONENTS graph iostreams program_options)
# cairo (Debian libcairo2-dev) draws the shape images as PNG (patch-map) in the PNG module
# (report/src/png_module.cpp), which only the module links; it has no CMake config.
find_package(PkgConfig REQUIRED)
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)

# Debian's RDKit ships no CMake config: cmake/FindRDKit.cmake makes the imported target RDKit::RDKit.
find_package(RDKit REQUIRED)

# Optional: Open MPI (Debian openmpi-bin, libopenmpi-dev) gives `surfcomp screen` its
# multi-process path (tools/screen_mpi.cpp, its MPI calls in the module tools/mpi_module.cpp,
# which alone links Open MPI); without it the program runs in one process.
find_package(MPI COMPONENTS CXX)

# The system's Python 3 (Debian python3-dev, pybind11-dev): the `surfcomp` Python module and the
# Python tests. A python3 earlier on PATH (pyenv, a virtual environment) lacks Debian's rdkit and
# numpy, so /usr/bin/python3 is preferred unless Python3_EXECUTABLE is given.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
find_package(pybind11 CONFIG)

if(SURFCOMP_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(SURFCOMP_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
