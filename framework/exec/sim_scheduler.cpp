// Executive::run_sim: the sim clock. One thread, discrete events: at each instant the due
// periodic nodes step in schedule order (upstream first), and a published sample steps its
// input-triggered subscribers at the same instant, in publish order, before the next timer.
// Nothing here reads the wall clock, so a graph and a seed make the same run, bit for bit.
#include "exec/executive.hpp"
#include "exec/node_runtime.hpp"

#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <queue>

namespace brickyard::fw {

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

}  // namespace brickyard::fw
