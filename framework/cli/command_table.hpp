#pragma once
// The entry point of each `brickyard COMMAND` (cli/main.cpp dispatches to them): the command's
// exit code, 0 success, 1 the run failed, 2 invalid input. Bad input may also be thrown as
// InvalidInput, which main prints, exiting with 2.
#include "cli/arguments.hpp"

namespace brickyard::fw::cli {

int cmd_run(const Args& a, bool validate_only);  // run GRAPH; validate GRAPH (validate_only)
int cmd_plugins(const Args& a);                  // plugins [NAME]
int cmd_graph(const Args& a);                    // graph GRAPH --dot
int cmd_report(const Args& a);                   // report RUN_DIR
int cmd_new_plugin(const Args& a);               // new-plugin NAME --dir DIR
int cmd_map(const Args& a);                      // map build RECORDING --out DIR
int cmd_bag(const Args& a);                      // bag info | play RECORDING
int cmd_capture(const Args& a);                  // capture info | play FILE (a pcap or a GNSS log)
int cmd_security(const Args& a);                 // security init GRAPH --out DIR
int cmd_topic(const Args& a);                    // topic list | echo | hz
int cmd_ros2(const Args& a);                     // ros2 msgs --out DIR

}  // namespace brickyard::fw::cli
