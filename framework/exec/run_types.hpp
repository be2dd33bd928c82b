#pragma once
// What a run is given and what it gives back: its options (the command line's), its result and
// summary, and the interrupt flag. Shared by the executive and the parts of a run that need no
// executive (summary, recording, lockstep, the node contexts).
#include "transport/dds.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::fw {

struct RunOptions {
  std::optional<double> duration_s;  // overrides the graph's clock.duration_s
  std::uint64_t seed = 0;
  std::string process;               // empty: every node
  std::optional<int> domain;         // overrides transport.domain
  bool quiet = false;
  double progress_s = -1;                // seconds of wall time between progress lines; 0: none;
                                         // < 0: 0.25 on a terminal (one updating line), 5 otherwise
  std::string record;                    // --record FILE: every wire's samples (docs/recording.md)
  std::string record_compression = "zstd";  // --record-compression: an MCAP recording's chunks
  std::string record_profile = "brickyard";  // --record-profile: an MCAP recording's names (brickyard or ros2)
  // The scene (/tf, /scene/*) into an MCAP recording too: --record-scene on|off; unsaid, on
  // unless --record-only narrows the recording to the wires it names.
  std::optional<bool> record_scene;
  std::vector<std::string> record_only;  // --record-only: "node.port" patterns ('*' any); empty: all
  std::vector<std::string> record_skip_types;  // message types not recorded (the --out default skips clouds)
  std::optional<int> live_port;          // --live PORT: the Foxglove WebSocket server (docs/live.md)
  std::string live_address = "127.0.0.1";  // --live-address: loopback unless said otherwise
  double record_cloud_precision = 0;      // --record-cloud-precision: clouds recorded to this many metres, compact (0: exact)
  double live_cloud_hz = 20;             // --live-cloud-hz: a cloud channel's most clouds a second, wall time (0: all)
  double pace = 0;                       // --pace X: sim clock at most X times real time (0: as fast as it goes)
  int threads = 0;        // sim clock: threads that step nodes (0: the machine's cores, at most 4)
  bool profile = false;  // --profile: each node's wall time in step, in the summary ("step_wall_s")
  DdsSecurity security;  // transport.security: this process's identity's files (checked readable before the run)
};

enum class RunResult { success, failed, interrupted, invalid_input };
const char* to_string(RunResult r);

struct RunSummary {
  RunResult result = RunResult::success;
  std::string reason;
  double sim_time_s = 0, wall_time_s = 0;
  nlohmann::json json;  // what summary.json holds
};

// Set from a signal handler: the running executive stops cleanly at the next event.
extern std::atomic<bool> g_interrupt;
// Set in a supervised process whose supervisor is gone (the kernel's parent-death signal, SIGHUP:
// PR_SET_PDEATHSIG): the run ends as interrupted, and says why.
extern std::atomic<bool> g_supervisor_gone;
inline const char* interrupt_reason() { return g_supervisor_gone ? "interrupted: its supervisor died" : "interrupted"; }

}  // namespace brickyard::fw
