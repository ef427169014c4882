# Finds Gmsh (Debian: libgmsh-dev). Defines Gmsh::Gmsh (the C++ API, for
# programs that call Gmsh themselves, such as the tests that write meshes),
# Gmsh_C_INCLUDE_DIR (gmshc.h, the C API) and Gmsh_SONAME, the name the
# library is loaded by at run time: Tribos' reader does not link libgmsh but
# loads it when a Gmsh mesh is first read (packages/mesh/src/detail/Tribos_GmshApi.hpp).
find_path(Gmsh_INCLUDE_DIR gmsh.h)
find_path(Gmsh_C_INCLUDE_DIR gmshc.h)
find_library(Gmsh_LIBRARY gmsh)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Gmsh DEFAULT_MSG Gmsh_LIBRARY Gmsh_INCLUDE_DIR Gmsh_C_INCLUDE_DIR)
if(Gmsh_FOUND)
  # libgmsh.so -> libgmsh.so.MAJOR.MINOR -> libgmsh.so.MAJOR.MINOR.PATCH; the
  # soname is MAJOR.MINOR.
  get_filename_component(Gmsh_LIBRARY_REAL "${Gmsh_LIBRARY}" REALPATH)
  get_filename_component(_gmsh_file "${Gmsh_LIBRARY_REAL}" NAME)
  if(_gmsh_file MATCHES "^(libgmsh\\.so\\.[0-9]+\\.[0-9]+)")
    set(Gmsh_SONAME "${CMAKE_MATCH_1}")
  else()
    set(Gmsh_SONAME "${_gmsh_file}")
  endif()
  if(NOT TARGET Gmsh::Gmsh)
    add_library(Gmsh::Gmsh UNKNOWN IMPORTED)
    set_target_properties(Gmsh::Gmsh PROPERTIES IMPORTED_LOCATION ${Gmsh_LIBRARY}
      INTERFACE_INCLUDE_DIRECTORIES ${Gmsh_INCLUDE_DIR})
  endif()
endif()
