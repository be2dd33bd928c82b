#include "exec/executive.hpp"
#include "loader/registry.hpp"
#include <brickyard/version.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <queue>
#include <thread>

#include <unistd.h>

namespace brickyard::fw {

std::atomic<bool> g_interrupt{false};

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
std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}
}  // namespace

class NodeContext;

class NodeRuntime {
 public:
  const ResolvedNode* rn;
  std::string name;
  Plugin* instance = nullptr;
  std::vector<std::unique_ptr<InputQueue>> inputs;
  std::vector<std::unique_ptr<OutputPort>> outputs;
  std::unique_ptr<NodeContext> ctx;
  Trigger trigger;
  nlohmann::json metrics = nlohmann::json::object();
  std::uint64_t steps = 0;
  std::uint64_t seed = 0;
  // sim: queued for an input-triggered step at this instant
  bool queued = false;
  std::string queued_port;
  // real: wake-up for input triggers
  std::mutex m;
  std::condition_variable cv;
  bool input_pending = false;
  std::string pending_port;

  const std::string& plugin_name() const { return rn->plugin->manifest.name; }
  InputQueue* input(std::string_view port) {
    for (auto& i : inputs)
      if (i->name() == port) return i.get();
    return nullptr;
  }
  OutputPort* output(std::string_view port) {
    for (auto& o : outputs)
      if (o->name() == port) return o.get();
    return nullptr;
  }
};

class NodeContext final : public Context {
 public:
  NodeContext(Executive& e, NodeRuntime& n) : e_(e), n_(n) {}
  std::int64_t now_ns() const override { return e_.now_ns(); }
  bool sim_clock() const override { return e_.sim(); }
  const std::string& node_name() const override { return n_.name; }
  const Params& params() const override { return n_.rn->params; }
  std::uint64_t seed() const override { return n_.seed; }
  const Trigger& trigger() const override { return n_.trigger; }
  void log(LogLevel level, std::string_view message) override { e_.log(n_, level, message); }
  void metric(std::string_view name, double value) override {
    n_.metrics[std::string(name)] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  }
  void metric(std::string_view name, std::vector<double> values) override {
    n_.metrics[std::string(name)] = values;
  }
  void metric(std::string_view name, std::string value) override { n_.metrics[std::string(name)] = value; }
  void finish(std::string_view reason) override {
    e_.request_stop(RunResult::success, "node '" + n_.name + "' finished the run: " + std::string(reason));
  }
  std::string find_file(std::string_view path) const override { return e_.find_file(path); }
  void status(std::string_view field, std::string_view value) override { e_.set_status(n_.name, field, value); }
  void fail(std::string_view reason) override {
    e_.request_stop(RunResult::failed, "node '" + n_.name + "' (" + n_.plugin_name() + "): " + std::string(reason));
  }

 protected:
  detail::InputChannel* input_channel(std::string_view port) override {
    if (auto* i = n_.input(port)) return i;
    throw std::invalid_argument("plugin " + n_.plugin_name() + " has no input port '" + std::string(port) + "'");
  }
  detail::OutputChannel* output_channel(std::string_view port) override {
    if (auto* o = n_.output(port)) return o;
    throw std::invalid_argument("plugin " + n_.plugin_name() + " has no output port '" + std::string(port) + "'");
  }

 private:
  Executive& e_;
  NodeRuntime& n_;
};

Executive::Executive(const ResolvedGraph& g, RunOptions opt) : graph_(g), opt_(std::move(opt)) {}

Executive::~Executive() {
  // Teardown order matters: deliveries stop, plugin objects go, then DDS entities.
  if (transport_) transport_->close_readers();
  for (auto& n : nodes_)
    if (n->instance) n->rn->plugin->descriptor->destroy(n->instance);
  nodes_.clear();
  transport_.reset();
}

std::int64_t Executive::now_ns() const { return sim() ? sim_now_ns_ : wall_ns(); }

void Executive::host_log(const std::string& msg) {
  if (opt_.quiet) return;
  std::lock_guard<std::mutex> l(log_m_);
  if (line_open_) { std::fputs("\r\033[K", stderr); line_open_ = false; }
  std::fprintf(stderr, "[brickyard] %s\n", msg.c_str());
}

void Executive::set_status(const std::string& node, std::string_view field, std::string_view value) {
  std::lock_guard<std::mutex> l(status_m_);
  for (auto& [name, fields] : status_) {
    if (name != node) continue;
    for (auto& [f, v] : fields)
      if (f == field) { v = value; return; }
    fields.emplace_back(std::string(field), std::string(value));
    return;
  }
}

void Executive::progress(bool last) {
  if (progress_every_s_ <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (!last && now - last_progress_ < std::chrono::duration<double>(progress_every_s_)) return;
  if (last && !tty_) return;  // the summary follows
  last_progress_ = now;
  const double wall = std::chrono::duration<double>(now - wall0_).count();
  char head[96];
  if (sim()) std::snprintf(head, sizeof head, "sim %.1f s (%.1fx real time)", sim_now_ns_ * 1e-9, wall > 0 ? sim_now_ns_ * 1e-9 / wall : 0.0);
  else std::snprintf(head, sizeof head, "t %.1f s", wall);
  std::string line = head;
  {
    std::lock_guard<std::mutex> l(status_m_);
    for (const auto& [node, fields] : status_)
      for (const auto& [f, v] : fields) line += " · " + f + " " + v;
  }
  std::lock_guard<std::mutex> l(log_m_);
  if (tty_) {
    std::fprintf(stderr, "\r\033[K%s%s", line.c_str(), last ? "\n" : "");
    line_open_ = !last;
  } else {
    std::fprintf(stderr, "[brickyard] progress: %s\n", line.c_str());
  }
}

void Executive::log(const NodeRuntime& n, LogLevel level, std::string_view msg) {
  if (opt_.quiet && level < LogLevel::warn) return;
  static const char* names[] = {"debug", "info", "warn", "error"};
  double t = sim() ? sim_now_ns_ * 1e-9 : (wall_ns() - real_start_ns_) * 1e-9;
  std::lock_guard<std::mutex> l(log_m_);
  if (line_open_) { std::fputs("\r\033[K", stderr); line_open_ = false; }
  std::fprintf(stderr, "[%9.3f] %s %s: %.*s\n", t, names[static_cast<int>(level)], n.name.c_str(),
               static_cast<int>(msg.size()), msg.data());
}

void Executive::request_stop(RunResult r, std::string reason) {
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
    f();
    return true;
  } catch (const BadInput& e) {
    // Bad input only while nothing runs yet; thrown later it is a failure of the run like any other.
    const bool setup = std::string_view(phase) == "configure";
    request_stop(setup ? RunResult::invalid_input : RunResult::failed,
                 "node '" + n.name + "' (" + n.plugin_name() + ")" + (setup ? ": " : std::string(" failed in ") + phase + ": ") + e.what());
  } catch (const std::exception& e) {
    request_stop(RunResult::failed, "node '" + n.name + "' (" + n.plugin_name() + ") failed in " + phase + ": " + e.what());
  } catch (...) {
    request_stop(RunResult::failed, "node '" + n.name + "' (" + n.plugin_name() + ") failed in " + phase +
                                        ": unknown exception");
  }
  return false;
}

std::vector<std::string> data_dirs() {
  std::vector<std::string> dirs = env_path_list("BRICKYARD_DATA_PATH");
  const std::string prefix = install_prefix();
  if (!prefix.empty()) dirs.push_back((std::filesystem::path(prefix) / "share" / "brickyard" / "data").string());
  return dirs;
}

std::string Executive::find_file(std::string_view path) const {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::error_code ec;
  if (p.is_absolute()) {
    if (fs::is_regular_file(p, ec)) return p.string();
    throw BadInput("file not found: " + p.string());
  }
  std::vector<fs::path> tried;
  const std::string& graph_file = graph_.decl->file;
  if (!graph_file.empty()) tried.push_back(fs::path(graph_file).parent_path() / p);
  tried.push_back(fs::current_path(ec) / p);
  for (const auto& d : data_dirs()) tried.push_back(fs::path(d) / p);
  std::string where;
  for (const auto& t : tried) {
    if (fs::is_regular_file(t, ec)) return t.lexically_normal().string();
    where += "\n  " + t.lexically_normal().string();
  }
  throw BadInput("file '" + std::string(path) + "' not found; looked in:" + where);
}

void Executive::build() {
  const GraphDecl& g = *graph_.decl;
  DdsSettings ds;
  ds.domain = opt_.domain.value_or(g.transport.domain);
  ds.interfaces = g.transport.interfaces;
  ds.peers = g.transport.peers;
  transport_ = std::make_unique<DdsTransport>(ds);

  std::map<std::string, NodeRuntime*> here;
  for (const auto& rn : graph_.nodes) {
    auto n = std::make_unique<NodeRuntime>();
    n->rn = &rn;
    n->name = rn.decl->name;
    n->seed = splitmix64(opt_.seed ^ fnv1a(n->name));
    std::set<std::string> wired;
    for (const auto& w : g.wires)
      if (w.to.node == n->name) wired.insert(w.to.port);
    for (const auto& p : rn.plugin->manifest.ports) {
      if (p.direction == PortDirection::input)
        n->inputs.push_back(std::make_unique<InputQueue>(p.name, p.type_name, p.depth, wired.count(p.name) > 0));
      else {
        n->outputs.push_back(std::make_unique<OutputPort>(p.name, p.type_name));
        n->outputs.back()->writer = transport_->make_writer(topic_name(n->name, p.name), p.type_name);
        const std::string topic = n->name + "." + p.name;
        const bool skip = std::find(opt_.record_skip_types.begin(), opt_.record_skip_types.end(), p.type_name) != opt_.record_skip_types.end();
        if (recorder_ && !skip && (opt_.record_only.empty() || topic_selected(topic, opt_.record_only))) {
          const int id = recorder_->add_topic(topic, p.type_name);
          // A failed write stops the run; it must not unwind through the publishing plugin.
          n->outputs.back()->tap = [this, id](const void* m) {
            try {
              recorder_->write(id, now_ns(), m);
            } catch (const std::exception& e) {
              request_stop(RunResult::failed, e.what());
            }
          };
        }
      }
    }
    n->ctx = std::make_unique<NodeContext>(*this, *n);
    status_.push_back({n->name, {}});
    here[n->name] = n.get();
    nodes_.push_back(std::move(n));
  }
  for (const auto& w : g.wires) {
    auto to = here.find(w.to.node);
    if (to == here.end()) continue;  // its reader lives in another process
    InputQueue* in = to->second->input(w.to.port);
    auto from = here.find(w.from.node);
    if (from != here.end()) {
      from->second->output(w.from.port)->local.push_back(in);
    } else {
      const PortSpec* ps = to->second->rn->plugin->manifest.port(w.to.port);
      transport_->make_reader(topic_name(w.from.node, w.from.port), ps->type_name, ps->depth,
                              [in](std::shared_ptr<const void> s) { in->push(std::move(s)); });
    }
  }
}

void Executive::step(NodeRuntime& n, Trigger t) {
  n.trigger = std::move(t);
  if (call(n, "step", [&] { n.instance->step(*n.ctx); })) ++n.steps;
}

void Executive::run_sim() {
  const auto& clock = graph_.decl->clock;
  auto dur = opt_.duration_s ? opt_.duration_s : clock.duration_s;
  const std::int64_t end_ns = dur ? static_cast<std::int64_t>(std::llround(*dur * 1e9)) : INT64_MAX;

  using Due = std::pair<std::int64_t, std::size_t>;  // (time, schedule order): earliest, then upstream first
  std::priority_queue<Due, std::vector<Due>, std::greater<Due>> timers;
  std::deque<std::size_t> ready;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    NodeRuntime& n = *nodes_[i];
    if (n.rn->period_ns > 0) timers.push({0, i});
    for (auto& in : n.inputs) {
      if (!n.rn->trigger_inputs.count(in->name())) continue;
      in->on_arrival = [&n, &ready, i](const std::string& port) {
        if (n.queued) return;
        n.queued = true;
        n.queued_port = port;
        ready.push_back(i);
      };
    }
  }
  std::uint64_t events = 0;
  auto drain = [&] {
    while (!ready.empty() && !stop_) {
      NodeRuntime& n = *nodes_[ready.front()];
      ready.pop_front();
      n.queued = false;
      step(n, Trigger{Trigger::Kind::input, n.queued_port});
    }
  };
  while (!stop_) {
    if (g_interrupt) {
      request_stop(RunResult::interrupted, "interrupted");
      break;
    }
    if (timers.empty()) {
      host_log("no periodic node left to step: the run ends");
      break;
    }
    auto [t, i] = timers.top();
    if (t > end_ns) {
      sim_now_ns_ = end_ns;
      break;
    }
    timers.pop();
    sim_now_ns_ = t;
    step(*nodes_[i], Trigger{Trigger::Kind::periodic, {}});
    drain();
    timers.push({t + nodes_[i]->rn->period_ns, i});
    if ((++events & 255) == 0) progress();
  }
}

void Executive::run_real() {
  const auto& clock = graph_.decl->clock;
  auto dur = opt_.duration_s ? opt_.duration_s : clock.duration_s;
  std::vector<std::thread> threads;
  for (auto& np : nodes_) {
    NodeRuntime& n = *np;
    for (auto& in : n.inputs) {
      if (!n.rn->trigger_inputs.count(in->name())) continue;
      in->on_arrival = [&n](const std::string& port) {
        {
          std::lock_guard<std::mutex> l(n.m);
          if (!n.input_pending) n.pending_port = port;
          n.input_pending = true;
        }
        n.cv.notify_one();
      };
    }
  }
  auto start = std::chrono::steady_clock::now();
  for (auto& np : nodes_) {
    NodeRuntime* n = np.get();
    if (n->rn->period_ns == 0 && n->rn->trigger_inputs.empty()) continue;
    threads.emplace_back([this, n, start] {
      auto period = std::chrono::nanoseconds(n->rn->period_ns);
      auto next = start;
      for (;;) {
        Trigger t;
        {
          std::unique_lock<std::mutex> l(n->m);
          auto ready = [&] { return stop_.load() || n->input_pending; };
          if (period.count() > 0) n->cv.wait_until(l, next, ready);
          else n->cv.wait(l, ready);
          if (stop_) return;
          if (n->input_pending) {
            n->input_pending = false;
            t = Trigger{Trigger::Kind::input, n->pending_port};
          } else {
            t = Trigger{Trigger::Kind::periodic, {}};
            next += period;
            // A step that overran its period does not cause a burst of catch-up steps.
            auto now = std::chrono::steady_clock::now();
            if (next < now) next = now;
          }
        }
        step(*n, t);
      }
    });
  }
  auto deadline = dur ? start + std::chrono::nanoseconds(static_cast<std::int64_t>(*dur * 1e9))
                      : std::chrono::steady_clock::time_point::max();
  while (!stop_) {
    if (g_interrupt) {
      request_stop(RunResult::interrupted, "interrupted");
      break;
    }
    if (std::chrono::steady_clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    progress();
  }
  stop_ = true;
  for (auto& n : nodes_) {
    { std::lock_guard<std::mutex> l(n->m); }
    n->cv.notify_all();
  }
  for (auto& t : threads) t.join();
}

RunSummary Executive::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  wall0_ = last_progress_ = wall0;
  tty_ = !opt_.quiet && isatty(2);
  progress_every_s_ = opt_.quiet ? 0.0 : opt_.progress_s >= 0 ? opt_.progress_s : tty_ ? 0.25 : 5.0;
  real_start_ns_ = wall_ns();
  const GraphDecl& g = *graph_.decl;
  bool built = false;
  if (!opt_.record.empty()) {
    try {
      recorder_ = std::make_unique<Recorder>(opt_.record);
      recorder_->set_metadata("graph", g.name);
      recorder_->set_metadata("graph_file", g.file);
      recorder_->set_metadata("clock", sim() ? "sim" : "real");
      recorder_->set_metadata("seed", std::to_string(opt_.seed));
      recorder_->set_metadata("process", opt_.process.empty() ? "all" : opt_.process);
      recorder_->set_metadata("brickyard_version", BRICKYARD_SDK_VERSION);
      recorder_->set_metadata("schema", "brickyard recording 1 (docs/recording.md)");
    } catch (const std::exception& e) {
      recorder_.reset();
      request_stop(RunResult::invalid_input, std::string("--record ") + e.what());
    }
  }
  if (!stop_) {
    try {
      build();
      built = true;
    } catch (const std::exception& e) {
      request_stop(RunResult::failed, std::string("transport: ") + e.what());
    }
  }
  if (built) {
    for (auto& n : nodes_)
      if (!call(*n, "construction", [&] { n->instance = n->rn->plugin->descriptor->create(); })) break;
  }
  std::vector<NodeRuntime*> configured;
  if (!stop_) {
    host_log("graph '" + g.name + "': " + std::to_string(nodes_.size()) + " nodes, " + (sim() ? "sim" : "real") + " clock");
    for (auto& n : nodes_) {
      if (!call(*n, "configure", [&] { n->instance->configure(*n->ctx); })) break;
      configured.push_back(n.get());
    }
  }
  std::vector<NodeRuntime*> active;
  if (!stop_) {
    for (auto* n : configured) {
      if (!call(*n, "activate", [&] { n->instance->activate(*n->ctx); })) break;
      active.push_back(n);
    }
  }
  if (!stop_) {
    host_log("running");
    if (sim()) run_sim();
    else run_real();
    progress(true);
  }
  if (transport_) transport_->close_readers();
  // The run loop's wake-up hooks refer to its own state: samples published from here on (in
  // deactivate) are queued, and step nothing.
  for (auto& n : nodes_)
    for (auto& in : n->inputs) in->on_arrival = nullptr;
  // Every node that was activated is deactivated, in reverse order, even after a failure:
  // sinks report their verdicts there.
  for (auto it = active.rbegin(); it != active.rend(); ++it)
    call(**it, "deactivate", [&] { (*it)->instance->deactivate(*(*it)->ctx); });

  nlohmann::json recording;
  if (recorder_) {
    try {
      recorder_->close();
      std::error_code ec;
      const auto abs = std::filesystem::absolute(recorder_->path(), ec);
      recording = {{"file", ec ? recorder_->path() : abs.lexically_normal().string()},
                   {"messages", recorder_->messages()}, {"bytes", recorder_->bytes()}};
    } catch (const std::exception& e) {
      request_stop(RunResult::failed, e.what());
    }
  }
  RunSummary s;
  s.result = stop_result_.value_or(RunResult::success);
  s.reason = stop_result_ ? stop_reason_ : (sim() ? "sim clock reached the end" : "duration reached");
  s.sim_time_s = sim() ? static_cast<double>(sim_now_ns_) / 1e9 : 0.0;
  s.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (!sim()) s.sim_time_s = s.wall_time_s;
  auto& j = s.json;
  j["graph"] = g.name;
  j["graph_file"] = g.file;
  j["result"] = to_string(s.result);
  j["reason"] = s.reason;
  j["clock"] = sim() ? "sim" : "real";
  j["seed"] = opt_.seed;
  j["process"] = opt_.process.empty() ? "all" : opt_.process;
  j["sim_time_s"] = s.sim_time_s;
  j["wall_time_s"] = s.wall_time_s;
  if (!recording.is_null()) j["recording"] = recording;
  j["nodes"] = nlohmann::json::object();
  for (auto& n : nodes_) {
    nlohmann::json nj;
    nj["plugin"] = n->plugin_name();
    nj["steps"] = n->steps;
    nj["metrics"] = n->metrics;
    for (auto& in : n->inputs) {
      nj["inputs"][in->name()] = {{"received", in->received()}, {"dropped", in->dropped()}};
    }
    for (auto& o : n->outputs) nj["outputs"][o->name()] = {{"published", o->published()}};
    j["nodes"][n->name] = nj;
  }
  return s;
}

}  // namespace brickyard::fw
