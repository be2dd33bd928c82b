# The CLI's commands. Included by tests/CMakeLists.txt.

# ---- CLI commands ----
function(cli_test name code regex)
  add_test(NAME cli.${name} COMMAND ${EXPECT} ${code} "${regex}" -- ${BY} ${ARGN})
endfunction()
cli_test(plugin_override 0 "notice: plugin 'testing.transform' from .*/duplicate/libfixture_duplicate.so overrides the one in .*/libtesting_transform.so" plugins --plugin-path ${FIXTURES}/duplicate)
cli_test(validate_ok 0 "chain.json: valid — 3 nodes, 2 wires" validate ${GOOD})
# A plugin of ABI 2.4 (before roles) is refused at validation, naming the library and both versions.
bad_input(older_abi "libfixture_older_abi.so: built against plugin ABI 2.4 \\(SDK 0.9.0\\), this host's is 3.1: rebuild the plugin against this SDK" validate ${CMAKE_CURRENT_SOURCE_DIR}/fixtures/older_abi_graph.json --plugin-path ${FIXTURES}/older_abi)
# Graphs that include graphs: run, and errors in the file that declared the value.
set(COMPOSED ${CMAKE_CURRENT_SOURCE_DIR}/graphs/composed)
by_next_domain(d)
add_test(NAME graph.composed_run COMMAND ${NETNS} ${EXPECT} 0 "check +testing.assert_sink +100 +.*passed 1.*success"
  -- ${BY} run ${COMPOSED}/chain_tripled.json --domain ${d})
bad_input(include_cycle   "cycle_b.json#/include/0: an include cycle: .*cycle_a.json includes .*cycle_b.json includes .*cycle_a.json" run ${COMPOSED}/cycle_a.json)
bad_input(include_bad_override "composed/bad_override.json#/nodes/double/params/gain: expected number" run ${COMPOSED}/bad_override.json)
# --set NODE.plugin=NAME: the node's plugin swapped, checked like the file's.
bad_input(set_unknown_plugin "#/nodes/src/plugin: unknown plugin \"nope.x\" \\(from --set src.plugin=nope.x\\)" run ${GOOD} --set src.plugin=nope.x)
# Roles: a plugin claiming one its ports do not fit, a node's role its plugin does not play, a
# role the SDK does not define, a planner swapped by --set for a plugin without the path output.
bad_input(role_claim "libfixture_role_claim.so: plugin 'fixture.false_planner': plays role 'planner' but no output 'path' \\(brickyard::msgs::Path\\)" validate ${GOOD} --plugin-path ${FIXTURES}/role_claim)
bad_input(role_not_played "role_not_played.json#/nodes/planner/role: plugin testing.transform of node 'planner' does not play role 'planner': no input 'estimate' \\(brickyard::msgs::LocalizationEstimate\\); no output 'path'" validate ${BAD}/role_not_played.json)
bad_input(unknown_role "unknown_role.json#/nodes/src/role: unknown role \"planer\" \\(roles: planner, path_tracker, " validate ${BAD}/unknown_role.json)
if(BRICKYARD_SIM)
  bad_input(set_plugin_role "race.json#/nodes/planner/plugin: plugin fixture.pathless_planner of node 'planner' does not play role 'planner': no output 'path' \\(brickyard::msgs::Path\\) \\(from --set planner.plugin=fixture.pathless_planner\\)"
            validate ${PROJECT_SOURCE_DIR}/configs/race.json --plugin-path ${FIXTURES}/pathless_planner --set planner.plugin=fixture.pathless_planner)
endif()
bad_input(set_plugin_param   "#/nodes/double/params/gain: unknown parameter \"gain\" of plugin testing.assert_sink.*\\(from --set double.gain=3\\)" run ${GOOD} --set double.plugin=testing.assert_sink --set double.gain=3)
if(BRICKYARD_SIM)  # the planner swap of the race graph: one flag
  cli_test(planner_swap 0 "notice: node 'planner' runs planning.racing_line \\(--set planner.plugin=planning.racing_line\\): the file's curvature_limit is not its parameter, left out.*race.json: valid"
           validate ${PROJECT_SOURCE_DIR}/configs/race.json --set planner.plugin=planning.racing_line)
endif()
cli_test(plugins_text 0 "testing.transform 1.0.0.*\n.*\n  in  in : brickyard::msgs::Scalar" plugins)
cli_test(plugins_json 0 "\"ports\": \\[" plugins --json)
# plugins NAME: that plugin alone, with the roles it plays; an unknown name is exit 2 naming the known.
add_test(NAME cli.plugins_one COMMAND ${EXPECT} 0 "^testing.transform 1.0.0" "testing.scripted_source" -- ${BY} plugins testing.transform)
if(BRICKYARD_SIM)
  add_test(NAME cli.plugins_roles COMMAND ${EXPECT} 0 "planning.road_graph .*\n  plays planner\n" "control.path_tracker" -- ${BY} plugins planning.road_graph)
endif()
cli_test(plugins_unknown 2 "plugins testing.nope: no plugin of that name \\(known: .*testing.transform" plugins testing.nope)
cli_test(plugins_json_params 0 "\"name\": \"rate_hz\",|\"unit\": \"Hz\"" plugins --json)
cli_test(plugins_broken_library 2 "libnot_elf.so: not a shared object" plugins --plugin-path ${FIXTURES}/not_elf)
cli_test(graph_dot 0 "digraph \"chain\".*\"src\" -> \"double\" \\[label=\"out → in.nScalar\"\\]" graph ${GOOD} --dot)
cli_test(version 0 "brickyard 0\\.3\\.0 \\(plugin ABI 3\\.1\\)" --version)
cli_test(unknown_command 2 "frobnicate: unknown command" frobnicate)
cli_test(bag_needs_a_command 2 "bag: needs a command \\(brickyard bag info \\| play RECORDING\\)" bag)
cli_test(map_unknown_command 2 "map frob: unknown map command" map frob)
cli_test(new_plugin_bad_name 2 "new-plugin Bad-Name: expected a name like" new-plugin Bad-Name --dir ${CMAKE_CURRENT_BINARY_DIR}/scaffold_bad)
# --role: a role it does not know, or one without a template, named with those it has (exit 2).
cli_test(new_plugin_unknown_role 2 "--role no_such_role: unknown role \\(roles: planner, path_tracker, .*; roles with one: planner\\)"
         new-plugin acme.x --role no_such_role --dir ${CMAKE_CURRENT_BINARY_DIR}/scaffold_role)
cli_test(new_plugin_role_without_template 2 "--role estimator: no template for this role yet \\(roles with one: planner\\)"
         new-plugin acme.x --role estimator --dir ${CMAKE_CURRENT_BINARY_DIR}/scaffold_role)
# A plugin library whose load-time code aborts or calls exit(): named, the run fails (exit 1) and
# its summary is written in --out (the folder made by the crash handler); validate names it too.
foreach(kind abort exit)
  set(said_abort "crashed with SIGABRT \\(abort\\) while it was being loaded")
  set(said_exit "called exit\\(\\) while it was being loaded")
  set(out ${RUNS}/load_${kind})
  add_test(NAME cli.plugin_load_${kind}_named COMMAND sh -c "mkdir -p ${RUNS} && rm -rf ${out} && \"$0\" \"$@\" && grep -q '\"result\": \"failed\", \"reason\": \"plugin library .*libfixture_load_${kind}.so' ${out}/summary.json"
    ${EXPECT} 1 "plugin library .*/load_${kind}/libfixture_load_${kind}.so ${said_${kind}}" -- ${BY} run ${GOOD} --plugin-path ${FIXTURES}/load_${kind} --out ${out})
  add_test(NAME cli.plugin_load_${kind}_named_by_validate
    COMMAND ${EXPECT} 1 "plugin library .*/load_${kind}/libfixture_load_${kind}.so ${said_${kind}}" -- ${BY} validate ${GOOD} --plugin-path ${FIXTURES}/load_${kind})
endforeach()
# `security init` that cannot write its files (a full disk: the file-size limit here) leaves no
# half-made keys folder (issue 44).
add_test(NAME cli.security_init_full_disk
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/security_init_full_disk.sh ${BY} ${CMAKE_CURRENT_SOURCE_DIR}/graphs/multiprocess/two_process.json
          ${CMAKE_CURRENT_BINARY_DIR}/runs/security_init_full_disk)
