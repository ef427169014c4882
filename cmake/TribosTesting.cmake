# tribos_add_test(NAME name SOURCES ... LIBS ... [RANKS 1 2 3] [LABELS ...])
# Builds one test executable and registers it once per rank count; under root
# mpiexec needs --allow-run-as-root, and 2-core machines need --oversubscribe.
set(TRIBOS_MPIEXEC_FLAGS --oversubscribe)
execute_process(COMMAND id -u OUTPUT_VARIABLE _tribos_uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(_tribos_uid STREQUAL "0")
  list(APPEND TRIBOS_MPIEXEC_FLAGS --allow-run-as-root)
endif()

function(tribos_add_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS;RANKS;LABELS;ARGS" ${ARGN})
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS})
  foreach(np IN LISTS T_RANKS)
    add_test(NAME ${T_NAME}_np${np}
      COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} ${TRIBOS_MPIEXEC_FLAGS}
              $<TARGET_FILE:${T_NAME}> ${T_ARGS})
    set_tests_properties(${T_NAME}_np${np} PROPERTIES PROCESSORS ${np}
      LABELS "${T_LABELS}" TIMEOUT 600
      ENVIRONMENT "OMPI_MCA_rmaps_base_oversubscribe=1;TRIBOS_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
  endforeach()
endfunction()
