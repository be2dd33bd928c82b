#pragma once
// A step run ahead of its turn on the sim clock (sim_scheduler.cpp) must not act on the run
// before its turn comes: what it publishes, logs, shows or requests is kept, in order, and done
// at its turn on the scheduler's thread, as if it had stepped then.
#include <cstdint>
#include <functional>
#include <vector>

namespace brickyard::fw {

using Deferred = std::vector<std::function<void()>>;

// Set on the thread running a step ahead of its turn; null everywhere else.
extern thread_local Deferred* t_deferred;
// A lockstep run (exec/lockstep.hpp): set on the scheduler's thread while an event of this
// process is done; each output published on appends its index, in order.
extern thread_local std::vector<std::uint16_t>* t_publog;
// The sim time of that step (its instant: the scheduler may have moved on); -1 everywhere else.
extern thread_local std::int64_t t_step_now_ns;

}  // namespace brickyard::fw
