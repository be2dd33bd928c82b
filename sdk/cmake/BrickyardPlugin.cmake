# brickyard_add_plugin(<target> SOURCES <files...> [LINK <libs...>])
#
# Builds a plugin library the way the host expects it: a MODULE (never linked against),
# hidden visibility so only the entry point is exported, and no undefined symbols so a
# missing dependency fails at link time instead of at dlopen.
function(brickyard_add_plugin target)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "brickyard_add_plugin(${target}): SOURCES is required")
  endif()
  add_library(${target} MODULE ${ARG_SOURCES})
  # brickyard_add_graph_test() puts the folder of every plugin of the project on the plugin path.
  set_property(GLOBAL APPEND PROPERTY BRICKYARD_PLUGIN_TARGETS ${target})
  target_link_libraries(${target} PRIVATE brickyard::sdk ${ARG_LINK})
  target_compile_features(${target} PRIVATE cxx_std_17)
  set_target_properties(${target} PROPERTIES
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_link_options(${target} PRIVATE "LINKER:--no-undefined")
  if(BRICKYARD_PLUGIN_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${BRICKYARD_PLUGIN_OUTPUT_DIR})
  endif()
  if(BRICKYARD_PLUGIN_INSTALL_DIR AND BRICKYARD_PLUGIN_INSTALL_COMPONENT)
    # A component of its own, left out of a plain install (the simulator's plugins).
    install(TARGETS ${target} LIBRARY DESTINATION ${BRICKYARD_PLUGIN_INSTALL_DIR}
            COMPONENT ${BRICKYARD_PLUGIN_INSTALL_COMPONENT} EXCLUDE_FROM_ALL)
  elseif(BRICKYARD_PLUGIN_INSTALL_DIR)
    install(TARGETS ${target} LIBRARY DESTINATION ${BRICKYARD_PLUGIN_INSTALL_DIR})
  endif()
endfunction()
