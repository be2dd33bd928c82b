#pragma once
// Runs a resolved graph: builds the nodes of this process, wires them, steps them on the sim
// clock (one thread, ordered, reproducible) or the real clock (a thread per node).
// executive.cpp: a run's lifecycle; wiring.cpp: the nodes and wires; sim_scheduler.cpp and
// real_scheduler.cpp: the two clocks; console, summary, recording, file_search, seeding: the rest.
#include "exec/channels.hpp"
#include "exec/console.hpp"
#include "graph/resolve.hpp"
#include "live/live_server.hpp"
#include "live/scene.hpp"
#include "record/recorder.hpp"
#include "transport/dds.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <optional>

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

class NodeRuntime;
class Lockstep;
struct LockRecord;

class Executive {
 public:
  Executive(const ResolvedGraph& g, RunOptions opt);
  ~Executive();
  RunSummary run();

  // For NodeContext.
  std::int64_t now_ns() const;
  std::string find_file(std::string_view path) const;
  bool sim() const { return graph_.decl->clock.sim; }
  std::uint64_t seed() const { return opt_.seed; }
  void log(const NodeRuntime& n, LogLevel level, std::string_view msg);
  void request_stop(RunResult r, std::string reason);
  // An input whose writer runs in another process (a split run).
  struct RemoteInput {
    std::string input, writer, process;  // "node.port", "node.port", the writer's process
    DdsReader* reader = nullptr;
    bool lost = false;                   // under stop_m_
    std::int64_t lost_at_ns = 0;         // wall time of the lapse
  };
  // Its writer went silent (its liveliness lapsed): said now, and the run fails at its end unless
  // the graph lets the writer's process die; it goes on meanwhile (a car interface keeps braking
  // the car). Or its writer is alive: when it had lapsed, how long it was gone is said and kept.
  void peer_liveliness(RemoteInput& in, bool alive);
  // A writer the graph does not name sent to the input (a participant not the writer's process).
  void foreign_writer(RemoteInput& in, const std::string& participant, const std::string& writer);
  void set_status(const std::string& node, std::string_view field, std::string_view value);

 private:
  void build();
  // Records an output's samples, serves them live and draws them in the scene (exec/output_tap.cpp).
  void tap_output(OutputPort& out, const std::string& topic, const std::string& type);
  bool call(NodeRuntime& n, const char* phase, const std::function<void()>& f);
  void run_sim();
  std::int64_t sim_end_ns() const;  // the sim clock's end (INT64_MAX: none)
  void run_real();
  void step(NodeRuntime& n, Trigger t);
  bool step_body(NodeRuntime& n, Trigger t);  // step without counting it: whether it returned
  void host_log(const std::string& msg);
  void progress(bool last = false);  // prints the progress line when it is due (or last)
  void pace(std::int64_t sim_ns);    // --pace: waits until the wall clock has caught up with sim_ns / pace
  bool await_peers();                // a split run's start-up: its inputs' writers matched, or the run fails
  // A split run on the sim clock (exec/lockstep.hpp): the start-up with its peers, whose own
  // start-up failures end this run too; an event of this process recorded, another's replayed.
  void lockstep_start();
  template <class Effects>
  void local_event(std::size_t i, std::int64_t t_ns, Effects&& effects);
  void remote_event(std::size_t i, std::int64_t t_ns);
  // The lifecycle's events, told apart from steps by their time (no step is at a negative time).
  static constexpr std::int64_t kConstruction = -3, kConfigure = -2, kActivate = -1;
  void lockstep_failed(const std::string& why, const std::optional<std::pair<RunResult, std::string>>& peer_stop);

  const ResolvedGraph& graph_;
  RunOptions opt_;
  std::unique_ptr<DdsTransport> transport_;
  std::unique_ptr<Recorder> recorder_;
  std::unique_ptr<LiveServer> live_;
  std::unique_ptr<LiveScene> scene_;  // the scene in Foxglove's schemas, beside the wires (--live)
  std::vector<std::unique_ptr<NodeRuntime>> nodes_;
  // Every node the sim scheduler steps, in schedule order: this process's, and in a lockstep run
  // the others' phantoms (kept in phantoms_) between them.
  std::vector<NodeRuntime*> sched_;
  std::vector<std::unique_ptr<NodeRuntime>> phantoms_;
  std::unique_ptr<Lockstep> lock_;
  std::vector<LockRecord>* deactivate_log_ = nullptr;  // a lockstep run's deactivation: what each node asks
  std::size_t deactivating_ = 0;                              // its place in the schedule
  std::map<std::pair<const OutputPort*, const InputQueue*>, int> lock_wires_;  // a phantom's wire into this process: its samples' key

  std::atomic<bool> stop_{false};
  std::atomic<std::int64_t> live_tap_ns_{0};  // wall time the stepping threads spent on the live view (summary: live.taps_s)
  std::vector<std::unique_ptr<RemoteInput>> remote_inputs_;
  std::vector<std::string> lost_peers_;  // under stop_m_: writers lost that fail the run
  nlohmann::json peer_events_ = nlohmann::json::array();  // under stop_m_: every lapse and return
  nlohmann::json foreign_writers_ = nlohmann::json::array();  // under stop_m_
  std::mutex stop_m_;
  std::optional<RunResult> stop_result_;
  std::string stop_reason_;

  std::int64_t sim_now_ns_ = 0;
  std::int64_t real_start_ns_ = 0;
  std::optional<std::chrono::steady_clock::time_point> pace_start_;
  Console console_;  // log lines and the progress line
};

}  // namespace brickyard::fw
