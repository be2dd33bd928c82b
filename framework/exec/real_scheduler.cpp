// Executive::run_real: the real clock. A thread per node: periodic nodes sleep until their next
// period (an overrun skips the missed periods instead of bursting), input-triggered nodes wake on
// arrival, and a node waiting on its device (Context::wake_on_readable: a driver) wakes as soon
// as the device has something to read. The calling thread watches the duration, interrupts and
// the progress line.
#include "exec/crash_guard.hpp"
#include "exec/executive.hpp"
#include "exec/node_runtime.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <thread>

namespace brickyard::fw {

namespace {

using Clock = std::chrono::steady_clock;

// When a node steps next on its period. Called once the period is due: a step that overran its
// period does not cause a burst of catch-up steps.
Trigger periodic_step(Clock::time_point& next, std::chrono::nanoseconds period) {
  next += period;
  const auto now = Clock::now();
  if (next < now) next = now;
  return Trigger{Trigger::Kind::periodic, {}};
}

// Whether `device` has something to read (or failed), waiting until `until` at most (none: no
// period), or until the node's wake-up eventfd is written (an input, the stop). The descriptor
// closed under the node (POLLNVAL) is forgotten: it would wake it without end.
bool device_readable(NodeRuntime& n, int device, std::optional<Clock::time_point> until) {
  pollfd fds[2] = {{device, POLLIN, 0}, {n.wake_event_fd, POLLIN, 0}};
  timespec wait{}, *timeout = nullptr;
  if (until) {
    const auto left = std::max<std::int64_t>(0, std::chrono::duration_cast<std::chrono::nanoseconds>(*until - Clock::now()).count());
    wait.tv_sec = left / 1000000000, wait.tv_nsec = left % 1000000000;
    timeout = &wait;
  }
  if (::ppoll(fds, 2, timeout, nullptr) <= 0) return false;  // the period is due, or a signal
  if (fds[1].revents & POLLIN) {
    std::uint64_t count;
    [[maybe_unused]] const ssize_t r = ::read(n.wake_event_fd, &count, sizeof count);
  }
  if (fds[0].revents & POLLNVAL) {
    std::lock_guard<std::mutex> l(n.m);
    if (n.device_fd == device) n.device_fd = -1;
    return false;
  }
  return fds[0].revents != 0;
}

}  // namespace

// The node's next trigger, waiting for it; none once the run stops.
std::optional<Trigger> Executive::next_real_trigger(NodeRuntime& n, Clock::time_point& next) {
  const std::chrono::nanoseconds period(n.rn->period_ns);
  for (;;) {
    int device = -1;
    {
      std::unique_lock<std::mutex> l(n.m);
      auto ready = [&] { return stop_.load() || n.input_pending; };
      if (n.device_fd < 0) {
        if (period.count() > 0) n.cv.wait_until(l, next, ready);
        else n.cv.wait(l, ready);
      }
      if (stop_) return std::nullopt;
      if (n.input_pending) {
        n.input_pending = false;
        return Trigger{Trigger::Kind::input, n.pending_port};
      }
      if (n.device_fd < 0) return periodic_step(next, period);
      device = n.device_fd;
    }
    if (period.count() > 0 && Clock::now() >= next) return periodic_step(next, period);
    if (device_readable(n, device, period.count() > 0 ? std::optional(next) : std::nullopt))
      return Trigger{Trigger::Kind::readable, {}};
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
          n.wake_device_wait();
        }
        n.cv.notify_one();
      };
    }
  }
  auto start = Clock::now();
  for (auto& np : nodes_) {
    NodeRuntime* n = np.get();
    // A node with neither a period nor an input trigger steps only when its device wakes it.
    if (n->rn->period_ns == 0 && n->rn->trigger_inputs.empty() && n->device_fd < 0) continue;
    threads.emplace_back([this, n, start] {
      auto next = start;
      while (const std::optional<Trigger> t = next_real_trigger(*n, next)) step(*n, *t);
    });
  }
  auto deadline = dur ? start + std::chrono::nanoseconds(static_cast<std::int64_t>(*dur * 1e9)) : Clock::time_point::max();
  while (!stop_) {
    if (g_interrupt) {
      request_stop(RunResult::interrupted, interrupt_reason());
      break;
    }
    if (Clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    progress();
  }
  const crash_guard::Ending ending;  // a node stuck in its step cannot hold the ended run for ever
  stop_ = true;
  for (auto& n : nodes_) {
    {
      std::lock_guard<std::mutex> l(n->m);
      n->wake_device_wait();
    }
    n->cv.notify_all();
  }
  for (auto& t : threads) t.join();
}

}  // namespace brickyard::fw
