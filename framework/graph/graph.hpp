#pragma once
// The graph file as declared: structure checked, nothing resolved against plugins yet.
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::fw {

struct NodeDecl {
  std::string name;
  std::string plugin;
  std::string process;            // empty: the default process "main"
  double deadline_s = 0;          // a step longer than this fails the run (wall time; 0: none; docs/reliability.md)
  nlohmann::json params = nlohmann::json::object();
  std::map<std::string, std::string> param_origin;  // param -> "--set ..." when overridden on the command line
  std::string plugin_origin;                        // "--set NODE.plugin=..." when the plugin was swapped there
  std::string replaced_plugin;                      // the file's plugin that --set swapped out
  std::string role;                                 // "role": the role its plugin must play (brickyard/roles.hpp)
};

struct Endpoint {
  std::string node, port;
  std::string text() const { return node + "." + port; }
};

struct WireDecl {
  Endpoint from, to;
  std::size_t index = 0;  // position in /wires
  std::string to_item;    // "" when "to" is one endpoint; "/K" for item K of a "to" list
  std::string to_ptr() const { return "/wires/" + std::to_string(index) + "/to" + to_item; }
};

// The longest run a clock can time: 10^7 s (116 days), far inside the int64 nanoseconds of the
// clocks (292 years); a longer one would wrap to a negative time.
inline constexpr double kMaxDuration_s = 1e7;

struct ClockDecl {
  bool sim = true;
  double step_s = 0.001;
  std::optional<double> duration_s;
};

struct TransportDecl {
  int domain = 0;
  std::vector<std::string> interfaces{"127.0.0.1"};  // UDP interfaces allowed; loopback only by default
  std::vector<std::string> peers{"127.0.0.1"};       // unicast discovery peers
  double startup_timeout_s = 10;  // a split run waits this long for its inputs' writers in other processes
  // A split run on the sim clock: a process that ended waits this long for its peers' ends
  // (Lockstep::finish), its supervisor a little longer. A peer is behind by little once a process
  // ended: every event's owner did it before the others replayed it, so what a peer has left is
  // replaying the last events and deactivating its nodes, and a deactivation stuck for
  // kLifecycleHang_s (60 s) ends its process (then it is lost, not awaited). Twice that is room
  // enough, and a peer whose end record never comes (alive, matched) holds no one for ever.
  double end_timeout_s = 120;
  bool ros2_naming = false;  // "naming": "ros2": topics and types on the wire as ROS 2 names them (docs/ros2.md)
  bool shared_memory = true;  // "shared_memory": false: UDP only between processes (docs/reliability.md: a killed writer can lock a peer's port)
  bool accept_foreign_writers = false;  // "foreign_writers": "accept": samples from writers the graph does not name are used (warned of either way)
  // "security": the folder `brickyard security init` made (resolved against the graph file's
  // folder); "off": none, warned of on a split run; empty (absent): a split run is secured with
  // keys made for the graph (security/default_keys.hpp, docs/security.md).
  std::string security;
};

// `"security": "off"`: a split run without DDS security, the explicit and warned choice (a folder
// named off is "./off").
inline const std::string kSecurityOff = "off";

// "processes": what the supervisor does when a process of a split run dies (docs/reliability.md).
struct ProcessDecl {
  enum class Restart { never, on_failure };
  Restart restart = Restart::never;
  int max_restarts = 3;    // on-failure: restarts at most this many times, then the run fails
  double backoff_s = 0.1;  // on-failure: the first restart's delay, doubled for each next (at most 5 s)
  bool may_die = false;    // its death does not fail the run (nor does its peers' losing it)
};

// "live": serve the run to Foxglove (docs/live.md), as `--live PORT` does; the flags win.
struct LiveDecl {
  std::optional<int> port;
  std::string address = "127.0.0.1";  // loopback unless the graph says otherwise
  std::optional<double> cloud_hz;      // a cloud channel's most clouds a second, wall time (0: every one)
};

struct GraphDecl {
  std::string file;          // path as given
  std::string name;
  std::string description;
  std::map<std::string, NodeDecl> nodes;  // sorted by name: a deterministic order everywhere
  std::vector<WireDecl> wires;
  ClockDecl clock;
  TransportDecl transport;
  LiveDecl live;
  std::map<std::string, ProcessDecl> processes;  // only those the graph's "processes" names
  std::vector<std::string> plugin_path;  // resolved against the graph file's folder
  // A composed graph (includes): JSON pointer -> the file that declared its value and its pointer
  // there; empty for a graph of one file.
  std::map<std::string, std::pair<std::string, std::string>> provenance;
  // "FILE#POINTER" of the file that declared the value at `pointer` (the graph's file when one).
  std::string where(const std::string& pointer) const;
};

inline const std::string kDefaultProcess = "main";

// The process's policy: the graph's, or the defaults (never restarted, may not die).
const ProcessDecl& process_policy(const GraphDecl& g, const std::string& process);

// "<file>#<pointer>" — how every post-parse error names its place.
std::string at(const std::string& file, const std::string& pointer);
std::string pointer_escape(const std::string& token);

// Parse and check a graph file; `sets` are --set node.param=value overrides. Throws InvalidInput.
// `args` are --arg name=value: the graph's named arguments (graph_args.hpp), filled in before the sets.
GraphDecl load_graph_file(const std::string& path, const std::vector<std::string>& sets = {},
                          const std::vector<std::string>& args = {});
GraphDecl parse_graph_text(const std::string& text, const std::string& file, const std::vector<std::string>& sets = {},
                           const std::vector<std::string>& args = {});

}  // namespace brickyard::fw
