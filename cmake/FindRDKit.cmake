# Finds RDKit's headers and the libraries surfcomp::core links, as the imported target
# RDKit::RDKit. Debian's RDKit ships no CMake config, so this module looks them up by name. The
# build uses it (SurfcompDependencies.cmake) and so does an installed surfcompConfig.cmake, where
# the static surfcomp::core needs RDKit at the consumer's link.
# Sets RDKit_FOUND and RDKIT_INCLUDE_DIR.
set(_rdkit_components
    FileParsers SmilesParse PartialCharges Descriptors DistGeomHelpers DistGeometry
    ForceFieldHelpers ForceField
    MolAlign O3AAlign MolTransforms SubstructMatch Subgraphs Depictor GraphMol
    DataStructs RDGeometryLib EigenSolvers Alignment Optimizer Trajectory
    Catalogs RDGeneral)

find_path(RDKIT_INCLUDE_DIR GraphMol/ROMol.h PATH_SUFFIXES rdkit)
set(_rdkit_library_vars)
foreach(_c IN LISTS _rdkit_components)
  find_library(RDKIT_${_c}_LIBRARY NAMES RDKit${_c})
  list(APPEND _rdkit_library_vars RDKIT_${_c}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(RDKit REQUIRED_VARS RDKIT_INCLUDE_DIR ${_rdkit_library_vars})

if(RDKit_FOUND AND NOT TARGET RDKit::RDKit)
  add_library(RDKit::RDKit INTERFACE IMPORTED)
  set_target_properties(RDKit::RDKit PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${RDKIT_INCLUDE_DIR}")
  foreach(_var IN LISTS _rdkit_library_vars)
    set_property(TARGET RDKit::RDKit APPEND PROPERTY INTERFACE_LINK_LIBRARIES "${${_var}}")
  endforeach()
endif()
unset(_rdkit_components)
unset(_rdkit_library_vars)
