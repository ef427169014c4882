# Finds the numerics library of Siconos (Debian: libsiconos-numerics-dev),
# optional: only the FCLIB benchmark against Siconos' fc3d solvers uses it.
# Defines SiconosNumerics_FOUND and the imported target
# SiconosNumerics::SiconosNumerics (include directories <prefix>/siconos and
# <prefix>/siconos/numerics, as its headers include SiconosConfig.h and each
# other by bare name).
find_path(SiconosNumerics_INCLUDE_DIR fc3d_Solvers.h PATH_SUFFIXES siconos/numerics)
find_path(SiconosNumerics_CONFIG_DIR SiconosConfig.h PATH_SUFFIXES siconos)
find_library(SiconosNumerics_LIBRARY siconos_numerics)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SiconosNumerics DEFAULT_MSG
  SiconosNumerics_LIBRARY SiconosNumerics_INCLUDE_DIR SiconosNumerics_CONFIG_DIR)
mark_as_advanced(SiconosNumerics_INCLUDE_DIR SiconosNumerics_CONFIG_DIR SiconosNumerics_LIBRARY)
if(SiconosNumerics_FOUND AND NOT TARGET SiconosNumerics::SiconosNumerics)
  add_library(SiconosNumerics::SiconosNumerics UNKNOWN IMPORTED)
  set_target_properties(SiconosNumerics::SiconosNumerics PROPERTIES
    IMPORTED_LOCATION "${SiconosNumerics_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SiconosNumerics_INCLUDE_DIR};${SiconosNumerics_CONFIG_DIR}")
endif()
