# cmake -DMODE=install|example ... -P run_installed.cmake (examples/CMakeLists.txt)
#
# MODE=install: installs BUILD_DIR into a fresh PREFIX and checks the tree:
#   the package config files, the Find modules, every library and program,
#   the public headers in include/tribos and internal ones apart in
#   include/tribos/internal (and no test-only header), and that the installed
#   program runs (tribos --print-parameters).
# MODE=example: configures SOURCE (a C++-only project) in a fresh BINARY against PREFIX alone,
#   checks that Tribos was found there, builds it and runs BINARY/EXAMPLE on
#   RANKS ranks with the arguments ARGS (a list); it must exit 0.
cmake_minimum_required(VERSION 3.18)
separate_arguments(MPIEXEC_FLAGS UNIX_COMMAND "${MPIEXEC_FLAGS}")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}): ${ARGN}")
  endif()
endfunction()

function(require_file path)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "not installed: ${path}")
  endif()
endfunction()

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE "${PREFIX}")
  run("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}")

  set(cmakedir "${PREFIX}/${LIBDIR}/cmake/Tribos")
  foreach(f TribosConfig.cmake TribosConfigVersion.cmake TribosTargets.cmake FindMETIS.cmake FindCHOLMOD.cmake)
    require_file("${cmakedir}/${f}")
  endforeach()
  foreach(lib core mesh fem qp friction feti contact semismooth io fclib fclib_solve driver)
    file(GLOB found "${PREFIX}/${LIBDIR}/libtribos_${lib}.*")
    if(NOT found)
      message(FATAL_ERROR "not installed: the library tribos_${lib} in ${PREFIX}/${LIBDIR}")
    endif()
  endforeach()
  # Public headers in include/tribos (the umbrella among them), the ones
  # they are built from in include/tribos/internal and not beside them.
  foreach(h Tribos.hpp Tribos_Types.hpp Tribos_Registry.hpp Tribos_QP.hpp Tribos_FrictionSolver.hpp Tribos_FetiContact.hpp
            Tribos_FetiProblem.hpp Tribos_FetiSolve.hpp Tribos_Monolithic.hpp Tribos_ResultSet.hpp Tribos_FCLIB.hpp
            Tribos_FCLIB_Solve.hpp Tribos_SemismoothStarNewton.hpp Tribos_Input.hpp Tribos_Run.hpp)
    require_file("${PREFIX}/${INCLUDEDIR}/tribos/${h}")
  endforeach()
  foreach(h Tribos_FileSystem.hpp Tribos_DenseBlas.hpp Tribos_AgreeOnError.hpp Tribos_SubdomainPseudoInverse.hpp
            Tribos_FetiOperators.hpp Tribos_QP_Utils.hpp)
    require_file("${PREFIX}/${INCLUDEDIR}/tribos/internal/${h}")
    if(EXISTS "${PREFIX}/${INCLUDEDIR}/tribos/${h}")
      message(FATAL_ERROR "internal header installed with the public ones: ${PREFIX}/${INCLUDEDIR}/tribos/${h}")
    endif()
  endforeach()
  file(GLOB_RECURSE test_only "${PREFIX}/*TestSupport*")
  if(test_only)
    message(FATAL_ERROR "test-only files installed: ${test_only}")
  endif()

  # The installed programs run from the prefix (RPATH, shared dependencies).
  foreach(exe tribos tribos_fclib)
    require_file("${PREFIX}/${BINDIR}/${exe}")
  endforeach()
  execute_process(COMMAND ${MPIEXEC} ${MPIEXEC_NUMPROC_FLAG} 1 ${MPIEXEC_FLAGS} "${PREFIX}/${BINDIR}/tribos" --print-parameters
                  RESULT_VARIABLE rc OUTPUT_VARIABLE xml)
  if(NOT rc EQUAL 0 OR NOT xml MATCHES "<ParameterList")
    message(FATAL_ERROR "installed tribos --print-parameters failed (${rc}):\n${xml}")
  endif()
  message(STATUS "installed into ${PREFIX}")

elseif(MODE STREQUAL "example")
  file(REMOVE_RECURSE "${BINARY}")
  # Only the scratch prefix: no package registry, no tree of this build.
  run("configure ${EXAMPLE}" "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${BINARY}" -DCMAKE_BUILD_TYPE=Release
      "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
      "-DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}")
  file(STRINGS "${BINARY}/CMakeCache.txt" tribos_dir REGEX "^Tribos_DIR:")
  string(REGEX REPLACE "^[^=]*=" "" tribos_dir "${tribos_dir}")
  string(FIND "${tribos_dir}" "${PREFIX}/" at)
  if(NOT at EQUAL 0)
    message(FATAL_ERROR "${EXAMPLE} found Tribos in ${tribos_dir}, not in ${PREFIX}")
  endif()
  run("build ${EXAMPLE}" "${CMAKE_COMMAND}" --build "${BINARY}" -j 2)
  run("run ${EXAMPLE}" ${MPIEXEC} ${MPIEXEC_NUMPROC_FLAG} ${RANKS} ${MPIEXEC_FLAGS} "${BINARY}/${EXAMPLE}" ${ARGS})

else()
  message(FATAL_ERROR "run_installed.cmake: MODE must be install or example")
endif()
