# Finds the Exodus II C library (Debian: libexodusii-dev, libexoIIv2c; SEACAS'
# libexodus elsewhere). Defines ExodusII::ExodusII. exodusII.h includes
# netcdf.h, whose directory is added too; the library itself links its NetCDF
# (Debian's libexoIIv2c the MPI one), so NetCDF is not linked here: a second,
# serial libnetcdf in the process would bring the serial HDF5 with it.
find_path(ExodusII_INCLUDE_DIR exodusII.h)
find_path(ExodusII_NetCDF_INCLUDE_DIR netcdf.h HINTS ${ExodusII_INCLUDE_DIR})
find_library(ExodusII_LIBRARY NAMES exoIIv2c exodus)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(ExodusII DEFAULT_MSG ExodusII_LIBRARY ExodusII_INCLUDE_DIR ExodusII_NetCDF_INCLUDE_DIR)
if(ExodusII_FOUND AND NOT TARGET ExodusII::ExodusII)
  add_library(ExodusII::ExodusII UNKNOWN IMPORTED)
  set_target_properties(ExodusII::ExodusII PROPERTIES IMPORTED_LOCATION ${ExodusII_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES "${ExodusII_INCLUDE_DIR};${ExodusII_NetCDF_INCLUDE_DIR}")
endif()
mark_as_advanced(ExodusII_INCLUDE_DIR ExodusII_NetCDF_INCLUDE_DIR ExodusII_LIBRARY)
