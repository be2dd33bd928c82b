#pragma once
// Runs a resolved graph: builds the nodes of this process, wires them, steps them on the sim
// clock (one thread, ordered, reproducible) or the real clock (a thread per node).
// executive.cpp: a run's lifecycle; wiring.cpp: the nodes and wires; sim_scheduler.cpp and
// real_scheduler.cpp: the two clocks; run_types.hpp: what a run is given and gives back; console,
// summary, recording, file_search, seeding: the rest.
#include "exec/channels.hpp"
#include "exec/console.hpp"
#include "exec/node_context.hpp"
#include "exec/peer_ends.hpp"
#include "exec/run_types.hpp"
#include "graph/resolve.hpp"
#include "live/live_server.hpp"
#include "live/scene.hpp"
#include "record/recorder.hpp"
#include "transport/dds.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::fw {

class NodeRuntime;
class Lockstep;
struct LockRecord;

class Executive final : public NodeHost {
 public:
  Executive(const ResolvedGraph& g, RunOptions opt);
  ~Executive();
  RunSummary run();

  // For NodeContext (NodeHost).
  std::int64_t now_ns() const override;
  std::string find_file(std::string_view path) const override;
  bool sim() const override { return graph_.decl->clock.sim; }
  std::uint64_t seed() const { return opt_.seed; }
  void log(const NodeRuntime& n, LogLevel level, std::string_view msg) override;
  void request_stop(RunResult r, std::string reason) override;
  // An input whose writer runs in another process (a split run).
  struct RemoteInput {
    std::string input, writer, process;  // "node.port", "node.port", the writer's process
    DdsReader* reader = nullptr;
    bool lost = false;                   // under stop_m_
    std::int64_t lost_at_ns = 0;         // wall time of the lapse
    // Steady time of the last sample (0: none yet): how long the writer had been silent when its
    // lapse was noticed, measured here rather than guessed from outside (docs/reliability.md).
    std::atomic<std::int64_t> last_sample_ns{0};
  };
  // Its writer went silent (its liveliness lapsed): said now, and the run fails at its end unless
  // the graph lets the writer's process die; it goes on meanwhile (a car interface keeps braking
  // the car). Or its writer is alive: when it had lapsed, how long it was gone is said and kept.
  void peer_liveliness(RemoteInput& in, bool alive);
  // A peer process said how its run ended, or left without saying it (exec/peer_ends.hpp).
  void peer_ended(const std::string& process, const PeerEnd& end);
  void peer_left_unsaid(const std::string& process);
  // A writer the graph does not name sent to the input (a participant not the writer's process).
  void foreign_writer(RemoteInput& in, const std::string& participant, const std::string& writer);
  void set_status(const std::string& node, std::string_view field, std::string_view value) override;

 private:
  // A run's steps (executive.cpp), in order.
  void open_record_and_live();  // --record's file and --live's server, before any node exists
  bool try_build();             // build(), its failure the run's: whether it was built
  // Construction, configuration and activation, node by node in schedule order: the nodes activated.
  std::vector<NodeRuntime*> bring_up(bool built);
  // One lifecycle phase over `over`, up to the first call that fails: the nodes it was done for.
  std::vector<NodeRuntime*> lifecycle_phase(std::int64_t tag, const std::vector<NodeRuntime*>& over,
                                            const std::function<bool(NodeRuntime&)>& one);
  void deactivate(const std::vector<NodeRuntime*>& active);
  void finish_lockstep(const std::vector<LockRecord>& asked);  // `asked`: this process's deactivations' requests
  nlohmann::json live_summary() const;  // summary.json's "live" (null without --live)
  nlohmann::json recording_summary();   // the recording closed: summary.json's "recording" (null without one)
  RunSummary summarize(std::chrono::steady_clock::time_point wall0, const nlohmann::json& live, const nlohmann::json& recording);

  // The nodes and wires (wiring.cpp).
  struct NodesByName {
    std::map<std::string, NodeRuntime*> here, phantom;  // this process's; another's, in a lockstep run
  };
  void build();
  void make_transport();
  NodeRuntime* add_node(const ResolvedNode& rn);  // this process's node: its ports, context and status fields
  void add_output(NodeRuntime& n, const PortSpec& p);  // its DDS writer and tap
  void make_lockstep();
  void wire(const WireDecl& w, const NodesByName& by_name);
  void connect_remote_input(const WireDecl& w, const NodeRuntime& to, InputQueue* in, const std::string& wire_type,
                            OutputPort* by_phantom);
  // What the scenes (the live view's, the recording's) draw of a topic's samples (exec/output_tap.cpp).
  std::function<void(const void*, std::uint64_t)> scene_handler(const std::string& topic, const std::string& type);
  // Records an output's samples, serves them live and draws them in the scene (exec/output_tap.cpp).
  void tap_output(OutputPort& out, const std::string& topic, const std::string& type);
  bool call(NodeRuntime& n, const char* phase, const std::function<void()>& f);
  class SimRun;  // one run of the sim clock (sim_scheduler.cpp)
  void run_sim();
  std::int64_t sim_end_ns() const;  // the sim clock's end (INT64_MAX: none)
  void run_real();
  // The real clock: a node's next trigger, waited for (real_scheduler.cpp); none once the run stops.
  std::optional<Trigger> next_real_trigger(NodeRuntime& n, std::chrono::steady_clock::time_point& next);
  void step(NodeRuntime& n, Trigger t);
  bool step_body(NodeRuntime& n, Trigger t);  // step without counting it: whether it returned
  // How long a step may stay stuck before the watchdog ends the process (0: never).
  double hang_after_s(const NodeRuntime& n) const;
  void host_log(const std::string& msg);
  void progress(bool last = false);  // prints the progress line when it is due (or last)
  void pace(std::int64_t sim_ns);    // --pace: waits until the wall clock has caught up with sim_ns / pace
  bool await_peers();                // a split run's start-up: its inputs' writers matched, or the run fails
  // A split run on the sim clock (exec/lockstep.hpp): the start-up with its peers, whose own
  // start-up failures end this run too; an event of this process recorded, another's replayed.
  void lockstep_start();
  template <class Effects>
  void local_event(std::size_t i, std::int64_t t_ns, Effects&& effects);
  // Its record queued for the others: the outputs it published on, and the stop it asked for
  // (`stopped_before`: the run had stopped before it).
  void record_local_event(std::size_t i, std::int64_t t_ns, std::vector<std::uint16_t> pubs, bool stopped_before);
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
  std::unique_ptr<SceneOutlet> scene_recording_;  // the same scene into the recording (MCAP), and its drawing
  std::unique_ptr<LiveScene> recorded_scene_;
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
  std::unique_ptr<PeerEnds> ends_;        // a split run on the real clock: how each process ended
  std::vector<std::string> failed_peers_;  // under stop_m_: processes that failed or left unsaid, failing the run
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

// An event of this process in a lockstep run: done, and its record queued for the others.
// Without lockstep just done.
template <class Effects>
void Executive::local_event(std::size_t i, std::int64_t t_ns, Effects&& effects) {
  if (!lock_) {
    effects();
    return;
  }
  std::vector<std::uint16_t> pubs;
  const bool was = stop_;
  t_publog = &pubs;
  effects();
  t_publog = nullptr;
  record_local_event(i, t_ns, std::move(pubs), was);
}

}  // namespace brickyard::fw
