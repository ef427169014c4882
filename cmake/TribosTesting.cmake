# tribos_add_test(NAME name SOURCES ... LIBS ... [UNIT_TESTS] [RANKS 1 2 3] [LABELS ...] [ARGS ...])
# Builds one test executable and registers it once per rank count; under root
# mpiexec needs --allow-run-as-root, and 2-core machines need --oversubscribe.
# UNIT_TESTS: the sources hold TEUCHOS_UNIT_TESTs, run by the shared main
# (test/support/Tribos_UnitTestMain.cpp); without it a source has its main.
set(TRIBOS_MPIEXEC_FLAGS --oversubscribe)
execute_process(COMMAND id -u OUTPUT_VARIABLE _tribos_uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(_tribos_uid STREQUAL "0")
  list(APPEND TRIBOS_MPIEXEC_FLAGS --allow-run-as-root)
endif()

# What test programs share (test/support: Tribos_TestSupport.hpp): on the
# include path of every test, never installed with the public headers.
add_library(tribos_test_support INTERFACE)
target_include_directories(tribos_test_support INTERFACE ${PROJECT_SOURCE_DIR}/test/support)
add_library(tribos_unit_test_main STATIC ${PROJECT_SOURCE_DIR}/test/support/Tribos_UnitTestMain.cpp)
target_link_libraries(tribos_unit_test_main PRIVATE tribos_core)

function(tribos_add_test)
  cmake_parse_arguments(T "UNIT_TESTS" "NAME" "SOURCES;LIBS;RANKS;LABELS;ARGS" ${ARGN})
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} tribos_test_support)
  if(T_UNIT_TESTS)
    target_link_libraries(${T_NAME} PRIVATE tribos_unit_test_main)
  endif()
  foreach(np IN LISTS T_RANKS)
    add_test(NAME ${T_NAME}_np${np}
      COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} ${TRIBOS_MPIEXEC_FLAGS}
              $<TARGET_FILE:${T_NAME}> ${T_ARGS})
    set_tests_properties(${T_NAME}_np${np} PROPERTIES PROCESSORS ${np}
      LABELS "${T_LABELS}" TIMEOUT 600
      ENVIRONMENT "OMPI_MCA_rmaps_base_oversubscribe=1;TRIBOS_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
  endforeach()
endfunction()

# Every test also gets the label of the package that adds it: the directory
# under packages/ (qp, friction, ...) or the top directory (drivers, test),
# so that `ctest -L qp` runs one package. Set through the directory property
# LABELS once every directory is known, so that tests added by a plain
# add_test are labelled too.
function(_tribos_package_label dir out)
  file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${dir}")
  string(REPLACE "/" ";" parts "${rel}")
  list(GET parts 0 label)
  list(LENGTH parts depth)
  if(label STREQUAL "packages")
    if(depth GREATER 1)
      list(GET parts 1 label)
    else()
      set(label "")  # the directory of the packages adds no test of its own
    endif()
  endif()
  set(${out} "${label}" PARENT_SCOPE)
endfunction()

function(_tribos_label_tests_by_package dir)
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    _tribos_package_label("${sub}" label)
    get_property(labels DIRECTORY "${sub}" PROPERTY LABELS)
    if(label AND NOT label IN_LIST labels)
      set_property(DIRECTORY "${sub}" APPEND PROPERTY LABELS "${label}")
    endif()
    _tribos_label_tests_by_package("${sub}")
  endforeach()
endfunction()

if(CMAKE_VERSION VERSION_GREATER_EQUAL 3.19)
  cmake_language(DEFER CALL _tribos_label_tests_by_package "${CMAKE_CURRENT_SOURCE_DIR}")
endif()
