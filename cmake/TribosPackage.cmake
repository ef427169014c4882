# The one place that makes a target a public Tribos library (the role of
# TriBITS' tribits_add_library(... HEADERS ...) in Trilinos packages):
#
#   tribos_install_library(<target> [EXPORT_NAME <name>] [HEADER_DIR <dir>] [HEADERS <h>...])
#
# - include directories: HEADER_DIR (default src/ of the calling package) in
#   the build tree; once installed include/tribos, then include/tribos/internal;
# - the exported name Tribos::<name> (default: the target without its
#   "tribos_" prefix, so tribos_qp is Tribos::qp) and the same name as an
#   ALIAS in the build tree, so that code written against the installed
#   package also builds inside this one;
# - installation of the library into the export set TribosTargets and of
#   its headers: HEADERS, or every *.hpp of HEADER_DIR (the Trilinos idiom
#   file(GLOB HEADERS ${DIR}/*.hpp): a header added to src/ is installed
#   without touching any CMakeLists.txt). A header named in
#   TRIBOS_PUBLIC_HEADERS goes to include/tribos, every other one to
#   include/tribos/internal (see there).
#
# The package keeps its own add_library (adding a source is one line there)
# and target_link_libraries; this function does the rest. Tribos::Tribos
# (tribos_finish_package) links every library registered here.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TRIBOS_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/tribos)
set(TRIBOS_INSTALL_INTERNAL_INCLUDEDIR ${TRIBOS_INSTALL_INCLUDEDIR}/internal)

# The public interface, by file name: what an application includes (the
# umbrella Tribos.hpp and the headers of docs/embedding.md, the QP solvers,
# the mesh readers, the result writers, FCLIB and the driver). They are
# installed in include/tribos; the headers they are built from (kernels,
# operators, solver internals) in include/tribos/internal, on the include
# path after the public ones (a public header includes them by name), and
# they may change in any release. The build tree keeps every header beside
# its sources. A name here that no library installs is an error
# (tribos_finish_package), so a renamed header cannot drop out silently.
set(TRIBOS_PUBLIC_HEADERS
  # core
  Tribos_Types.hpp Tribos_Error.hpp Tribos_MpiStartup.hpp Tribos_Registry.hpp Tribos_LocalCsr.hpp
  Tribos_FrictionLaw.hpp
  # mesh and fem
  Tribos_Mesh.hpp Tribos_MeshFile.hpp Tribos_Decomposition.hpp Tribos_Discretization.hpp
  Tribos_Elasticity.hpp Tribos_Assembly.hpp Tribos_Loads.hpp Tribos_NodalVector.hpp Tribos_RigidMotions.hpp
  Tribos_Monolithic.hpp
  # qp and friction
  Tribos_QP.hpp Tribos_QP_Solver.hpp Tribos_QP_Status.hpp Tribos_QP_Factory.hpp Tribos_QP_ConstraintSet.hpp
  Tribos_QP_EqualityConstraint.hpp Tribos_QP_MPRGP.hpp Tribos_QP_MPGP.hpp Tribos_QP_SMALBE.hpp
  Tribos_FrictionSolver.hpp Tribos_ContactDual.hpp Tribos_DualTransform.hpp
  # feti and contact: the embedding API (Tribos.hpp includes it all)
  Tribos.hpp Tribos_FetiProblem.hpp Tribos_ConstraintRows.hpp Tribos_ContactConstraint.hpp Tribos_ContactSearch.hpp
  Tribos_FetiContact.hpp Tribos_FetiSolve.hpp Tribos_ResultKKT.hpp Tribos_TpetraSubdomain.hpp
  Tribos_ContactConditions.hpp Tribos_ContactSolver.hpp Tribos_AssembledContact.hpp Tribos_SolveResult.hpp
  # semismooth, io, fclib, driver
  Tribos_SemismoothStarNewton.hpp Tribos_ResultSet.hpp Tribos_ResultWriter.hpp Tribos_ParameterReader.hpp
  Tribos_FCLIB.hpp Tribos_FCLIB_SparseMatrix.hpp Tribos_FCLIB_Accuracy.hpp Tribos_FCLIB_Solve.hpp
  Tribos_FCLIB_Export.hpp Tribos_Driver.hpp Tribos_Input.hpp Tribos_Run.hpp Tribos_RunReport.hpp)

set(TRIBOS_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tribos)

function(tribos_install_library target)
  cmake_parse_arguments(L "" "EXPORT_NAME;HEADER_DIR" "HEADERS" ${ARGN})
  if(L_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "tribos_install_library(${target}): unknown arguments ${L_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT L_EXPORT_NAME)
    string(REGEX REPLACE "^tribos_" "" L_EXPORT_NAME "${target}")
  endif()
  if(NOT L_HEADER_DIR)
    set(L_HEADER_DIR src)
  endif()
  get_filename_component(header_dir "${L_HEADER_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(L_HEADERS)
    list(TRANSFORM L_HEADERS PREPEND "${CMAKE_CURRENT_SOURCE_DIR}/" REGEX "^[^/]")
  else()
    file(GLOB L_HEADERS CONFIGURE_DEPENDS "${header_dir}/*.hpp")
  endif()

  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    set(scope INTERFACE)
  else()
    set(scope PUBLIC)
    # Embedding applications may link the static libraries into their own
    # shared libraries.
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  target_include_directories(${target} ${scope}
    $<BUILD_INTERFACE:${header_dir}>
    $<INSTALL_INTERFACE:${TRIBOS_INSTALL_INCLUDEDIR}>
    $<INSTALL_INTERFACE:${TRIBOS_INSTALL_INTERNAL_INCLUDEDIR}>)
  # The headers use C++17: so must every code that includes them.
  target_compile_features(${target} ${scope} cxx_std_17)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${L_EXPORT_NAME})
  add_library(Tribos::${L_EXPORT_NAME} ALIAS ${target})

  install(TARGETS ${target} EXPORT TribosTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  set(public_headers "")
  set(internal_headers "")
  foreach(h IN LISTS L_HEADERS)
    get_filename_component(name "${h}" NAME)
    if(name IN_LIST TRIBOS_PUBLIC_HEADERS)
      list(APPEND public_headers "${h}")
      set_property(GLOBAL APPEND PROPERTY TRIBOS_INSTALLED_PUBLIC_HEADERS "${name}")
    else()
      list(APPEND internal_headers "${h}")
    endif()
  endforeach()
  install(FILES ${public_headers} DESTINATION ${TRIBOS_INSTALL_INCLUDEDIR})
  install(FILES ${internal_headers} DESTINATION ${TRIBOS_INSTALL_INTERNAL_INCLUDEDIR})
  set_property(GLOBAL APPEND PROPERTY TRIBOS_LIBRARIES ${target})
endfunction()

# An installed program, exported as Tribos::<its file name> (tribos,
# tribos_fclib) so that applications can run it from their own builds.
function(tribos_install_executable target)
  get_target_property(name ${target} OUTPUT_NAME)
  if(NOT name)
    set(name ${target})
  endif()
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  install(TARGETS ${target} EXPORT TribosTargets RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# Targets that carry third-party usage requirements (Trilinos, HDF5): no
# headers of their own, exported so that the imported Tribos targets carry
# the include directories and libraries; the package config finds the
# dependencies they name before it loads them.
function(tribos_export_dependency target export_name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  add_library(Tribos::${export_name} ALIAS ${target})
  install(TARGETS ${target} EXPORT TribosTargets)
endfunction()

# Called once at the end of the top-level CMakeLists.txt: Tribos::Tribos
# (every library), the export set, TribosConfig.cmake,
# TribosConfigVersion.cmake and the Find modules the config needs.
function(tribos_finish_package)
  get_property(installed GLOBAL PROPERTY TRIBOS_INSTALLED_PUBLIC_HEADERS)
  foreach(name IN LISTS TRIBOS_PUBLIC_HEADERS)
    if(NOT name IN_LIST installed)
      message(FATAL_ERROR "TRIBOS_PUBLIC_HEADERS (cmake/TribosPackage.cmake) names ${name}, which no library installs")
    endif()
  endforeach()
  get_property(libraries GLOBAL PROPERTY TRIBOS_LIBRARIES)
  add_library(tribos_all INTERFACE)
  target_link_libraries(tribos_all INTERFACE ${libraries})
  set_target_properties(tribos_all PROPERTIES EXPORT_NAME Tribos)
  add_library(Tribos::Tribos ALIAS tribos_all)
  install(TARGETS tribos_all EXPORT TribosTargets)

  install(EXPORT TribosTargets NAMESPACE Tribos:: DESTINATION ${TRIBOS_INSTALL_CMAKEDIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TribosConfig.cmake.in
    ${PROJECT_BINARY_DIR}/cmake/TribosConfig.cmake
    INSTALL_DESTINATION ${TRIBOS_INSTALL_CMAKEDIR})
  # Before 1.0 a minor version may change the interface: 0.2.x satisfies a
  # request for 0.2 and nothing else.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/TribosConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/cmake/TribosConfig.cmake ${PROJECT_BINARY_DIR}/cmake/TribosConfigVersion.cmake
                ${PROJECT_SOURCE_DIR}/cmake/FindMETIS.cmake ${PROJECT_SOURCE_DIR}/cmake/FindCHOLMOD.cmake
                ${PROJECT_SOURCE_DIR}/cmake/FindGmsh.cmake ${PROJECT_SOURCE_DIR}/cmake/FindExodusII.cmake
          DESTINATION ${TRIBOS_INSTALL_CMAKEDIR})
endfunction()
