# Evidence: determinism, processes, DDS, the installed SDK, perception. Included by tests/CMakeLists.txt.

# ---- evidence: determinism, two processes, a plain Fast DDS subscriber, the installed SDK ----
# The executive steps nodes side by side: one thread and four make the same run, for a race and
# for a step that fails on a helper thread.
if(BRICKYARD_SIM)
  by_next_domain(d)
  add_test(NAME evidence.threads_same_race
    COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/threads.sh ${BY} ${PROJECT_SOURCE_DIR}/configs/race.json ${d} ${RUNS}/threads_race
            --duration 12 --arg track=tracks/Spielberg.csv --arg wall_side=left --arg inner_wall=true "--arg" "pylons=[{\"s\":300,\"d\":0}]")
endif()
by_next_domain(d)
add_test(NAME evidence.threads_same_failure
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/threads.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/fail_step_handed_out.json ${d} ${RUNS}/threads_failure)
evidence_script(determinism determinism.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/seeded_noise.json)
by_next_domain(d)
add_test(NAME evidence.two_processes
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/two_process.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json ${d} ${RUNS}/two_process)
# A process of a split run killed: the other notices within the liveliness lease.
evidence_script(peer_lost peer_lost.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json)
# A peer started by hand that fails by a throw or exit(): the healthy process fails naming it.
evidence_script(peer_failed peer_failed.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process_fault.json)
# A node stuck in a lifecycle call (here its deactivate) ends the process after kLifecycleHang_s
# (60 s), naming it, its summary written: before, the process never ended.
by_next_domain(d)
add_test(NAME evidence.hang_in_deactivate
  COMMAND ${NETNS} ${EXPECT} 1 "node 'fault' has been in its deactivate for 6[0-9.]+ s, far past what a lifecycle call may take; the process ends here"
          -- ${BY} run ${CMAKE_CURRENT_SOURCE_DIR}/graphs/fault.json --domain ${d} --quiet --progress 0 --set fault.mode=hang_deactivate
          --duration 1 --out ${RUNS}/hang_in_deactivate)
# A process killed outside any supervisor: its shared-memory segment removed by the next run, a
# live run's kept (two domains: the killed run's, and the live one's beside it).
by_next_domains(d 2)
add_test(NAME evidence.shm_reclaimed
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/shm_reclaimed.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/fault_real.json ${d} ${RUNS}/shm_reclaimed)
set_tests_properties(evidence.shm_reclaimed PROPERTIES PROCESSORS 2)

# One sim clock across processes: a split graph on the sim clock, its processes in
# lockstep, is the run in one process — summaries and recordings — on one thread and on four; a
# step that fails in one process, and a configure that fails, end both alike; a killed peer is
# named within 1.5 s and fails the run.
by_next_domain(d)
add_test(NAME evidence.lockstep_same
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/lockstep_same.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json ${d} ${RUNS}/lockstep_same --seed 7)
by_next_domain(d)
# The same, secured: the processes authenticated, the clock records encrypted with the rest.
add_test(NAME evidence.lockstep_same_secured
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/lockstep_same.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json ${d} ${RUNS}/lockstep_same_secured --seed 7)
set_tests_properties(evidence.lockstep_same_secured PROPERTIES ENVIRONMENT BY_SECURE=1)
by_next_domain(d)
add_test(NAME evidence.lockstep_same_failure
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/lockstep_same.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json ${d} ${RUNS}/lockstep_same_failure --seed 7 --arg fault=step)
by_next_domain(d)
add_test(NAME evidence.lockstep_same_invalid
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/lockstep_same.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json ${d} ${RUNS}/lockstep_same_invalid --seed 7 --arg fault=configure)
# Lockstep's waits between two participants over DDS (framework/tests/test_lockstep_dds.cpp): a
# peer whose end record never comes holds the other no longer than the limit, named.
foreach(t PeersThatEndHearEachOthersEndsAndVerdicts APeerWhoseEndNeverComesIsNamedOnceTheWaitIsOver)
  by_next_domain(d)
  add_test(NAME LockstepDds.${t} COMMAND ${NETNS} $<TARGET_FILE:brickyard_lockstep_dds_tests> --gtest_filter=LockstepDds.${t})
  set_tests_properties(LockstepDds.${t} PROPERTIES ENVIRONMENT BRICKYARD_TEST_DOMAIN=${d} TIMEOUT 120 LABELS unit.framework)
endforeach()
evidence_script(lockstep_peer_killed lockstep_peer_killed.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json)
evidence_script(lockstep_peer_stopped lockstep_peer_stopped.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json)
evidence_script(lockstep_faults lockstep_faults.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_fault_split.json)
# A peer that never starts: the process fails within its start-up timeout, named (it used to wait for its end forever).
by_next_domain(d)
add_test(NAME evidence.lockstep_peer_never_starts
  COMMAND ${NETNS} bash -c "timeout 30 $0 run $1 --process a --domain $2 --quiet --progress 0 --no-report --arg startup_timeout_s=1 2>&1; echo exit=$?"
          ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/sim_lockstep.json ${d})
set_tests_properties(evidence.lockstep_peer_never_starts PROPERTIES PASS_REGULAR_EXPRESSION "process 'b' did not join the lockstep within 1 s.*exit=1")
if(BRICKYARD_SIM)
  # The main job, one lap, split between the simulator's process and the car stack's.
  by_next_domain(d)
  add_test(NAME evidence.lockstep_same_race
    COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/lockstep_same.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/ims_race_split.json ${d} ${RUNS}/lockstep_same_race
            --arg clock=sim --set referee.laps=1 --duration 120 --seed 7)
  set_tests_properties(evidence.lockstep_same_race PROPERTIES TIMEOUT 400)
endif()

# The supervisor: a split run's processes as children, a killed one restarted, a crashed one
# named, a peer that never starts, Ctrl-C.
evidence_script(supervisor supervisor.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/supervised.json)

# A writer the graph does not name, on a wire between processes: its samples dropped, said.
evidence_script(foreign_writer foreign_writer.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json)

# ROS 2's names on the wire: a split graph with transport.naming ros2, secured by default, heard
# by topic list and echo under those names.
evidence_script(ros2_naming ros2_naming.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json)

# DDS security from the graph: a secured split run, attacked without an identity, with a stolen
# one, and with permissions signed by another CA; bad security files refused.
evidence_script(security security.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json)
evidence_script(security_signed security.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json)
set_tests_properties(evidence.security_signed PROPERTIES ENVIRONMENT BY_PROTECT=sign)

# Two hosts: the split main job over two network namespaces joined by a veth pair, security on,
# its traffic on the veth alone. Skipped (77) where no veth can be made.
if(BRICKYARD_SIM)
  evidence_script(two_hosts two_hosts.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/ims_race_split.json)
  # Both processes on the real clock with every sample encrypted: beside another test on a
  # 2-core machine the stack was starved past the 0.5 s liveliness lease (CI, a 1.7 s command
  # gap, then the stack's writers lost): it takes both cores.
  set_tests_properties(evidence.two_hosts PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 400 PROCESSORS 2)
  # The split race attacked from the machine, secured by default and with "off" (which must show
  # what the attacks get): no command value on the wire or in /dev/shm, none read without an
  # identity, no command forged under the stack's name taken; over shared memory and over UDP.
  # Real clock, both cores (as two_hosts).
  evidence_script(race_attacked race_attacked.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/ims_race_split.json)
  set_tests_properties(evidence.race_attacked PROPERTIES TIMEOUT 400 PROCESSORS 2 SKIP_RETURN_CODE 77)
endif()

# A graph of 100 000 nodes validated, and a zero-delay cycle through them all refused.
add_test(NAME graph.validate_100k_nodes
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/big_graph.sh ${BY} ${RUNS}/big_graph)

# brickyard report on hand-edited summaries: drawn or refused naming the file, never a crash.
evidence_script(report_bad_summary report_bad_summary.py ${GOOD})

by_next_domain(d)
add_test(NAME evidence.ctrl_c_clean_shutdown
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/interrupt.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json ${d} ${RUNS}/interrupt)
by_next_domain(d)
add_test(NAME graph.configs_demo
  COMMAND ${NETNS} ${EXPECT} 0 "\\[brickyard\\] success" -- ${BY} run ${PROJECT_SOURCE_DIR}/configs/demo.json --domain ${d} --out ${RUNS}/demo)

# The plain subscriber compiles its own copy of the IDL: it shares no code with Brickyard.
set(raw_gen ${CMAKE_CURRENT_BINARY_DIR}/raw_gen)
file(MAKE_DIRECTORY ${raw_gen})
add_custom_command(
  OUTPUT ${raw_gen}/Scalar.cxx ${raw_gen}/ScalarPubSubTypes.cxx ${raw_gen}/Header.cxx ${raw_gen}/HeaderPubSubTypes.cxx
  COMMAND ${FASTDDSGEN} -cs -replace -I ${PROJECT_SOURCE_DIR}/sdk/msgs/core -d ${raw_gen} ${PROJECT_SOURCE_DIR}/sdk/msgs/core/Header.idl ${PROJECT_SOURCE_DIR}/sdk/msgs/testing/Scalar.idl
  DEPENDS ${PROJECT_SOURCE_DIR}/sdk/msgs/core/Header.idl ${PROJECT_SOURCE_DIR}/sdk/msgs/testing/Scalar.idl
  COMMENT "fastddsgen: Scalar for the plain Fast DDS subscriber" VERBATIM)
add_executable(raw_dds_subscriber cli/raw_dds_subscriber.cpp
  ${raw_gen}/Scalar.cxx ${raw_gen}/ScalarPubSubTypes.cxx ${raw_gen}/Header.cxx ${raw_gen}/HeaderPubSubTypes.cxx)
target_include_directories(raw_dds_subscriber PRIVATE ${raw_gen})
target_link_libraries(raw_dds_subscriber PRIVATE fastrtps fastcdr)
target_compile_options(raw_dds_subscriber PRIVATE -Wno-all -Wno-extra)
by_next_domain(d)
add_test(NAME evidence.plain_dds_subscriber
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/plain_subscriber.sh ${BY} $<TARGET_FILE:raw_dds_subscriber>
          ${CMAKE_CURRENT_SOURCE_DIR}/graphs/real_clock.json ${d})

by_next_domain(d)
add_test(NAME evidence.sdk_install_and_template
  COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/sdk_install.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR}/sdk/template
          ${CMAKE_CURRENT_BINARY_DIR}/sdk_test ${d} ${BRICKYARD_SIM})
# It compiles: run it alone so timing-sensitive real-clock tests are not starved of CPU.
set_tests_properties(evidence.sdk_install_and_template PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)

if(BRICKYARD_SIM)
# ---- perception ----
# Same graph and seed, same summary: the chain's metrics and the scorer's figures to the last bit.
evidence_script(perception_determinism determinism.sh ${CMAKE_CURRENT_SOURCE_DIR}/graphs/perception_ims_straight.json)
# The accuracy targets on simulated IMS frames, as a regression guard.
if(BRICKYARD_BENCH)  # bench/ is built with the simulator only
  add_test(NAME evidence.eval_perception COMMAND eval_perception)
  # A track mapped from a drive (docs/mapping.md): the extraction alone, from the true
  # poses (10 s). The whole stack's (eval_map_track --only IMS, 2.5 minutes) misses the banking
  # target on IMS at this commit (0.97°): not a CI test until it holds.
  add_test(NAME evidence.map_track_true_poses COMMAND eval_map_track --true-poses IMS --out ${RUNS}/map_track_true_poses)
  # Issue 41 (docs/results-gnss-faults.md): racing on the map through GNSS faults on one road
  # course. Spielberg with its outer wall only (one wall and the road for long stretches: the
  # harder layout for the map), mapped by a
  # mapping drive, raced clean, then with both receivers gone for 60 s, both biased together by
  # 10 m claiming RTK-fixed, and one biased; each row held to the issue's targets (laps,
  # contacts, error, the bias found within 1 s).
  by_next_domain(d)
  add_test(NAME cli.eval_gnss_faults_no_host COMMAND ${EXPECT} 2 "eval_gnss_faults: --brickyard: /nonexistent/brickyard: not a file"
    -- $<TARGET_FILE:eval_gnss_faults> --brickyard /nonexistent/brickyard)
  by_next_domain(d_fault)  # the fault runs' (eval_gnss_faults --domain d: d + 1)
  add_test(NAME evidence.gnss_faults_spielberg
    COMMAND ${NETNS} env EVAL_GNSS_FAULTS_DIR=${RUNS}/gnss_faults $<TARGET_FILE:eval_gnss_faults> --track Spielberg --layout outer
            --placements 1 --durations 60 --faults dropout,bias_both,bias_one --domain ${d})
  set_tests_properties(evidence.gnss_faults_spielberg PROPERTIES TIMEOUT 900)
  # Both receivers drifting together at (0.2, -0.2) m/s claiming RTK-fixed, on Monza with its outer
  # wall only, at a sixth, a half and five sixths of lap 2 (seed 1): the first put the car into
  # the wall 12.9 s in before the motion check (docs/algorithms.md); every run must finish clean.
  by_next_domains(d_drift 2)  # the clean run's, and the fault runs' (--jobs 1: d + 1)
  add_test(NAME evidence.gnss_drift_monza
    COMMAND ${NETNS} env EVAL_GNSS_FAULTS_DIR=${RUNS}/gnss_drift $<TARGET_FILE:eval_gnss_faults> --track Monza --layout outer
            --placements 3 --seed 1 --durations 60 --faults drift_both --domain ${d_drift})
  set_tests_properties(evidence.gnss_drift_monza PROPERTIES TIMEOUT 1200)
endif()
endif()
