#pragma once
// A node of this process during a run: its plugin instance, ports, context and counters, and the
// wake-up state each scheduler keeps for it.
#include "exec/channels.hpp"
#include "exec/node_context.hpp"
#include "graph/resolve.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::fw {

class NodeRuntime {
 public:
  const ResolvedNode* rn;
  std::string name;
  bool phantom = false;  // another process's node in a lockstep run: ports only (exec/lockstep.hpp)
  Plugin* instance = nullptr;
  std::vector<std::unique_ptr<InputQueue>> inputs;
  std::vector<std::unique_ptr<OutputPort>> outputs;
  std::unique_ptr<NodeContext> ctx;
  Trigger trigger;
  nlohmann::json metrics = nlohmann::json::object();
  std::uint64_t steps = 0;
  double step_wall_s = 0;  // with --profile: wall time spent in step
  std::uint64_t seed = 0;
  // sim: queued for an input-triggered step at this instant
  bool queued = false;
  std::string queued_port;
  // sim: stepped ahead of its turn (sim_scheduler.cpp): 0 not, 1 handed out, 2 stepping,
  // 3 stepped; its trigger, whether the step returned, and what it did, kept for its turn
  std::atomic<int> ahead{0};
  Trigger ahead_trigger;
  std::int64_t ahead_now_ns = 0;  // the instant of the step handed out
  bool undelivered = false;       // a latency step's outputs wait for their delivery (sim_scheduler.cpp)
  bool ahead_ok = false;
  Deferred deferred;
  // real: wake-up for input triggers
  std::mutex m;
  std::condition_variable cv;
  bool input_pending = false;
  std::string pending_port;
  // real: the device the node waits on (Context::wake_on_readable; -1 none), and the eventfd
  // that wakes its wait for an input or the stop (made with the first device; closed with it).
  int device_fd = -1;
  int wake_event_fd = -1;

  NodeRuntime() = default;
  NodeRuntime(const NodeRuntime&) = delete;
  NodeRuntime& operator=(const NodeRuntime&) = delete;
  ~NodeRuntime();
  // Wakes the thread of a node waiting on its device (an input arrived, the run stops). Under m.
  void wake_device_wait() const;

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

}  // namespace brickyard::fw
