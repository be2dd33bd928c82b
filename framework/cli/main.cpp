// brickyard — the host executive: the command line, dispatched to its commands
// (cli/command_table.hpp); bad input exits with 2, any other error with 1.
#include "cli/arguments.hpp"
#include "cli/command_table.hpp"
#include "cli/usage.hpp"
#include "graph/diagnostics.hpp"

#include <brickyard/abi.hpp>
#include <brickyard/version.hpp>

#include <iostream>
#include <string>

using namespace brickyard::fw;

namespace {

int dispatch(const cli::Args& a) {
  if (a.command == "run") return cli::cmd_run(a, false);
  if (a.command == "validate") return cli::cmd_run(a, true);
  if (a.command == "plugins") return cli::cmd_plugins(a);
  if (a.command == "graph") return cli::cmd_graph(a);
  if (a.command == "report") return cli::cmd_report(a);
  if (a.command == "new-plugin") return cli::cmd_new_plugin(a);
  if (a.command == "map") return cli::cmd_map(a);
  if (a.command == "bag") return cli::cmd_bag(a);
  if (a.command == "capture") return cli::cmd_capture(a);
  if (a.command == "security") return cli::cmd_security(a);
  if (a.command == "topic") return cli::cmd_topic(a);
  if (a.command == "ros2") return cli::cmd_ros2(a);
  cli::usage_error(a.command, "unknown command (commands: run, validate, plugins, graph, report, map, bag, capture, topic, security, ros2, new-plugin)");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" || std::string(argv[1]) == "help")) {
      std::cout << cli::kUsage;
      return 0;
    }
    if (argc >= 2 && std::string(argv[1]) == "--version") {
      std::cout << "brickyard " << BRICKYARD_SDK_VERSION << " (plugin ABI " << BRICKYARD_ABI_MAJOR << "." << BRICKYARD_ABI_MINOR << ")\n";
      return 0;
    }
    return dispatch(cli::parse_args(argc, argv));
  } catch (const InvalidInput& e) {
    std::cerr << format_diagnostics(e.diagnostics());
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
