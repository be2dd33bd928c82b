# The graph tests (tests/graphs). Included by tests/CMakeLists.txt.

# ---- graph tests: tests/graphs/*.json; fail_* must exit 1 and say why. Registered with the SDK's
# brickyard_add_graph_test (the exit code and the message together), as a plugin's own project
# registers its graphs (docs/testing.md), run in a private network namespace ----
set(fail_assert_why    "node 'check' \\(testing.expect\\): 1 of 1 expectations failed: /0 value sample to sample decreasing, always in the whole run: sample 1 at 0.100 s: value = 1 after 0 \\(4 of 5 samples failed\\)")
set(fail_expect_every_failure_why "error check: expectation failed: /0 count within \\[1, 5\\]: 11 samples.*error check: expectation failed: /2 speed\\[\\*\\] within \\[20, 60\\], always in the whole run: sample 0 at 0.000 s: speed\\[0\\] = [0-9.]+ \\(11 of 11 samples failed\\).*error check: expectation failed: /3 poses\\[3\\].x equals 0, eventually in the whole run: never held over 11 samples.*node 'check' \\(testing.expect\\): 3 of 4 expectations failed \\(each above\\)")
set(fail_expect_fusion_naive_follows_jump_why "expectation failed: /1 \\(x, y\\) within 0.5 of ref's \\(x, y\\), always in \\[1 s, 4 s\\]: sample [0-9]+ at 2.[0-9]+ s: distance 1.[0-9]+.*node 'check' \\(testing.expect\\): 2 of 6 expectations failed")
set(fail_configure_why "node 'broken' \\(testing.transform\\) failed in configure: configured to fail in configure")
set(fail_sim_wall_contact_why "node 'referee' \\(sim.referee\\): crash: wall contact at s = [0-9.]+ m")
set(fail_sim_gnss_wrong_offset_why "node 'check' \\(sim.gnss_checker\\): fix at t = 1.000 s is 0.51 m from the expected position")
set(fail_localization_naive_no_emergency_why "node 'score' \\(sim.localization_scorer\\): EMERGENCY never raised")
set(fail_perception_wall_not_grown_why "node 'score' \\(sim.perception_scorer\\): [0-9]+ false obstacles \\(at most 0 allowed\\)")
set(fail_resilient_naive_hits_wall_why "node 'referee' \\(sim.referee\\): crash: wall contact at s = [0-9.]+ m")
set(fail_obstacles_racing_line_why "node 'referee' \\(sim.referee\\): obstacle passed -?[0-9.]+ m off at s = [0-9.]+ m \\(at least 1.00 m required\\)")
set(fail_race_car_stops_why "node 'referee' \\(sim.referee\\): did not finish: 0 of 1 laps; the car stopped at s = [0-9.]+ m and stood 2.0 s")
set(fail_race_ends_by_duration_why "node 'referee' \\(sim.referee\\): did not finish: 0 of 2 laps; the run ended at t = 10.0 s with the car at s = [0-9.]+ m")
set(fail_race_pylon_hit_why "node 'referee' \\(sim.referee\\): obstacle passed -?[0-9.]+ m off at s = [0-9.]+ m \\(at least 0.50 m required\\)")
# The headline run must hand steering to the wall follower and back before it ends well.
set(resilient_ims_fault_in_turn_want "manager: PATH -> WALL_FOLLOW at t = [0-9.]+ s: localization EMERGENCY.*manager: WALL_FOLLOW -> PATH at t = .*\\[brickyard\\] success")
set(fail_step_why      "node 'broken' \\(testing.transform\\) failed in step: configured to fail at sample 5")
set(fail_step_handed_out_why "node 'broken' \\(testing.transform\\) failed in step: configured to fail at sample 5")
set(fail_expect_road_graph_no_obstacle_why "expectation failed: /5 \\(poses\\[\\*\\].x, poses\\[\\*\\].y\\) at least 2 from \\(4.433, -297.876\\), always in \\[1 s, 3 s\\]: sample [0-9]+ at 1.[0-9]+ s: poses\\[[0-9]+\\].x = [-0-9.]+, poses\\[[0-9]+\\].y = [-0-9.]+: [0-9.]+ from it.*node 'check' \\(testing.expect\\): 1 of 6 expectations failed")
set(fail_latency_age_why "node 'check' \\(testing.expect\\): 1 of 1 expectations failed: /0 age \\(arrival less header.stamp_ns\\) within \\[0, 0.01\\] s: sample 0 at 0.050000 s stamped 0.000000 s: 0.050000 s old")
# The race through the CAN bus (docs/vehicle-interface.md): one clean lap, within 1 % of the same
# stack wired straight to the car (race_direct_ims.json: 59.94 s, so 59.34 to 60.54 s), and on a
# lossy bus the gaps counted and no command timeout. Graphs with two nodes on a UDP wire (these,
# and sim_gnss_wire's receiver) are reproducible on one thread only (two steps side by side race
# for the socket).
set(race_direct_ims_want "info referee: lap 1: 59\\.9[0-9]* s.*\\[brickyard\\] success")
set(race_can_ims_want "info referee: lap 1: (59\\.[3-9]|60\\.[0-5])[0-9]* s.*dbw +sim.drive_by_wire .* timeouts 0.*vehicle +vehicle_interface.raptor_dbw .* watchdog_trips 0 · wheel_speed_report_bad 0 .* wheel_speed_report_received [0-9]+.*\\[brickyard\\] success")
set(race_can_ims_lossy_want "info referee: lap 1: (59\\.[3-9]|60\\.[0-5])[0-9]* s.*dbw +sim.drive_by_wire .* lost_in [1-9][0-9]+ · lost_out [1-9][0-9]+ .* steering_cmd_counter_skips [1-9][0-9]+ · .* timeouts 0.*vehicle +vehicle_interface.raptor_dbw .* steering_report_counter_skips [1-9][0-9]+ .* watchdog_trips 0.*\\[brickyard\\] success")
# The stack falls silent: the interface stops the car, then its heartbeat; the drive-by-wire holds it.
set(can_stack_silent_stops_want "vehicle: commands: ACTIVE -> STOPPING.*vehicle: commands: STOPPING -> HANDED_OVER: stopped in [0-9.]+ m and [0-9.]+ s; ct_report's heartbeat stops.*dbw: drive-by-wire: commands or heartbeat lost: braking.*\\[brickyard\\] success")
# Race control's flags through the same bus (docs/race-control.md): sim.race_control's judge says
# each flag met within the distance the car needs (and fails the run otherwise); the manager's
# transition, and the acknowledgement the simulated drive-by-wire read back in ct_report.
set(race_control_yellow_want "manager: race control: RACING -> CAUTION at t = 8\\.0[0-9]+ s: track flag YELLOW: speed capped at 26\\.8 m/s.*race_control: YELLOW at 8\\.000 s from [0-9.]+ m/s: 26\\.8 m/s reached after [0-9.]+ m, within the [0-9.]+ m allowed.*dbw +sim\\.drive_by_wire .* track_cond_ack 3 · veh_sig_ack 1.*manager +control\\.system_manager .* race_state CAUTION.*\\[brickyard\\] success")
set(race_control_red_want "manager: race control: RACING -> STOPPING at t = 8\\.0[0-9]+ s: track flag RED, vehicle flag NONE: a controlled stop at 6 m/s\\^2.*race_control: RED \\(1\\), NONE \\(1\\), 0 mph at 8\\.000 s from [0-9.]+ m/s: stopped after [0-9.]+ m, within the [0-9.]+ m allowed.*dbw +sim\\.drive_by_wire .* track_cond_ack 1 · veh_sig_ack 1.*\\[brickyard\\] success")
set(race_control_checkered_want "manager: race control: RACING -> FINISHING at t = 3\\.0[0-9]+ s: CHECKERED at lap count 0.*race_control: checkered at 3\\.000 s: the lap finished at [0-9.]+ s \\(lap count 1\\).*manager: race control: FINISHING -> FINISHED.*race_control: checkered at 3\\.000 s: after the line: stopped after [0-9.]+ m, within the [0-9.]+ m allowed.*dbw +sim\\.drive_by_wire .* track_cond_ack 4 · veh_sig_ack 4.*\\[brickyard\\] success")
set(race_control_silent_want "vehicle: race control lost: its heartbeat unchanged for 1 s.*manager: race control: RACING -> STOPPING at t = [0-9.]+ s: race control lost \\(its heartbeat stopped\\).*race_control: silence at 8\\.000 s from [0-9.]+ m/s: stopped after [0-9.]+ m, within the [0-9.]+ m allowed.*\\[brickyard\\] success")
set(fail_race_control_red_soft_brake_why "node 'race_control' \\(sim\\.race_control\\): RED \\(1\\), NONE \\(1\\), 0 mph at 8\\.000 s from [0-9.]+ m/s: still [0-9.]+ m/s after the [0-9.]+ m allowed \\(the car needs [0-9.]+ m at 6 m/s\\^2\\)")
# The bus cut both ways for 0.5 s: the manager, watching the vehicle's status, stops the car along
# the path and hands it back 2 s after the reports come again (docs/vehicle-interface.md).
set(can_bus_cut_want "vehicle: steering_report silent: nothing for 0\\.1 s.*manager: PATH -> SAFE_STOP at t = 8\\.1[0-9]+ s: the drive-by-wire's steering report silent.*dbw: drive-by-wire: commands or heartbeat lost: braking.*manager: SAFE_STOP -> PATH at t = 10\\.5[0-9]+ s: the car's side well again.*\\[brickyard\\] success")
# The stack killed at 34 s, at 84 m/s on IMS's straight: the interface stops the car along the path.
set(stack_killed_can_want "vehicle: commands: ACTIVE -> STOPPING: none fresh.*vehicle: commands: STOPPING -> HANDED_OVER: stopped in [0-9.]+ m.*dbw: drive-by-wire: commands or heartbeat lost: braking.*vehicle +vehicle_interface\\.raptor_dbw .* held_stops 0 .* path_stops 1 .*\\[brickyard\\] success")
# The receiver as a SPAN INS: every fix from INSPVAX; BESTPOS and BESTVEL, one each a fix, the driver's other reports.
set(sim_gnss_wire_inspvax_want "rx +drivers\\.gnss .* fixes (9[5-9]|10[0-1]) .* other_reports (19[0-9]|20[0-2]) .*wire +sim\\.gnss_wire .*\\[brickyard\\] success")
# An Ouster on its wire: every packet of the rotations read (the last one sent as the run ends), every frame whole.
set(expect_drivers_ouster_imu_pcap_want "imu +drivers\\.ouster_imu .* capture_datagrams 74 · capture_refused 0 · malformed 0 · packets 10 · samples 10 · silences 0 .*\\[brickyard\\] success")
set(ouster_on_wire_want "lidar +drivers\\.ouster_lidar .* bad_column 0 · bad_crc 0 · bad_packet_type 0 · bad_size 0 · decoded_packets 3199 .* frames 49 · frames_complete 49 · frames_incomplete 0 · late 0 · missing_columns 0 .*lidar_wire +sim\\.ouster +[0-9]+ +bytes_dropped 0 · frames 51 · packets_sent 3200 .*\\[brickyard\\] success")
foreach(g race_can_ims race_can_ims_lossy can_stack_silent_stops can_bus_cut stack_killed_can sim_gnss_wire race_control_yellow race_control_red race_control_checkered
        race_control_silent fail_race_control_red_soft_brake ouster_on_wire sim_gnss_wire_inspvax)
  set(${g}_args --threads 1)
endforeach()
file(GLOB graph_files CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/graphs/*.json)
foreach(g ${graph_files})
  get_filename_component(name ${g} NAME_WE)
  by_uses_sim(${g} sim)
  if(sim AND NOT BRICKYARD_SIM)
    continue()
  endif()
  by_next_domain(d)
  if(name MATCHES "^fail_")
    set(absent "\\[brickyard\\] success")
    if(name STREQUAL "fail_configure")
      set(absent "\\[brickyard\\] (running|success)")  # configure failed: nothing ran
    endif()
    brickyard_add_graph_test(NAME graph.${name} GRAPH ${g} EXPECT_EXIT 1 EXPECT_OUTPUT "${${name}_why}" EXPECT_ABSENT "${absent}"
      LAUNCHER ${NETNS} ARGS --domain ${d} --out ${RUNS}/${name} ${${name}_args})
  else()
    set(want "\\[brickyard\\] success")
    if(DEFINED ${name}_want)  # a graph that must also say something on its way
      set(want "${${name}_want}")
    endif()
    brickyard_add_graph_test(NAME graph.${name} GRAPH ${g} EXPECT_OUTPUT "${want}" LAUNCHER ${NETNS}
      ARGS --domain ${d} --out ${RUNS}/${name} ${${name}_args})
  endif()
endforeach()
