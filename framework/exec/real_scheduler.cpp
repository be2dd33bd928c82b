// Executive::run_real: the real clock. A thread per node: periodic nodes sleep until their next
// period (an overrun skips the missed periods instead of bursting), input-triggered nodes wake on
// arrival. The calling thread watches the duration, interrupts and the progress line.
#include "exec/executive.hpp"
#include "exec/node_runtime.hpp"

#include <chrono>
#include <thread>

namespace brickyard::fw {

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

}  // namespace brickyard::fw
