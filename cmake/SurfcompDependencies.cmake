# Third-party libraries, all from Debian bookworm packages (scripts/install-deps.sh).
# CGAL ships Find modules that shadow others: OpenMesh and Eigen are found in CONFIG mode.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(OpenMesh REQUIRED CONFIG)
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL 5.5 REQUIRED)
find_package(TBB REQUIRED CONFIG)
find_package(nlohmann_json 3 REQUIRED CONFIG)
find_package(Boost 1.74 REQUIRED COMPONENTS graph iostreams program_options)

# OpenVDB's find module lives outside CMake's default search path.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

# Debian's RDKit ships no CMake config: an imported target over its libraries.
find_path(RDKIT_INCLUDE_DIR GraphMol/ROMol.h PATH_SUFFIXES rdkit REQUIRED)
set(_rdkit_components
    FileParsers SmilesParse PartialCharges Descriptors ForceFieldHelpers ForceField
    MolAlign O3AAlign MolTransforms SubstructMatch Subgraphs Depictor GraphMol
    DataStructs RDGeometryLib EigenSolvers Alignment Optimizer Trajectory
    Catalogs RDGeneral)
add_library(surfcomp_rdkit INTERFACE)
target_include_directories(surfcomp_rdkit SYSTEM INTERFACE ${RDKIT_INCLUDE_DIR})
foreach(_c IN LISTS _rdkit_components)
  find_library(RDKIT_${_c}_LIBRARY NAMES RDKit${_c} REQUIRED)
  target_link_libraries(surfcomp_rdkit INTERFACE ${RDKIT_${_c}_LIBRARY})
endforeach()
add_library(RDKit::RDKit ALIAS surfcomp_rdkit)

if(SURFCOMP_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(SURFCOMP_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
