# Bad input: exit 2, the culprit named, nothing started (and the same checks of the map source
# and the vehicle file). Included by tests/CMakeLists.txt.

# ---- bad input: exit 2, the culprit named, nothing started ----
set(BAD ${CMAKE_CURRENT_SOURCE_DIR}/bad_inputs)
set(GOOD ${CMAKE_CURRENT_SOURCE_DIR}/graphs/chain.json)
function(bad_case name regex absent)
  by_next_domain(d)
  add_test(NAME bad_input.${name}
    COMMAND ${NETNS} ${EXPECT} 2 "${regex}" "${absent}" -- ${BY} ${ARGN} --domain ${d})
endfunction()
function(bad_input name regex)
  bad_case(${name} "${regex}" "${NOT_STARTED}" ${ARGN})
endfunction()

bad_input(end_timeout_zero "sim_lockstep.json#/transport/end_timeout_s: expected seconds, more than 0 and at most 600, found 0" validate ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json --arg end_timeout_s=0)
bad_input(huge_seed "--seed 99999999999999999999999: expected a non-negative integer of at most 19 digits" run ${GOOD} --seed 99999999999999999999999)
bad_input(malformed_json        "malformed.json:3:[0-9]+: invalid JSON"          run ${BAD}/malformed.json)
bad_input(top_level_array       "top_array.json#: expected object, found array"   run ${BAD}/top_array.json)
bad_input(nodes_not_object      "nodes_not_object.json#/nodes: expected object, found array" run ${BAD}/nodes_not_object.json)
bad_input(unknown_top_key       "#/wirez: unknown key"                            run ${BAD}/unknown_top_key.json)
bad_input(unknown_node_key      "#/nodes/src/parameters: unknown key"             run ${BAD}/unknown_node_key.json)
bad_input(duplicate_node        "duplicate_node.json:3:3: duplicate key \"src\""  run ${BAD}/duplicate_node.json)
bad_input(unknown_plugin        "#/nodes/src/plugin: unknown plugin \"testing.no_such_plugin\"" run ${BAD}/unknown_plugin.json)
bad_input(latency_over_period "latency_over_period.json#/nodes/src/params/latency_s: latency 0.2 s is longer than the node's period \\(0.1 s\\)" run ${BAD}/latency_over_period.json)
bad_input(latency_on_input_split "latency_on_input_split.json#/nodes/double/params/latency_s: a latency on a node woken by its inputs needs the graph in one process on the sim clock" run ${BAD}/latency_on_input_split.json)
bad_input(not_shared_object     "libnot_elf.so: not a shared object"              run ${GOOD} --plugin-path ${FIXTURES}/not_elf)
bad_input(missing_entry_point   "libfixture_no_entry.so: missing entry point brickyard_plugin_library" run ${GOOD} --plugin-path ${FIXTURES}/no_entry)
bad_input(abi_major             "libfixture_abi_mismatch.so: built against plugin ABI 99.0 \\(SDK 99.0.0\\), this host's is 3.1" run ${GOOD} --plugin-path ${FIXTURES}/abi_mismatch)
bad_input(manifest_all_problems "libfixture_bad_manifest.so: .*declared twice.*unknown message type acme::Unknown.*constraint names 'mode', which is not a number param.*its defaults break its own constraint: parameter 'lo' \\(2\\) must be at most 'hi' \\(1\\).*not a number param.*declared twice" run ${GOOD} --plugin-path ${FIXTURES}/bad_manifest)
# Two providers of one name in one folder: still an error (in an earlier folder it overrides: cli.plugin_override).
file(MAKE_DIRECTORY ${FIXTURES}/duplicate_same_folder)
file(CREATE_LINK ${FIXTURES}/duplicate/libfixture_duplicate.so ${FIXTURES}/duplicate_same_folder/libfixture_duplicate.so SYMBOLIC)
file(CREATE_LINK ${BRICKYARD_PLUGIN_OUTPUT_DIR}/libtesting_transform.so ${FIXTURES}/duplicate_same_folder/libtesting_transform.so SYMBOLIC)
bad_input(duplicate_plugin      "libtesting_transform.so: plugin 'testing.transform' is also provided by .*libfixture_duplicate.so" run ${GOOD} --plugin-path ${FIXTURES}/duplicate_same_folder)
bad_input(unknown_port          "#/wires/0/from: node \"src\" \\(testing.scripted_source\\) has no port \"outt\"" run ${BAD}/unknown_port.json)
bad_input(wrong_direction       "#/wires/0/from: \"t.in\" is an input"            run ${BAD}/wrong_direction.json)
bad_input(type_mismatch         "#/wires/0: type mismatch: b.out carries brickyard::msgs::Blob" run ${BAD}/type_mismatch.json)
bad_input(two_writers           "#/wires/2/to: input \"check.in\" already has a writer" run ${BAD}/two_writers.json)
bad_input(unwired_input         "#/nodes/check: required input \"in\"" run ${BAD}/unwired_input.json)
# Bad input found by a node's configure (files, JSON parameters): exit 2, the culprit named, no step run.
function(bad_config name regex)
  bad_case(${name} "${regex}" "\\[brickyard\\] running" ${ARGN})
endfunction()
# testing.expect's expectations, checked against the wire's type before any step.
bad_config(expect_unknown_field "node 'check' \\(testing.expect\\): parameter 'expect' /1/field: poses\\[\\*\\].q: no member 'q' in Pose2D \\(members: x, y, yaw\\) \\(brickyard::msgs::Path\\) \\(.*expect_unknown_field.json#/nodes/check/params/expect/1/field\\)" run ${BAD}/expect_unknown_field.json)
bad_config(expect_near_unwired "parameter 'expect' /0/near: compares with the input 'ref', which is not wired" run ${BAD}/expect_near_unwired.json)
bad_config(json_source_bad_field "node 'path' \\(testing.json_source\\): parameter 'samples' /0/msg/poses/0/x: expected a number, found \"a\" \\(brickyard::msgs::Path\\) \\(.*json_source_bad_field.json#/nodes/path/params/samples/0/msg/poses/0/x\\)" run ${BAD}/json_source_bad_field.json)
# The same checks at validation (Manifest::check, ABI 2.4): nothing runs, and every node's failure is said.
bad_config(expect_unknown_field_validate "node 'check' \\(testing.expect\\): parameter 'expect' /1/field: poses\\[\\*\\].q: no member 'q' in Pose2D .*expect_unknown_field.json#/nodes/check/params/expect/1/field" validate ${BAD}/expect_unknown_field.json)
bad_config(json_source_bad_field_validate "node 'path' \\(testing.json_source\\): parameter 'samples' /0/msg/poses/0/x: expected a number" validate ${BAD}/json_source_bad_field.json)
# The LQR tracker plans over the vehicle file's steering delay and command_latency, 0.3 s at most.
bad_config(tracker_latency_too_long "node 'path_tracker' \\(control.path_tracker\\): parameter 'command_latency': 0.3 s with the steering's 0.02 s delay \\(vehicles/av21.json\\) is more than the 0.3 s the lqr law plans over" validate ${PROJECT_SOURCE_DIR}/configs/race.json --set path_tracker.command_latency=0.3)
# A data file a parameter names is read at validation, not first at the run's start (the
# track files above are refused there too: "error:", before any run).
if(BRICKYARD_SIM)
  bad_config(validate_missing_track "node 'map' \\(map.track_file\\): .*tracks/Nowhere.csv" validate ${PROJECT_SOURCE_DIR}/configs/race.json --arg track=tracks/Nowhere.csv)
  # A rival's driver at no pace (issue 46).
  # A rival placed wrong, refused at validation (its `track` and `clear_of`: docs/tracking.md).
  set(RIVAL ${CMAKE_CURRENT_SOURCE_DIR}/graphs/rivals/rival_ahead.json)
  bad_config(rival_start_off_road "node 'rival' \\(sim.vehicle\\): parameter 'start_d': the car \\(1.94 m wide\\) at d = 7.00 m stands off the road at s = 120.0 m" run ${RIVAL} --set rival.start_d=7)
  bad_config(rival_start_inside "node 'rival' \\(sim.vehicle\\): parameter 'start_s': the car at s = 2.0 m, d = 0.00 m stands inside the one starting at s = 0.0 m, d = 0.00 m" validate ${RIVAL} --set rival.start_s=2)
  bad_config(rival_start_inside_race "node 'rival' \\(sim.vehicle\\): parameter 'start_s': the car at s = 1.0 m, d = 0.50 m stands inside the one starting at s = 0.0 m" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/rivals/race_rival.json --arg rival_start_s=1 --arg rival_offset=0 --set rival.start_d=0.5)
  bad_config(rival_clear_of_not_pairs "node 'rival' \\(sim.vehicle\\): parameter 'clear_of': /0: not an \\[s, d\\] pair" run ${RIVAL} --set "rival.clear_of=[[0]]")
  bad_config(rival_speed_scale_zero "sim_truth_lap.json#/nodes/driver/params/speed_scale: .*found 0" validate ${PROJECT_SOURCE_DIR}/configs/sim_truth_lap.json --set driver.speed_scale=0)
  # The tracking scorer's range bands out of order.
  bad_config(tracking_bands_not_rising "node 'tracking' \\(sim.tracking_scorer\\): parameter 'bands_m': the range bands' far ends must rise.*race_rival.json#/nodes/tracking/params/bands_m" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/rivals/race_rival.json --set "tracking.bands_m=[60,30]")
endif()
# One pass: a structural error elsewhere in the graph does not hide a plugin's own check.
bad_config(validate_checks_with_structure "map/params/bogus: unknown parameter \"bogus\".*node 'check' \\(testing.expect\\): parameter 'expect' /1/field: poses\\[\\*\\].q: no member 'q'" validate ${BAD}/expect_unknown_field.json --set map.bogus=1)
bad_config(validate_every_check "error: node 'path' \\(testing.json_source\\): parameter 'samples' /0/msg/poses/0/x: expected a number, found \"a\" .*validate_every_check.json#/nodes/path/params/samples/0/msg/poses/0/x\\).*error: node 'check' \\(testing.expect\\): parameter 'expect' /0/field: steer_rate: no member 'steer_rate' in ControlCommand .*validate_every_check.json#/nodes/check/params/expect/0/field" validate ${BAD}/validate_every_check.json)
by_next_domain(d)
add_test(NAME bad_input.json_source_too_big COMMAND sh -c "mkdir -p ${RUNS} && truncate -s 300M ${RUNS}/too_big.json && exec \"$0\" \"$@\""
  ${NETNS} ${EXPECT} 2 "node 'path' \\(testing.json_source\\): file .*too_big.json: larger than 256 MiB"
  -- ${BY} run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/expect_tracker_straight.json --set path.file=${RUNS}/too_big.json --domain ${d})
bad_input(any_to_any "any_to_any.json#/wires/0: src.out and check.in both take any message type: nothing says which \\(set src's parameter 'type'\\)" run ${BAD}/any_to_any.json)
# The sensor drivers: a device that cannot be opened, a source or datum that cannot be right, a
# recording that is not a regular file, a metadata file missing or malformed (docs/drivers.md).
set(DRIVER_GNSS ${CMAKE_CURRENT_SOURCE_DIR}/graphs/expect_drivers_gnss_log.json)
set(DRIVER_OUSTER ${CMAKE_CURRENT_SOURCE_DIR}/graphs/expect_drivers_ouster_pcap.json)
bad_config(driver_serial_missing "node 'gnss' \\(drivers.gnss\\): parameter 'source': serial:///dev/ttyBY_NONE: cannot open: No such file or directory" run ${DRIVER_GNSS} --set gnss.source=serial:///dev/ttyBY_NONE)
bad_config(driver_source_port "node 'gnss' \\(drivers.gnss\\): parameter 'source': .*udp://127.0.0.1:70000.*70000" validate ${DRIVER_GNSS} --set gnss.source=udp://127.0.0.1:70000)
bad_config(driver_datum "node 'gnss' \\(drivers.gnss\\): parameter 'datum': latitude outside \\[-90, 90\\] deg" validate ${DRIVER_GNSS} --set gnss.datum=[91,0,0])
bad_config(driver_log_not_regular "node 'gnss' \\(drivers.gnss\\): /dev/zero: not a regular file" run ${DRIVER_GNSS} --set gnss.source=file:///dev/zero)
bad_config(driver_metadata_missing "node 'lidar' \\(drivers.ouster_lidar\\): .*nowhere_metadata.json" validate ${DRIVER_OUSTER} --set lidar.metadata=nowhere_metadata.json)
bad_config(driver_metadata_malformed "node 'lidar' \\(drivers.ouster_lidar\\): parameter 'metadata': .*malformed.json: metadata: not a JSON object" validate ${DRIVER_OUSTER} --set lidar.metadata=${BAD}/malformed.json)
set(DRIVER_OUSTER_IMU ${CMAKE_CURRENT_SOURCE_DIR}/graphs/expect_drivers_ouster_imu_pcap.json)
bad_config(driver_imu_source_not_udp "node 'imu' \\(drivers.ouster_imu\\): parameter 'source': tcp://127.0.0.1:7503: an Ouster sensor's IMU is read from udp:// or pcap://" validate ${DRIVER_OUSTER_IMU} --set imu.source=tcp://127.0.0.1:7503)
bad_config(driver_imu_metadata_missing "node 'imu' \\(drivers.ouster_imu\\): .*nowhere_metadata.json" validate ${DRIVER_OUSTER_IMU} --set imu.metadata=nowhere_metadata.json)
bad_config(driver_imu_capture_missing "node 'imu' \\(drivers.ouster_imu\\): file not found: /nonexistent.pcap" run ${DRIVER_OUSTER_IMU} --set imu.source=pcap:///nonexistent.pcap)
# The test of the test: the same capture mounted upside down fails the graph's expectations (exit 1).
by_next_domain(d)
add_test(NAME graph.fail_ouster_imu_upside_down
  COMMAND ${NETNS} ${EXPECT} 1 "accel_z within \\[9.5, 10.5\\].*accel_z = -10\\." -- ${BY} run ${DRIVER_OUSTER_IMU} --set imu.mount_rpy_deg=[180,0,0] --domain ${d})
# The vehicle interface (docs/vehicle-interface.md): a DBC without a message the mapping needs, at
# validation; a SocketCAN interface that does not exist, when configure opens it; a vehicle file
# without the drive-by-wire's section; shift rules the car's gears cannot follow. No simulator.
set(RAPTOR ${BAD}/raptor_dbw_no_can.json)
bad_config(raptor_dbw_no_can_interface "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'bus': can://bynocan0: no such network interface" run ${RAPTOR})
bad_config(raptor_dbw_dbc_missing_message "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'dbc': .*raptor_no_steering.dbc: no message steering_cmd \\(the vehicle interface needs" validate ${RAPTOR} --set vehicle.dbc=${BAD}/raptor_no_steering.dbc)
bad_config(raptor_dbw_vehicle_without_dbw "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'vehicle': .*car_without_dbw.json: /drive_by_wire: missing" validate ${RAPTOR} --set vehicle.vehicle=${BAD}/car_without_dbw.json)
# Race control (docs/race-control.md): the DBC must carry base_to_car_summary, the codes must tell the flags apart.
bad_config(raptor_dbw_dbc_no_race_control "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'dbc': .*raptor_no_race_control.dbc: no message base_to_car_summary" validate ${RAPTOR} --set vehicle.dbc=${BAD}/raptor_no_race_control.dbc)
bad_config(raptor_dbw_flag_codes_twice "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'track_flag_green': code 3 is 'track_flag_yellow' already" validate ${RAPTOR} --set vehicle.track_flag_green=3)
bad_config(raptor_dbw_race_control_bus_not_udp "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'race_control_bus': 'can://can0': udp://HOST:PORT" validate ${RAPTOR} --set vehicle.race_control_bus=can://can0)
bad_config(raptor_dbw_shift_hunts "node 'vehicle' \\(vehicle_interface.raptor_dbw\\): parameter 'shift_down_rpm': 4600 rpm must be below 4500 rpm, where an upshift at 7000 rpm lands" validate ${RAPTOR} --set vehicle.shift_down_rpm=4600)
if(BRICKYARD_SIM)  # the nodes that find these live in simulator graphs
  # The simulated Ouster: its packets go to a UDP port only; its metadata read as the driver reads it.
  set(SIM_OUSTER ${CMAKE_CURRENT_SOURCE_DIR}/graphs/ouster_on_wire.json)
  bad_config(sim_ouster_sink_not_udp "node 'lidar_wire' \\(sim.ouster\\): parameter 'sink': tcp://127.0.0.1:39640: an Ouster sends to udp://HOST:PORT" validate ${SIM_OUSTER} --set lidar_wire.sink=tcp://127.0.0.1:39640)
  bad_config(sim_ouster_metadata_malformed "node 'lidar_wire' \\(sim.ouster\\): parameter 'metadata': .*malformed.json: metadata: not a JSON object" validate ${SIM_OUSTER} --set lidar_wire.metadata=${BAD}/malformed.json)
  bad_config(sim_gnss_wire_bestvel_no_truth "node 'wire' \\(sim.gnss_wire\\): parameter 'bestvel': needs the car's motion: wire its input 'truth'" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/sim_gnss_wire.json --set wire.bestvel=true)
  bad_config(race_control_bad_script "node 'race_control' \\(sim.race_control\\): parameter 'script' /1/track_flag: 'blue' is no flag of this field \\(.*race_control_bad_script.json#/nodes/race_control/params/script/1/track_flag\\)" validate ${BAD}/race_control_bad_script.json)
  # The world's track file and pylons: read at validation, so nothing starts.
  bad_input(track_bad_row   "error: node 'world' \\(sim.world\\): track file .*bad_track.csv:4: field 3 is not a number: 'abc'" run ${BAD}/bad_track.json)
  bad_input(track_missing   "node 'world' \\(sim.world\\): file 'tracks/NoSuchTrack.csv' not found; looked in:" run ${BAD}/missing_track.json)
  bad_input(pylon_without_d "node 'world' \\(sim.world\\): parameter 'pylons' /1: needs s and d" run ${BAD}/bad_pylons.json)
  bad_config(fusion_antenna  "node 'estimator' \\(estimation.resilient_fusion\\): parameter 'antenna1': needs 3 numbers" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/localization_double_degradation.json --set estimator.antenna1=[1.6,0])
  bad_config(gnss_mount      "node 'gnss' \\(sim.gnss\\): parameter 'vehicle_mount': .*vehicle 'Dallara AV-21' has no mount \"gnss_roof\"" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/sim_gnss_faults.json --set gnss.vehicle_mount=gnss_roof --set gnss.antenna=[])
  # The localization scorer's samples file in a folder that does not exist: named, nothing runs.
  bad_config(scorer_samples_unwritable "node 'score' \\(sim.localization_scorer\\): parameter 'samples_file': .*no_such_dir/s.csv: cannot write the samples" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/localization_double_degradation.json --set score.samples_file=${RUNS}/no_such_dir/s.csv)
  bad_config(fusion_mount    "node 'estimator' \\(estimation.resilient_fusion\\): parameter 'antenna0_mount': vehicles/av21.json: vehicle 'Dallara AV-21' has no mount \"gnss_roof\"" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/localization_double_degradation.json --set estimator.antenna0_mount=gnss_roof)
  bad_config(track_figure8 "error: node 'map' \\(map.track_file\\): track file .*figure8_track.csv: its centre line crosses itself between lines 1 and 102 at 23 degrees: two stretches over each other, not a bridge \\(one of at least 30 degrees\\)" run ${PROJECT_SOURCE_DIR}/configs/race.json --arg track=${BAD}/figure8_track.csv)
  bad_config(track_overlapping "error: node 'map' \\(map.track_file\\): track file .*overlapping_track.csv: the track runs over itself: near lines 4 and 218" run ${PROJECT_SOURCE_DIR}/configs/race.json --arg track=${BAD}/overlapping_track.csv)
  bad_config(track_far_point "error: node 'map' \\(map.track_file\\): track file .*far_point_track.csv:3: a point more than 1000 km from the origin" run ${PROJECT_SOURCE_DIR}/configs/race.json --arg track=${BAD}/far_point_track.csv)
  bad_config(faults_window   "node 'gnss' \\(sim.gnss\\): parameter 'faults' /1/end_s: must be after start_s" run ${BAD}/bad_faults.json)
endif()
# Constraints between parameters (ParamBinding::not_above / below): found by validation, before
# any node is built, at the pointer of the value the graph (or --set) gave.
bad_input(param_order           "#/nodes/check/params/max_value: parameter 'min_value' \\(1\\) must be at most 'max_value' \\(0\\) \\(from --set check.max_value=0\\)" validate ${GOOD} --set check.max_value=0)
if(BRICKYARD_SIM)
  bad_input(lidar_fov         "#/nodes/lidar/params/v_max_deg: parameter 'v_min_deg' \\(.*\\) must be below 'v_max_deg'" run ${BAD}/bad_lidar_fov.json)
  bad_input(fusion_epsilon    "#/nodes/estimator/params/epsilon_m: parameter 'epsilon_m' \\(6\\) must be at most 'delta_m' \\(5\\) \\(from --set estimator.epsilon_m=6\\)" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/localization_double_degradation.json --set estimator.epsilon_m=6)
  bad_input(clustering_sizes  "#/nodes/clusters/params/max_size: parameter 'min_size' \\(10\\) must be at most 'max_size' \\(5\\)" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/perception_ims_straight.json --set clusters.min_size=10 --set clusters.max_size=5)
  bad_input(tracker_lookahead "#/nodes/path_tracker/params/lookahead_min: parameter 'lookahead_min' \\(80\\) must be at most 'lookahead_max' \\(60\\)" validate ${CMAKE_CURRENT_SOURCE_DIR}/graphs/resilient_ims_fault_in_turn.json --set path_tracker.lookahead_min=80)
endif()
bad_input(param_wrong_type      "#/nodes/src/params/rate_hz: expected number, found \"fast\"" run ${BAD}/param_wrong_type.json)
bad_input(param_out_of_range    "#/nodes/src/params/rate_hz: expected a value from 0.001 to 1e\\+06 Hz, found 0" run ${BAD}/param_out_of_range.json)
bad_input(param_unknown         "#/nodes/src/params/rate: unknown parameter \"rate\"" run ${BAD}/param_unknown.json)
bad_input(param_missing         "#/nodes/b/params: missing required parameter \"size_bytes\"" run ${BAD}/param_missing.json)
bad_input(set_syntax            "--set src_rate_hz: expected node.param=value"    run ${GOOD} --set src_rate_hz)
bad_input(set_unknown_node      "--set nope.gain=2: the graph has no node \"nope\"" run ${GOOD} --set nope.gain=2)
bad_input(set_unknown_param     "#/nodes/double/params/gane: unknown parameter .*from --set double.gane=2" run ${GOOD} --set double.gane=2)
bad_input(set_wrong_type        "#/nodes/src/params/count: expected integer, found 2.5 \\(from --set" run ${GOOD} --set src.count=2.5)
bad_input(unknown_process       "--process nope: no node of the graph runs in process \"nope\"" run ${GOOD} --process nope)
bad_input(zero_delay_cycle      "#/wires: zero-delay cycle a -> b -> a"           run ${BAD}/zero_delay_cycle.json)
bad_input(deep_nesting          "deep.json:1:[0-9]+: nesting deeper than 64"      run ${FIXTURES}/deep.json)
bad_input(bad_endpoint          "#/wires/0/from: expected \"node.port\", found \"src\"" run ${BAD}/bad_endpoint.json)
bad_input(bad_clock_mode        "#/clock/mode: expected \"sim\" or \"real\"" run ${BAD}/bad_clock_mode.json)
bad_input(sim_split_restart     "sim_split_restart.json#/processes/a/restart: on-failure needs the real clock" run ${BAD}/sim_split_restart.json --process a)
bad_input(sim_split_foreign     "sim_split_foreign.json#/transport/foreign_writers: accept needs the real clock" run ${BAD}/sim_split_foreign.json --process a)
bad_input(bad_domain            "#/transport/domain: expected a DDS domain id"    run ${BAD}/bad_domain.json)
bad_input(unknown_process_policy "bad_processes.json#/processes/c: no node runs in process \"c\"" run ${BAD}/bad_processes.json)
bad_input(bad_restart_policy  "bad_processes.json#/processes/a/restart: expected \"never\" or \"on-failure\", found \"always\"" run ${BAD}/bad_processes.json)
bad_input(security_no_out       "security init: needs --out DIR" security init ${GOOD})
bad_input(security_days         "--days 0: expected a whole number of days from 1 to 3650" security init ${GOOD} --out /tmp/x --days 0)
bad_input(security_play_no_identity "--security /tmp/by_no_keys: bag play writes topics: it needs --identity NAME" bag play ${PROJECT_SOURCE_DIR}/fuzz/corpus/fuzz_mcap/chain_zstd.mcap --security /tmp/by_no_keys)
bad_input(security_topic_no_keys "--security /tmp/by_no_keys: identity 'observer': .*/tmp/by_no_keys/identity_ca.pem: does not exist" topic echo src.out --security /tmp/by_no_keys)
bad_input(security_protect      "--protect nope: expected sign or encrypt" security init ${GOOD} --out /tmp/x --protect nope)
bad_input(security_out_unwritable "/proc/brickyard_keys: cannot write beside it \\(/proc/.brickyard_keys.init: " security init ${GOOD} --out /proc/brickyard_keys)
bad_input(security_out_a_file   "\\.json: cannot create the folder: it exists and is not a folder" security init ${GOOD} --out ${GOOD})
bad_input(security_observer     "node 'src' runs in process 'observer'" security init ${BAD}/security_observer_process.json --out /tmp/by_security_observer)
bad_input(security_missing      "security_missing.json#/transport/security: .*no_such_keys is not a folder: make it with .brickyard security init" validate ${BAD}/security_missing.json)
bad_input(supervised_record   "--record: a supervised run records each process into --out DIR/PROCESS/recording.mcap" run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json --record /tmp/x.mcap)
# The graph's own domain (bad_case adds --domain): no network namespace needed, nothing starts.
add_test(NAME bad_input.supervised_domain COMMAND ${EXPECT} 2
  "supervised_domain.json#/transport/domain: a run split into processes needs a DDS domain id from 0 to 231, found 232"
  "${NOT_STARTED}" -- ${BY} run ${BAD}/supervised_domain.json)
bad_input(bad_deadline          "bad_deadline.json#/nodes/fault/deadline_s: expected seconds, more than 0 and at most 3600, found -1" run ${BAD}/bad_deadline.json)
bad_input(bad_live_port         "bad_live_port.json#/live/port: expected a port from 0 to 65535, found 70000" run ${BAD}/bad_live_port.json)
bad_input(bad_live_cloud_hz     "bad_live_cloud_hz.json#/live/cloud_hz: expected clouds a second from 0 \\(every one\\) to 1000, found -5" run ${BAD}/bad_live_cloud_hz.json)
bad_input(missing_plugin_dir    "no/such/folder: plugin folder does not exist"    run ${BAD}/missing_plugin_dir.json)
bad_input(missing_graph_file    "nope.json: no such file"                         run ${BAD}/nope.json)
# A folder with the user's own summary.json: --out refuses rather than replace it.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/foreign_out/summary.json "{\"mine\": true}\n")
bad_input(out_foreign_summary   "--out .*foreign_out: .*foreign_out/summary.json was not written by brickyard: move it or use another folder" run ${GOOD} --out ${CMAKE_CURRENT_BINARY_DIR}/foreign_out)
bad_input(huge_duration         "--duration: expected a positive number of seconds, at most 1e7" run ${GOOD} --duration 1e308)
# Names of 100 000 characters: refused in one pass, quoted short; a regex overflowed the stack.
string(REPEAT "a" 100000 BY_LONG_NAME)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/long_node_name.json "{\"nodes\": {\"${BY_LONG_NAME}\": {\"plugin\": \"testing.scripted_source\"}}}")
bad_input(long_node_name        "node name \"aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa… \\(100000 characters\\)\" must be letters" run ${CMAKE_CURRENT_BINARY_DIR}/long_node_name.json)
bad_input(long_set_name         "--set src.aaaaaaaaaaaaaaaaaaaaaaaaaaaaaa[a]*… \\(100006 characters\\): expected node.param=value" run ${GOOD} --set src.${BY_LONG_NAME}=1)
bad_input(long_plugin_name      "new-plugin aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa… \\(100000 characters\\): expected a name" new-plugin ${BY_LONG_NAME} --dir /tmp/by_never)
bad_input(bad_duration          "--duration -3: expected a number|--duration: expected a positive" run ${GOOD} --duration -3)
bad_input(unknown_option        "--fast: unknown option"                          run ${GOOD} --fast)
bad_input(bad_threads_zero      "--threads 0: expected an integer from 1 to 64"   run ${GOOD} --threads 0)
bad_input(bad_threads_word      "--threads four: expected an integer from 1 to 64" run ${GOOD} --threads four)
bad_input(validate_reports_all  "unknown plugin.*\n.*unknown parameter|unknown parameter.*\n.*unknown plugin" validate ${BAD}/unknown_plugin.json --set src.x=1)

# ---- the map source and the vehicle file: bad input names the file ----
bad_config(map_narrow  "node 'map' \\(map.track_file\\): track file .*narrow_track.csv: at s = [0-9.]+ m \\(point 41\\) it is 1.60 m wide, narrower than the car \\(1.94 m, vehicles/av21.json\\)" run ${BAD}/narrow_map.json)
bad_config(map_bad_row "node 'map' \\(map.track_file\\): track file .*bad_track.csv:4: field 3 is not a number: 'abc'" run ${BAD}/bad_map_track.json)
# The bank column (a mapped track's, docs/mapping.md): asked for of a file without it; dropped by one row.
bad_config(map_bank_file_no_column "node 'map' \\(map.track_file\\): parameter 'bank_mode': .*IMS.csv: bank_mode 'file', but the track file has no bank_deg column" run ${BAD}/bank_file_no_column.json)
bad_config(map_bank_column_dropped "node 'map' \\(map.track_file\\): track file .*bank_column_dropped.csv:5: 4 fields, expected 5" run ${BAD}/bank_column_dropped.json)
# A thousand bad wires (two problems each): the first 50 problems said, the rest counted (a million printed 123 MB).
add_test(NAME bad_input.many_problems_summarized COMMAND sh -c "mkdir -p ${RUNS} && python3 -c 'import json; print(json.dumps({\"nodes\": {\"src\": {\"plugin\": \"testing.scripted_source\"}}, \"wires\": [{\"from\": \"ghost%d.out\" % i, \"to\": \"src.in\"} for i in range(1000)]}))' > ${RUNS}/many_problems.json && exec \"$0\" \"$@\""
  ${EXPECT} 2 "no node named .ghost24.*error: and 1950 more problems \\(2000 in all; the first 50 above\\)" "ghost25" -- ${BY} validate ${RUNS}/many_problems.json)
# A value nested 60,000 deep (120 kB, under one argument's 128 KiB): refused before the JSON
# parser's recursion meets it (it crashed validate and run).
string(REPEAT "[" 60000 DEEP_OPEN)
string(REPEAT "]" 60000 DEEP_CLOSE)
bad_input(set_value_too_deep "--set src.rate_hz=\\[+… \\(120012 characters\\): the value: nesting deeper than 32 levels"
          run ${GOOD} --set "src.rate_hz=${DEEP_OPEN}${DEEP_CLOSE}")
bad_input(arg_value_too_deep "--arg track=\\[+… \\(120006 characters\\): the value: nesting deeper than 32 levels"
          validate ${PROJECT_SOURCE_DIR}/configs/race.json --arg "track=${DEEP_OPEN}${DEEP_CLOSE}")
# Graph arguments (configs/race.json): one never declared; a graph file beside a planned line.
bad_input(arg_undeclared "--arg trak=x: the graph declares no argument \"trak\" \\(declared: bank_deg, .*track, wall_side\\)"
          run ${PROJECT_SOURCE_DIR}/configs/race.json --arg trak=x)
if(BRICKYARD_SIM)
  bad_config(vehicle_bad_key "node 'path_tracker' \\(control.path_tracker\\): parameter 'vehicle': .*bad_vehicle.json: /geometry/wheelbase: unknown key"
             run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/resilient_ims_fault_in_turn.json --set path_tracker.vehicle=${BAD}/bad_vehicle.json)
  bad_config(wall_follower_unwired "node 'wall_follower' \\(control.wall_follower\\): law paper follows the wall wired to input 'wall', which is not wired"
             run ${PROJECT_SOURCE_DIR}/configs/race.json --set wall_follower.law=paper)
  bad_config(graph_file_with_planned_line "node 'planner' \\(planning.road_graph\\): graph_file needs a raceline file: with raceline plan"
             run ${PROJECT_SOURCE_DIR}/configs/race.json --set planner.graph_file=x.byrg)
  # Every file a parameter names is found and read at validation, naming the node: the car's file,
  # a racing line, the simulator's track, a road-graph file.
  set(RACE ${PROJECT_SOURCE_DIR}/configs/race.json)
  bad_input(validate_vehicle_missing "node 'path_tracker' \\(control.path_tracker\\): file 'vehicles/none.json' not found; looked in:"
            validate ${RACE} --set path_tracker.vehicle=vehicles/none.json)
  bad_input(validate_vehicle_bad_key "node 'lidar_left' \\(sim.lidar\\): parameter 'vehicle': .*bad_vehicle.json: /geometry/wheelbase: unknown key"
            validate ${RACE} --set lidar_left.vehicle=${BAD}/bad_vehicle.json)
  bad_input(validate_raceline_missing "node 'planner' \\(planning.racing_line\\): file 'racelines/none.csv' not found"
            validate ${RACE} --set planner.plugin=planning.racing_line --set planner.raceline=racelines/none.csv)
  bad_input(validate_world_track_missing "node 'world' \\(sim.world\\): file 'tracks/none.csv' not found"
            validate ${RACE} --set world.track=tracks/none.csv)
  # The map localizer's map (configs/race_on_map.json): missing, not a point cloud, empty.
  set(ON_MAP ${PROJECT_SOURCE_DIR}/configs/race_on_map.json)
  bad_input(validate_map_file_not_given "node 'map_localizer' \\(mapping.map_localizer\\): parameter 'map_file': empty: the track's map is needed"
            validate ${ON_MAP})
  bad_input(validate_map_file_missing "node 'map_localizer' \\(mapping.map_localizer\\): file 'maps/none.pcd' not found"
            validate ${ON_MAP} --arg map_file=maps/none.pcd)
  bad_input(validate_map_file_not_pcd "node 'map_localizer' \\(mapping.map_localizer\\): parameter 'map_file': .*not_a_map.pcd: FIELDS must be 'x y z'"
            validate ${ON_MAP} --arg map_file=${BAD}/not_a_map.pcd)
  bad_input(validate_map_file_empty "node 'map_localizer' \\(mapping.map_localizer\\): parameter 'map_file': .*empty_map.pcd: the map holds no point"
            validate ${ON_MAP} --arg map_file=${BAD}/empty_map.pcd)
  # A map that does not cover the track it is used on (three points at the origin; IMS's lap).
  bad_input(validate_map_far_from_track "node 'map_localizer' \\(mapping.map_localizer\\): parameter 'map_file': .*three_point_map.pcd: far from the track: [0-9]+ % of its centre line lies within 30 m of the map"
            validate ${ON_MAP} --arg map_file=${CMAKE_CURRENT_SOURCE_DIR}/graphs/three_point_map.pcd)
  bad_input(validate_graph_file_missing "node 'planner' \\(planning.road_graph\\): file 'nothing.byrg' not found"
            validate ${PROJECT_SOURCE_DIR}/configs/ims_race.json --set planner.graph_file=nothing.byrg)
endif()
# A graph file or an include that is a FIFO, a folder, a device, too large or missing: exit 2
# within seconds naming it (a FIFO's open waited for a writer for ever).
add_test(NAME bad_input.graph_file_kinds COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/graph_file_kinds.sh ${BY} ${RUNS}/graph_file_kinds)
