# A DDS program of another vendor on ROS 2's names (issue 45, docs/ros2.md): tests/ros2/cyclone_peer,
# Cyclone DDS (Debian's cyclonedds-dev, installed by scripts/setup) with its types compiled by
# Cyclone's idlc from what `brickyard ros2 idl` writes at build time: no Brickyard code in it.
find_package(CycloneDDS QUIET)
find_program(CYCLONE_IDLC idlc)
if(NOT CycloneDDS_FOUND OR NOT CYCLONE_IDLC)
  message(STATUS "Cyclone DDS not found: evidence.ros2_cyclone is not built (scripts/setup installs cyclonedds-dev)")
  return()
endif()
set(ros2_dir ${CMAKE_CURRENT_BINARY_DIR}/ros2)
add_custom_command(OUTPUT ${ros2_dir}/brickyard_msgs_dds.idl
  COMMAND ${CMAKE_COMMAND} -E make_directory ${ros2_dir}
  COMMAND $<TARGET_FILE:brickyard> ros2 idl --out ${ros2_dir}/brickyard_msgs_dds.idl
  DEPENDS brickyard
  COMMENT "brickyard ros2 idl: the SDK's messages on ROS 2's names")
add_custom_command(OUTPUT ${ros2_dir}/brickyard_msgs_dds.c ${ros2_dir}/brickyard_msgs_dds.h
  COMMAND ${CYCLONE_IDLC} -o ${ros2_dir} ${ros2_dir}/brickyard_msgs_dds.idl
  DEPENDS ${ros2_dir}/brickyard_msgs_dds.idl
  COMMENT "idlc: Cyclone DDS's types for them")
add_executable(cyclone_peer ros2/cyclone_peer.c ${ros2_dir}/brickyard_msgs_dds.c)
target_include_directories(cyclone_peer PRIVATE ${ros2_dir})
target_link_libraries(cyclone_peer PRIVATE CycloneDDS::ddsc)
set_target_properties(cyclone_peer PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
by_next_domain(d)
set(race_graph "")
if(BRICKYARD_SIM)
  set(race_graph ${PROJECT_SOURCE_DIR}/configs/race.json)
endif()
add_test(NAME evidence.ros2_cyclone
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/ros2_cyclone.sh ${BY} $<TARGET_FILE:cyclone_peer> ${CMAKE_CURRENT_SOURCE_DIR}/clients
          ${CMAKE_CURRENT_SOURCE_DIR}/graphs/ros2/cyclone_source.json ${d} ${RUNS}/ros2_cyclone ${race_graph})
set_tests_properties(evidence.ros2_cyclone PROPERTIES TIMEOUT 180)
