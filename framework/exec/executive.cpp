// A run's lifecycle: recording opened, nodes built, constructed, configured, activated, stepped
// by the clock's scheduler, deactivated (every activated node, even after a failure), and the
// summary. Also what the executive serves NodeContext: the clock, logs, end requests.
#include "exec/executive.hpp"
#include "exec/node_checks.hpp"
#include "exec/crash_guard.hpp"
#include "exec/file_search.hpp"
#include "exec/lockstep.hpp"
#include "exec/node_runtime.hpp"
#include "exec/recording.hpp"
#include "exec/summary.hpp"

#include <algorithm>
#include <set>
#include <chrono>
#include <thread>
#include <cstdio>

namespace brickyard::fw {

std::atomic<bool> g_interrupt{false};
std::atomic<bool> g_supervisor_gone{false};
thread_local Deferred* t_deferred = nullptr;
thread_local std::int64_t t_step_now_ns = -1;
thread_local std::vector<std::uint16_t>* t_publog = nullptr;

const char* to_string(RunResult r) {
  switch (r) {
    case RunResult::success: return "success";
    case RunResult::failed: return "failed";
    case RunResult::interrupted: return "interrupted";
    case RunResult::invalid_input: return "invalid_input";
  }
  return "?";
}

namespace {
std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}
std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Executive::Executive(const ResolvedGraph& g, RunOptions opt) : graph_(g), opt_(std::move(opt)) {}

Executive::~Executive() {
  // Teardown order matters: deliveries stop, plugin objects go, then DDS entities.
  if (transport_) transport_->close_readers();
  ends_.reset();
  lock_.reset();  // (after its readers, which feed it)
  for (auto& n : nodes_)
    if (n->instance) n->rn->plugin->descriptor->destroy(n->instance);
  nodes_.clear();
  transport_.reset();
}

std::int64_t Executive::now_ns() const { return sim() ? sim_now_ns_ : wall_ns(); }

void Executive::host_log(const std::string& msg) {
  if (opt_.quiet) return;
  console_.line([&] { std::fprintf(stderr, "[brickyard] %s\n", msg.c_str()); });
}

void Executive::set_status(const std::string& node, std::string_view field, std::string_view value) {
  if (t_deferred) {
    t_deferred->emplace_back([this, node, f = std::string(field), v = std::string(value)] { set_status(node, f, v); });
    return;
  }
  console_.set_status(node, field, value);
}

void Executive::pace(std::int64_t sim_ns) {
  // The host's own use of the wall clock, for a person watching (--live): never seen by a node.
  const auto now = std::chrono::steady_clock::now();
  if (!pace_start_) pace_start_ = now;
  const auto due = *pace_start_ + std::chrono::nanoseconds(static_cast<std::int64_t>(static_cast<double>(sim_ns) / opt_.pace));
  while (!g_interrupt && !stop_ && std::chrono::steady_clock::now() < due)
    std::this_thread::sleep_until(std::min(due, std::chrono::steady_clock::now() + std::chrono::milliseconds(50)));
}

void Executive::progress(bool last) {
  console_.progress(last, sim(), sim_now_ns_, [this] {
    const std::string stale = stale_inputs_text(nodes_, now_ns());
    return stale.empty() ? stale : "stale " + stale;
  });
}

void Executive::log(const NodeRuntime& n, LogLevel level, std::string_view msg) {
  if (t_deferred) {
    t_deferred->emplace_back([this, &n, level, m = std::string(msg)] { log(n, level, m); });
    return;
  }
  if (opt_.quiet && level < LogLevel::warn) return;
  static const char* names[] = {"debug", "info", "warn", "error"};
  double t = sim() ? sim_now_ns_ * 1e-9 : (wall_ns() - real_start_ns_) * 1e-9;
  console_.line([&] {
    std::fprintf(stderr, "[%9.3f] %s %s: %.*s\n", t, names[static_cast<int>(level)], n.name.c_str(),
                 static_cast<int>(msg.size()), msg.data());
  });
}

void Executive::peer_liveliness(RemoteInput& in, bool alive) {
  const std::int64_t now = wall_ns();
  const double t = sim() ? sim_now_ns_ * 1e-9 : (now - real_start_ns_) * 1e-9;
  const bool may_die = process_policy(*graph_.decl, in.process).may_die;
  const std::string who = "input " + in.input + ": its writer " + in.writer + " (process '" + in.process + "')";
  std::string line;
  {
    std::lock_guard<std::mutex> l(stop_m_);
    if (!alive && !in.lost) {
      in.lost = true;
      in.lost_at_ns = now;
      std::string what = who + " went silent: no liveliness for 0.5 s";
      if (const std::int64_t last = in.last_sample_ns.load(); last > 0) {
        char since[64];
        std::snprintf(since, sizeof since, ", nothing from it for %.2f s", static_cast<double>(steady_ns() - last) * 1e-9);
        what += since;
      }
      what += " (did the process die?)";
      peer_events_.push_back({{"input", in.input}, {"writer", in.writer}, {"process", in.process}, {"event", "lost"}, {"t_s", t}});
      // Once per writer, however often it lapses.
      const bool known = std::any_of(lost_peers_.begin(), lost_peers_.end(), [&](const std::string& l) { return l.rfind(who + " went silent", 0) == 0; });
      if (!may_die && !known) lost_peers_.push_back(what);
      char at[48];
      std::snprintf(at, sizeof at, " at t = %.2f s", t);
      line = "warning: " + what + at + (may_die ? "; the graph lets process '" + in.process + "' die: the run goes on"
                                                : std::string("; the run goes on, and fails at its end"));
    } else if (alive && in.lost) {
      in.lost = false;
      const double gone = static_cast<double>(now - in.lost_at_ns) * 1e-9;
      peer_events_.push_back({{"input", in.input}, {"writer", in.writer}, {"process", in.process}, {"event", "back"}, {"t_s", t},
                              {"gone_s", gone}});
      char msg[96];
      std::snprintf(msg, sizeof msg, " is back, %.2f s after it went silent, at t = %.2f s", gone, t);
      line = who + msg;
    }
  }
  if (!line.empty()) console_.line([&] { std::fprintf(stderr, "[brickyard] %s\n", line.c_str()); });  // even with --quiet
}

void Executive::peer_ended(const std::string& process, const PeerEnd& end) {
  const double t = sim() ? sim_now_ns_ * 1e-9 : (wall_ns() - real_start_ns_) * 1e-9;
  const bool failed = end.result == RunResult::failed || end.result == RunResult::invalid_input;
  const bool may_die = process_policy(*graph_.decl, process).may_die;
  const std::string what = "process '" + process + "' " + (failed ? "failed" : "ended") + ": " + end.reason;
  {
    std::lock_guard<std::mutex> l(stop_m_);
    peer_events_.push_back({{"process", process}, {"event", "ended"}, {"result", to_string(end.result)}, {"reason", end.reason}, {"t_s", t}});
    if (failed && !may_die) failed_peers_.push_back(what);
  }
  if (!failed) {
    host_log(what);
    return;
  }
  char at[48];
  std::snprintf(at, sizeof at, " (at t = %.2f s)", t);
  const std::string line = "warning: " + what + at +
                           (may_die ? "; the graph lets it die: the run goes on" : "; the run goes on, and fails at its end");
  console_.line([&] { std::fprintf(stderr, "[brickyard] %s\n", line.c_str()); });  // even with --quiet
}

void Executive::peer_left_unsaid(const std::string& process) {
  if (process_policy(*graph_.decl, process).may_die) return;
  const std::string what = "process '" + process + "' left without saying how its run ended (a plugin's exit()? its end record lost?)";
  {
    std::lock_guard<std::mutex> l(stop_m_);
    peer_events_.push_back({{"process", process}, {"event", "left unsaid"}});
    failed_peers_.push_back(what);
  }
  console_.line([&] { std::fprintf(stderr, "[brickyard] warning: %s\n", what.c_str()); });
}

void Executive::foreign_writer(RemoteInput& in, const std::string& participant, const std::string& writer) {
  const bool accepted = graph_.decl->transport.accept_foreign_writers;
  const double t = sim() ? sim_now_ns_ * 1e-9 : (wall_ns() - real_start_ns_) * 1e-9;
  {
    std::lock_guard<std::mutex> l(stop_m_);
    foreign_writers_.push_back({{"input", in.input}, {"participant", participant}, {"writer", writer}, {"t_s", t}, {"accepted", accepted}});
  }
  const std::string line = "warning: input " + in.input + ": a writer the graph does not name sent to it (participant '" + participant +
                           "', writer " + writer + "; the graph's is " + in.writer + " of process '" + in.process + "'): " +
                           (accepted ? "its samples are used (transport.foreign_writers accept)" : "its samples are dropped");
  console_.line([&] { std::fprintf(stderr, "[brickyard] %s\n", line.c_str()); });  // even with --quiet
}

// A split run's start-up: each input whose writer runs in another process waits until that writer
// has matched (its process is up, its ports made), at most transport.startup_timeout_s, before
// the clock starts — the planner no longer gets the world seconds late. A first sample is not
// awaited: processes feed each other in a loop (the car's state out, its commands back), and
// neither could send first. A writer that never appears fails the run, named.
bool Executive::await_peers() {
  if (remote_inputs_.empty()) return true;
  const double limit = graph_.decl->transport.startup_timeout_s;
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    std::vector<const RemoteInput*> missing;
    for (const auto& r : remote_inputs_)
      if (r->reader->matched() == 0) missing.push_back(r.get());
    if (missing.empty()) return true;
    if (g_interrupt || stop_) return false;
    if (std::chrono::steady_clock::now() - t0 > std::chrono::duration<double>(limit)) {
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.3g s", limit);
      std::string why = "start-up: no writer appeared within " + std::string(secs) + " (transport.startup_timeout_s) for input " +
                        missing.front()->input + " (writer " + missing.front()->writer + ", process '" + missing.front()->process +
                        "'; did it start?)";
      if (missing.size() > 1) why += " and " + std::to_string(missing.size() - 1) + " more input(s)";
      request_stop(RunResult::failed, why);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

// A lockstep run's start-up (exec/lockstep.hpp): every wire across processes matched both ways
// (a sample written before its reader is known would be lost, and the replay would wait for it),
// then a hello to and from each peer, which carries the graph's fingerprint and whether its
// process started. A peer that could not start ends this run with its verdict.
void Executive::lockstep_start() {
  std::map<const DdsWriter*, std::set<std::string>> readers;  // each output's writer: the processes it feeds
  for (const auto& w : graph_.decl->wires) {
    const auto& from = graph_.decl->nodes.at(w.from.node), &to = graph_.decl->nodes.at(w.to.node);
    if (from.process != opt_.process || to.process == opt_.process) continue;
    for (auto& n : nodes_)
      if (n->name == w.from.node)
        if (OutputPort* o = n->output(w.from.port); o && o->writer) readers[o->writer].insert(to.process);
  }
  auto matched = [&] {
    for (const auto& r : remote_inputs_)
      if (r->reader->matched() == 0) return false;
    for (const auto& [w, ps] : readers)
      if (w->matched() < static_cast<int>(ps.size())) return false;
    return true;
  };
  LockRecord hello;
  if (stop_) {
    std::lock_guard<std::mutex> l(stop_m_);
    hello.stop = true;
    hello.result = static_cast<std::uint8_t>(stop_result_.value_or(RunResult::failed));
    hello.reason = stop_reason_;
  }
  std::string why;
  std::optional<std::pair<RunResult, std::string>> peer_stop;
  if (!lock_->start(graph_.decl->transport.startup_timeout_s, matched, hello, why, peer_stop) && !stop_) lockstep_failed(why, peer_stop);
}

void Executive::request_stop(RunResult r, std::string reason) {
  if (t_deferred) {
    t_deferred->emplace_back([this, r, reason = std::move(reason)]() mutable { request_stop(r, std::move(reason)); });
    return;
  }
  if (deactivate_log_) {  // a lockstep run's deactivation: applied with the other processes' (finish_lockstep)
    LockRecord d;
    d.node = static_cast<std::uint32_t>(deactivating_);
    d.result = static_cast<std::uint8_t>(r);
    d.reason = std::move(reason);
    deactivate_log_->push_back(std::move(d));
    return;
  }
  std::lock_guard<std::mutex> l(stop_m_);
  // A failure outranks an earlier request to finish; otherwise the first request wins.
  if (stop_result_ && !(r == RunResult::failed && *stop_result_ != RunResult::failed)) return;
  stop_result_ = r;
  stop_reason_ = std::move(reason);
  stop_ = true;
  for (auto& n : nodes_) n->cv.notify_all();
}

bool Executive::call(NodeRuntime& n, const char* phase, const std::function<void()>& f) {
  try {
    // Named if the plugin takes the process down, or its step hangs far past its deadline, or a
    // lifecycle call past kLifecycleHang_s.
    const bool step = std::string_view(phase) == "step";
    const crash_guard::Running running(n.name.c_str(), phase, step ? hang_after_s(n) : kLifecycleHang_s);
    f();
    return true;
  } catch (const BadInput& e) {
    // Bad input only while nothing runs yet; thrown later it is a failure of the run like any other.
    const bool setup = std::string_view(phase) == "configure";
    request_stop(setup ? RunResult::invalid_input : RunResult::failed,
                 "node '" + n.name + "' (" + n.plugin_name() + ")" + (setup ? ": " : std::string(" failed in ") + phase + ": ") +
                     (setup ? with_param_place(*graph_.decl, n.name, e.what()) : std::string(e.what())));
  } catch (const std::exception& e) {
    request_stop(RunResult::failed, "node '" + n.name + "' (" + n.plugin_name() + ") failed in " + phase + ": " + e.what());
  } catch (...) {
    request_stop(RunResult::failed, "node '" + n.name + "' (" + n.plugin_name() + ") failed in " + phase +
                                        ": unknown exception");
  }
  return false;
}

std::string Executive::find_file(std::string_view path) const { return find_data_file(graph_.decl->file, path); }

void Executive::step(NodeRuntime& n, Trigger t) {
  if (step_body(n, std::move(t))) ++n.steps;
}

double Executive::hang_after_s(const NodeRuntime& n) const {
  const double d = n.rn->deadline_s;
  if (d <= 0) return 0;
  return sim() && !n.rn->deadline_by_graph ? std::max(kSimHang_s, 2 * d) : std::max(2 * d, d + 1.0);
}

bool Executive::step_body(NodeRuntime& n, Trigger t) {
  n.trigger = std::move(t);
  // The wall clock only with --profile or a step deadline: the host's own measurement, never seen by a node.
  // On the sim clock only a deadline the graph set fails a run (a run's result must not depend on
  // the machine); any other only ends a step stuck for kSimHang_s there (hang_after_s).
  const double deadline = sim() && !n.rn->deadline_by_graph ? 0.0 : n.rn->deadline_s;
  const auto t0 = opt_.profile || deadline > 0 ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  const bool ok = call(n, "step", [&] { n.instance->step(*n.ctx); });
  if (opt_.profile || deadline > 0) {
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (opt_.profile) n.step_wall_s += took;
    // The node's step deadline (wall time; docs/reliability.md): a step that took longer fails the run.
    if (deadline > 0 && took > deadline) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "'s step took %.3f s, past its deadline of %.3f s%s", took, deadline,
                    n.rn->deadline_derived ? " (derived from its trigger: docs/reliability.md)" : "");
      request_stop(RunResult::failed, "node '" + n.name + "' (" + n.plugin_name() + ")" + msg);
    }
  }
  return ok;
}

RunSummary Executive::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  console_.start(opt_.quiet, opt_.progress_s, wall0);
  real_start_ns_ = wall_ns();
  open_record_and_live();
  const bool built = !stop_ && try_build();
  if (live_ && built) {
    live_->start();
    host_log("live: ws://" + opt_.live_address + ":" + std::to_string(live_->port()) + " (Foxglove: Open connection, Foxglove WebSocket)");
  }
  // A lockstep run meets its peers before anything of its nodes runs: from construction on,
  // every lifecycle call is an event of its process, so every process stops at the same node.
  if (lock_) lockstep_start();
  const std::vector<NodeRuntime*> active = bring_up(built);
  if (!stop_ && !sim() && !await_peers() && g_interrupt) request_stop(RunResult::interrupted, interrupt_reason());
  if (!stop_) {
    host_log("running");
    if (sim()) run_sim();
    else run_real();
    progress(true);
  }
  if (ends_)
    for (const std::string& p : ends_->left_unsaid(0.5)) peer_left_unsaid(p);
  if (transport_ && !lock_) transport_->close_readers();
  // The run loop's wake-up hooks refer to its own state: samples published from here on (in
  // deactivate) are queued, and step nothing. The other processes' phantoms too: a sample a
  // node publishes to another process in deactivate arrives at one.
  for (auto* group : {&nodes_, &phantoms_})
    for (auto& n : *group)
      for (auto& in : n->inputs) in->on_arrival = nullptr;
  deactivate(active);
  const nlohmann::json live = live_summary();
  const nlohmann::json recording = recording_summary();
  RunSummary s = summarize(wall0, live, recording);
  if (ends_) ends_->say({s.result, s.reason}, 0.5);  // its peers hear how it ended (exec/peer_ends.hpp)
  return s;
}

void Executive::open_record_and_live() {
  const GraphDecl& g = *graph_.decl;
  if (!opt_.record.empty()) {
    try {
      recorder_ = open_recording(opt_, g, sim());
    } catch (const std::exception& e) {
      recorder_.reset();
      request_stop(RunResult::invalid_input, std::string("--record ") + e.what());
    }
  }
  if (!stop_ && opt_.live_port) {
    LiveOptions lo;
    lo.address = opt_.live_address;
    lo.port = static_cast<std::uint16_t>(*opt_.live_port);
    lo.sim_clock = sim();
    lo.cloud_hz = opt_.live_cloud_hz;
    lo.name = "brickyard: " + g.name;
    try {
      live_ = std::make_unique<LiveServer>(lo);
    } catch (const std::exception& e) {
      request_stop(RunResult::invalid_input, e.what());
    }
  }
}

bool Executive::try_build() {
  try {
    build();
    return true;
  } catch (const std::exception& e) {
    request_stop(RunResult::failed, std::string("transport: ") + e.what());
    return false;
  }
}

std::vector<NodeRuntime*> Executive::lifecycle_phase(std::int64_t tag, const std::vector<NodeRuntime*>& over,
                                                     const std::function<bool(NodeRuntime&)>& one) {
  std::vector<NodeRuntime*> done;
  for (std::size_t i = 0; i < over.size(); ++i) {
    NodeRuntime& n = *over[i];
    if (n.phantom) {
      remote_event(i, tag);
      if (stop_) break;
      continue;
    }
    bool ok = false;
    local_event(i, tag, [&] { ok = one(n); });
    if (!ok) break;
    done.push_back(&n);
  }
  return done;
}

std::vector<NodeRuntime*> Executive::bring_up(bool built) {
  std::vector<NodeRuntime*> every;  // this process's nodes, or with lockstep every process's
  if (lock_) every = sched_;
  else
    for (auto& n : nodes_) every.push_back(n.get());
  if (built && !stop_)
    lifecycle_phase(kConstruction, every,
                    [&](NodeRuntime& n) { return call(n, "construction", [&] { n.instance = n.rn->plugin->descriptor->create(); }); });
  std::vector<NodeRuntime*> configured;
  if (!stop_) {
    host_log("graph '" + graph_.decl->name + "': " + std::to_string(nodes_.size()) + " nodes, " + (sim() ? "sim" : "real") + " clock");
    configured =
        lifecycle_phase(kConfigure, every, [&](NodeRuntime& n) { return call(n, "configure", [&] { n.instance->configure(*n.ctx); }); });
  }
  std::vector<NodeRuntime*> active;
  if (!stop_)
    active = lifecycle_phase(kActivate, lock_ ? every : configured,
                             [&](NodeRuntime& n) { return call(n, "activate", [&] { n.instance->activate(*n.ctx); }); });
  return active;
}

// Every node that was activated is deactivated, in reverse order, even after a failure: sinks
// report their verdicts there. In a lockstep run what each asks is kept, and applied with the
// other processes' in the one order of the schedule (finish_lockstep).
void Executive::deactivate(const std::vector<NodeRuntime*>& active) {
  std::vector<LockRecord> asked;
  if (lock_) deactivate_log_ = &asked;
  for (auto it = active.rbegin(); it != active.rend(); ++it) {
    deactivating_ = (*it)->rn->order;
    call(**it, "deactivate", [&] { (*it)->instance->deactivate(*(*it)->ctx); });
  }
  deactivate_log_ = nullptr;
  if (lock_) finish_lockstep(asked);
}

void Executive::finish_lockstep(const std::vector<LockRecord>& asked) {
  // The peers may be behind: this process's last records and samples reach them before it goes.
  std::vector<DdsWriter*> writers;
  for (auto& n : nodes_)
    for (auto& o : n->outputs)
      if (o->writer) writers.push_back(o->writer);
  RunResult result = RunResult::success;
  std::string reason = "sim clock reached the end", why;
  {
    std::lock_guard<std::mutex> l(stop_m_);
    if (stop_result_) result = *stop_result_, reason = stop_reason_;
  }
  std::vector<LockRecord> all = lock_->finish(result, reason, writers, asked, why, graph_.decl->transport.end_timeout_s);
  all.insert(all.end(), asked.begin(), asked.end());
  // Deactivation runs downstream first (reverse schedule order): the same requests in the same
  // order as in one process, so the same verdict.
  std::stable_sort(all.begin(), all.end(), [](const LockRecord& a, const LockRecord& b) { return a.node > b.node; });
  for (const auto& r : all) request_stop(static_cast<RunResult>(r.result), r.reason);
  if (!why.empty()) request_stop(RunResult::failed, why);
  transport_->close_readers();
}

nlohmann::json Executive::live_summary() const {
  nlohmann::json live;
  if (live_) {
    const LiveStats st = live_->stats();
    live = {{"port", live_->port()}, {"clients", st.clients}, {"sent", st.sent}, {"dropped", st.dropped},
            {"refused_requests", st.refused_requests}, {"disconnected", st.disconnected}, {"clouds_thinned", st.clouds_thinned},
            {"cloud_hz", opt_.live_cloud_hz}, {"server_cpu_s", st.server_cpu_s},
            {"taps_s", 1e-9 * static_cast<double>(live_tap_ns_.load())}};
    // The server and the scene stay until the executive goes (taps may publish until the plugins
    // are destroyed); its clients are closed then.
  }
  return live;
}

nlohmann::json Executive::recording_summary() {
  nlohmann::json recording;
  if (recorder_) {
    try {
      recording = close_recording(*recorder_);
    } catch (const std::exception& e) {
      request_stop(RunResult::failed, e.what());
    }
  }
  return recording;
}

RunSummary Executive::summarize(std::chrono::steady_clock::time_point wall0, const nlohmann::json& live, const nlohmann::json& recording) {
  RunSummary s;
  s.result = stop_result_.value_or(RunResult::success);
  s.reason = stop_result_ ? stop_reason_ : (sim() ? "sim clock reached the end" : "duration reached");
  {
    std::lock_guard<std::mutex> l(stop_m_);
    std::vector<std::string> peers = lost_peers_;
    peers.insert(peers.end(), failed_peers_.begin(), failed_peers_.end());
    if (!peers.empty() && s.result != RunResult::failed && s.result != RunResult::invalid_input) {
      s.result = RunResult::failed;
      s.reason = peers.front() + (peers.size() > 1 ? " (and " + std::to_string(peers.size() - 1) + " more)" : "");
    }
  }
  s.sim_time_s = sim() ? static_cast<double>(sim_now_ns_) / 1e9 : 0.0;
  s.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (!sim()) s.sim_time_s = s.wall_time_s;
  s.json = summary_json(s, *graph_.decl, opt_, sim(), recording, nodes_, now_ns());
  if (!live.is_null()) s.json["live"] = live;
  // Per wire from another process: how many writers fed it (a second one is a stray or forged
  // writer under the expected name, or the writer's process restarted).
  for (const auto& r : remote_inputs_)
    s.json["remote_inputs"][r->input] = {{"writer", r->writer}, {"writers_heard", r->reader->writers_heard()}};
  {
    std::lock_guard<std::mutex> l(stop_m_);
    if (!lost_peers_.empty()) s.json["lost_peers"] = lost_peers_;
    if (!failed_peers_.empty()) s.json["failed_peers"] = failed_peers_;
    if (!peer_events_.empty()) s.json["peer_events"] = peer_events_;
    if (!foreign_writers_.empty()) s.json["foreign_writers"] = foreign_writers_;
  }
  return s;
}

}  // namespace brickyard::fw
