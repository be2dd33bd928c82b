# brickyard_unit_tests(AREA SOURCES <files> LINK <libraries>): an area's unit tests, kept in the
# tests/ folder beside its code and built into one executable of its own, brickyard_<AREA>_tests,
# whose GoogleTest cases join CTest labelled unit.AREA (`ctest -L unit` runs every area's,
# `ctest -L unit.planning` one area's). An edit to one area's algorithm rebuilds its library, its
# plugins and this executable, and no other area's tests:
#   ninja brickyard_planning_tests && ctest --test-dir build -L unit.planning    (docs/testing.md)
# Test helpers shared by areas (the AV-21 from its vehicle file, synthetic shapes) are in
# tests/support/. Nothing is added when BRICKYARD_TESTS is off.
function(brickyard_unit_tests area)
  if(NOT BRICKYARD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK" ${ARGN})
  set(target brickyard_${area}_tests)
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_LINK} GTest::gtest_main)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_compile_definitions(${target} PRIVATE BRICKYARD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(${target} DISCOVERY_TIMEOUT 30 PROPERTIES LABELS unit.${area})
endfunction()
