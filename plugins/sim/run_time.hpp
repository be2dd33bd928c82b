#pragma once
// Plugin-side: times of the run in seconds from its start, the time base of the simulator's
// scripts (fault windows, race control's flags, a constant command's start, a scorer's windows).
// On the sim clock the run starts at zero and this is the clock itself, bit for bit. On the real
// clock `now` is the wall's time since the epoch, so a script's "start_s": 75 would lie in 1970:
// there the run's start is the node's first look at the clock (a node's first step comes within
// its period of the run's start; a split simulator's processes each start their own).
#include <brickyard/context.hpp>

#include <cstdint>

namespace brickyard::sim {

class RunTime {
 public:
  // The run's start on the node's clock (the first call fixes it on the real clock).
  std::int64_t start_ns(const Context& ctx) {
    if (start_ns_ < 0) start_ns_ = ctx.sim_clock() ? 0 : ctx.now_ns();
    return start_ns_;
  }
  // A stamp (or now) in seconds from the run's start.
  double of(const Context& ctx, std::int64_t stamp_ns) { return static_cast<double>(stamp_ns - start_ns(ctx)) * 1e-9; }
  double now_s(const Context& ctx) { return of(ctx, ctx.now_ns()); }
  std::int64_t now_ns(const Context& ctx) { return ctx.now_ns() - start_ns(ctx); }

 private:
  std::int64_t start_ns_ = -1;
};

}  // namespace brickyard::sim
