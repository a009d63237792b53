# hexcal_add_test(NAME name SOURCES a_test.cc ... LIBS lib ... [COST seconds])
# One executable per test file, registered in CTest as <folder>/<name>, with the
# shared gtest main (tests/test_main.cc) that reseeds the RNG for every test.
# COST (seconds under the sanitizers) lets CTest start the long tests first on a
# fresh machine, where it has no timings of its own: with -j2 a long test that
# starts last is the whole run's tail. Every executable of a folder in
# HEXCAL_SANITIZED_FOLDERS is also a dependency of the target
# hexcal_unit_tests, which `make sanitize` builds instead of everything (the
# CLI and its commands are half of that build and no sanitized test runs them).
set(HEXCAL_SANITIZED_FOLDERS core vision charts devices session sim report workflow)

function(hexcal_add_test)
  if(HEXCAL_FUZZ)
    return()  # a fuzz build has no tests/ (root CMakeLists.txt), so no test main
  endif()
  cmake_parse_arguments(T "" "NAME;COST" "SOURCES;LIBS;LABELS" ${ARGN})
  get_filename_component(folder "${CMAKE_CURRENT_SOURCE_DIR}" NAME)
  set(target "${folder}_${T_NAME}")
  add_executable(${target} ${T_SOURCES})
  target_link_libraries(${target} PRIVATE ${T_LIBS} hexcal_test_support)
  add_test(NAME "${folder}/${T_NAME}" COMMAND ${target})
  set_tests_properties("${folder}/${T_NAME}" PROPERTIES
    ENVIRONMENT "HEXCAL_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
  # Only the folders `make sanitize` runs (scripts/sanitize-ctest.sh): app/'s
  # tests link the whole CLI, which the sanitizer build leaves out.
  if(folder IN_LIST HEXCAL_SANITIZED_FOLDERS)
    set_property(GLOBAL APPEND PROPERTY HEXCAL_UNIT_TEST_TARGETS ${target})
  endif()
  if(T_COST)
    set_tests_properties("${folder}/${T_NAME}" PROPERTIES COST ${T_COST})
  endif()
  if(T_LABELS)
    set_tests_properties("${folder}/${T_NAME}" PROPERTIES LABELS "${T_LABELS}")
  endif()
endfunction()

# hexcal_add_tests(LIBS lib ... TESTS name ...)
# hexcal_add_test for each name, from name.cc, all with the same LIBS: a folder's
# plain tests in one list. A test with a COST or libraries of its own keeps a
# hexcal_add_test call.
function(hexcal_add_tests)
  cmake_parse_arguments(T "" "" "TESTS;LIBS" ${ARGN})
  foreach(name IN LISTS T_TESTS)
    hexcal_add_test(NAME ${name} SOURCES ${name}.cc LIBS ${T_LIBS})
  endforeach()
endfunction()

# The target of every unit test executable (and of helpers added to the property
# by hand); call once, after every add_subdirectory.
function(hexcal_add_unit_tests_target)
  get_property(targets GLOBAL PROPERTY HEXCAL_UNIT_TEST_TARGETS)
  if(targets)
    add_custom_target(hexcal_unit_tests DEPENDS ${targets})
  endif()
endfunction()
