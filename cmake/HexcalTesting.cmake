# hexcal_add_test(NAME name SOURCES a_test.cc ... LIBS lib ...)
# One executable per test file, registered in CTest as <folder>/<name>, with the
# shared gtest main (tests/test_main.cc) that reseeds the RNG for every test.
function(hexcal_add_test)
  if(HEXCAL_FUZZ)
    return()  # a fuzz build has no tests/ (root CMakeLists.txt), so no test main
  endif()
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  get_filename_component(folder "${CMAKE_CURRENT_SOURCE_DIR}" NAME)
  set(target "${folder}_${T_NAME}")
  add_executable(${target} ${T_SOURCES})
  target_link_libraries(${target} PRIVATE ${T_LIBS} hexcal_test_support)
  add_test(NAME "${folder}/${T_NAME}" COMMAND ${target})
  set_tests_properties("${folder}/${T_NAME}" PROPERTIES
    ENVIRONMENT "HEXCAL_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
  if(T_LABELS)
    set_tests_properties("${folder}/${T_NAME}" PROPERTIES LABELS "${T_LABELS}")
  endif()
endfunction()
