#pragma once
// The command line: a command, its target and further positional arguments, and every option
// (cli/usage.cpp says what each means).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::fw::cli {

struct Args {
  std::string command, target, dir, role, out, process, record, record_compression = "zstd", record_profile = "brickyard";
  std::optional<bool> record_scene;  // --record-scene on|off
  std::vector<std::string> more;  // positional arguments after the target (map build RECORDING)
  std::vector<std::string> record_only;
  std::vector<std::string> sets, args, plugin_paths;
  std::optional<double> duration;
  std::optional<int> domain;
  double progress = -1, pace = 0;
  std::optional<int> live_port;
  std::optional<long> count;
  double rate = 1.0;
  std::vector<std::string> only;
  std::string live_address = "127.0.0.1";
  bool live_address_set = false;
  std::optional<double> live_cloud_hz;  // --live-cloud-hz
  double record_cloud_precision = 0;    // --record-cloud-precision (0: clouds exact)
  int threads = 0;
  std::uint64_t seed = 0;
  bool json = false, dot = false, quiet = false, no_report = false, profile = false, one_process = false;
  std::vector<std::string> child_flags;  // what a supervised run's children are given as they are
  std::string bag_map;  // bag play --map FILE: a ROS 2 bag's topics onto wires (cli/bag_map.hpp)
  std::string security, identity, protect = "encrypt";  // security init; topic and bag play against a secured graph
  bool ros2_naming = false;  // topic, bag play: --naming ros2 (a graph whose transport.naming is "ros2")
  int days = 365;
  std::string to, metadata;         // capture play's sink; capture info's Ouster metadata
  std::optional<int> port;          // capture: a pcap's UDP destination port
  bool loop = false;                // capture play: start again at the end
};

// Bad input on the command line: throws InvalidInput (exit 2) naming `where`.
[[noreturn]] void usage_error(const std::string& where, const std::string& msg);

// argv as Args; throws InvalidInput on an unknown option, a bad value or a stray argument.
Args parse_args(int argc, char** argv);

}  // namespace brickyard::fw::cli
