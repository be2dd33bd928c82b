# The house's rules, checked: includes, ports and parameters declared once, function length.
# Included by tests/CMakeLists.txt.

# ---- the house: nothing car-side includes the simulator (docs/architecture.md) ----
add_test(NAME architecture.car_side_never_includes_the_simulator
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/car_side_includes.sh ${PROJECT_SOURCE_DIR})
add_test(NAME architecture.include_check_catches_a_violation
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/car_side_includes.sh --self-test ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/include_self_test)
add_test(NAME architecture.plugins_declare_each_parameter_once
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/params_declared_once.sh ${PROJECT_SOURCE_DIR})
add_test(NAME architecture.parameter_check_catches_a_violation
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/params_declared_once.sh --self-test ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/param_self_test)
# No function over 80 lines, no plugin.cpp over 150 (scripts/long-functions.allowed is empty).
add_test(NAME architecture.no_new_long_functions COMMAND ${PROJECT_SOURCE_DIR}/scripts/long-functions --check)
# The check catches a planted long function and a planted long adapter.
add_test(NAME architecture.long_function_check_catches_a_new_one
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/long_functions_self_test.sh ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/long_functions_self_test)
add_test(NAME architecture.plugins_declare_each_port_once
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/ports_declared_once.sh ${PROJECT_SOURCE_DIR})
add_test(NAME architecture.port_check_catches_a_violation
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/ports_declared_once.sh --self-test ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/port_self_test)
# scripts/bench-report merges a benchmark's rounds into its block of the document, and refuses
# what it cannot do (docs/performance.md).
add_test(NAME architecture.bench_report_merges_rounds
  COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/bench_report_self_test.py ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/bench_report_self_test)
