# brickyard_add_graph_test(NAME <test> GRAPH <graph.json>
#                          [EXPECT_EXIT <code>]       # default 0
#                          [EXPECT_OUTPUT <regex>]    # CMake regular expression over stdout + stderr
#                          [EXPECT_ABSENT <regex>]    # ... that the output must not match
#                          [ARGS <arg>...]            # more `brickyard run` arguments: --set, --seed, --duration...
#                          [PLUGIN_PATH <dir>...]     # default: the folder of every brickyard_add_plugin() target
#                          [LAUNCHER <cmd>...])       # a command the run is started through (a private network
#                                                     # namespace, a timeout, valgrind)
#
# A CTest test that runs the host on a graph,
#   brickyard run <graph> --plugin-path <dir>... <args>...
# and passes only when the exit code is EXPECT_EXIT *and* the output matches EXPECT_OUTPUT. The
# host is brickyard::brickyard (the installed executable, imported by find_package(brickyard)).
# Exit codes: 0 success, 1 the run failed (an assertion, a plugin error), 2 invalid input. A
# failing case says why, so match its reason, e.g.
#   EXPECT_EXIT 1 EXPECT_OUTPUT "node 'check' \\(testing.assert_sink\\): sample 1 \\(value 5\\): expected 10"
# GRAPH is relative to the current source folder, PLUGIN_PATH to the current build folder. The
# run's working directory is the current build folder. BRICKYARD_GRAPH_TEST_ARGS (a cache list)
# is added to every run, e.g. -DBRICKYARD_GRAPH_TEST_ARGS="--domain;7" to keep parallel runs on
# one machine apart.
set(_BRICKYARD_RUN_GRAPH_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/brickyard_run_graph.cmake")
set(BRICKYARD_GRAPH_TEST_ARGS "" CACHE STRING "Arguments added to every brickyard_add_graph_test() run, e.g. --domain;7")

function(brickyard_add_graph_test)
  cmake_parse_arguments(PARSE_ARGV 0 ARG "" "NAME;GRAPH;EXPECT_EXIT;EXPECT_OUTPUT;EXPECT_ABSENT" "ARGS;PLUGIN_PATH;LAUNCHER")
  if(NOT ARG_NAME OR NOT ARG_GRAPH)
    message(FATAL_ERROR "brickyard_add_graph_test: NAME and GRAPH are required")
  endif()
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "brickyard_add_graph_test(${ARG_NAME}): unknown arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT DEFINED ARG_EXPECT_EXIT)
    set(ARG_EXPECT_EXIT 0)
  elseif(NOT ARG_EXPECT_EXIT MATCHES "^[0-9]+$")
    message(FATAL_ERROR "brickyard_add_graph_test(${ARG_NAME}): EXPECT_EXIT ${ARG_EXPECT_EXIT}: expected an exit code")
  endif()
  if(TARGET brickyard::brickyard)
    set(host brickyard::brickyard)
  elseif(TARGET brickyard)  # inside the Brickyard source tree
    set(host brickyard)
  else()
    message(FATAL_ERROR "brickyard_add_graph_test(${ARG_NAME}): no brickyard::brickyard target (find_package(brickyard) first)")
  endif()
  get_filename_component(graph "${ARG_GRAPH}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  set(dirs "")
  foreach(d IN LISTS ARG_PLUGIN_PATH)
    get_filename_component(d "${d}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
    list(APPEND dirs "${d}")
  endforeach()

  # What is known now goes to <id>.data.cmake; the host's and the plugins' paths, generator
  # expressions, to <id>-<config>.cmake, written once every plugin target exists (end of the
  # top-level folder), so the default plugin path sees plugins added after this call too.
  string(MAKE_C_IDENTIFIER "${ARG_NAME}" id)
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/brickyard_graph_tests")
  string(CONCAT data "set(GRAPH [==[${graph}]==])\n" "set(EXPECT_EXIT ${ARG_EXPECT_EXIT})\n"
         "set(EXPECT_OUTPUT [==[${ARG_EXPECT_OUTPUT}]==])\n" "set(EXPECT_ABSENT [==[${ARG_EXPECT_ABSENT}]==])\n" "set(LAUNCHER")
  foreach(a IN LISTS ARG_LAUNCHER)
    string(APPEND data " [==[${a}]==]")
  endforeach()
  string(APPEND data ")\nset(RUN_ARGS")
  foreach(a IN LISTS ARG_ARGS BRICKYARD_GRAPH_TEST_ARGS)
    string(APPEND data " [==[${a}]==]")
  endforeach()
  string(APPEND data ")\nset(PLUGIN_PATH")
  foreach(d IN LISTS dirs)
    string(APPEND data " [==[${d}]==]")
  endforeach()
  string(APPEND data ")\n")
  file(WRITE "${dir}/${id}.data.cmake" "${data}")

  if(ARG_PLUGIN_PATH)
    set(default_path 0)
  else()
    set(default_path 1)
  endif()
  set_property(GLOBAL APPEND PROPERTY _BRICKYARD_GRAPH_TESTS "${id}|${dir}|${host}|${default_path}|${_BRICKYARD_RUN_GRAPH_SCRIPT}")
  get_property(deferred GLOBAL PROPERTY _BRICKYARD_GRAPH_TESTS_DEFERRED)
  if(NOT deferred)
    set_property(GLOBAL PROPERTY _BRICKYARD_GRAPH_TESTS_DEFERRED TRUE)
    cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL _brickyard_write_graph_tests)
  endif()

  add_test(NAME "${ARG_NAME}" COMMAND "${CMAKE_COMMAND}" -P "${dir}/${id}-$<CONFIG>.cmake"
           WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  set_property(TEST "${ARG_NAME}" APPEND PROPERTY LABELS brickyard_graph)
endfunction()

function(_brickyard_write_graph_tests)
  get_property(tests GLOBAL PROPERTY _BRICKYARD_GRAPH_TESTS)
  get_property(plugins GLOBAL PROPERTY BRICKYARD_PLUGIN_TARGETS)
  foreach(t IN LISTS tests)
    string(REPLACE "|" ";" f "${t}")
    list(GET f 0 id)
    list(GET f 1 dir)
    list(GET f 2 host)
    list(GET f 3 default_path)
    list(GET f 4 runner)
    set(text "set(BRICKYARD_EXE [==[$<TARGET_FILE:${host}>]==])\ninclude([==[${dir}/${id}.data.cmake]==])\n")
    if(default_path)
      foreach(p IN LISTS plugins)
        string(APPEND text "list(APPEND PLUGIN_PATH [==[$<TARGET_FILE_DIR:${p}>]==])\n")
      endforeach()
    endif()
    string(APPEND text "include([==[${runner}]==])\n")
    file(GENERATE OUTPUT "${dir}/${id}-$<CONFIG>.cmake" CONTENT "${text}")
  endforeach()
endfunction()
