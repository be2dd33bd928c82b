#pragma once
// sim.drive_by_wire's metrics at the end of a run: the frames, each command's counters, its own
// stops and how the last one went (from the car's truth), the last acknowledgements read.
#include <brickyard/context.hpp>

#include "sim/common/drive_by_wire.hpp"
#include "sim/common/stop_meter.hpp"

#include <string>

namespace brickyard::sim {

inline void report_metrics(Context& ctx, const SimDriveByWire& dbw, const StopMeter& stop) {
  namespace vi = brickyard::vehicle_interface;
  const SimDbwCounts& c = dbw.counts();
  ctx.metric("frames_in", c.frames_in), ctx.metric("lost_in", c.lost_in), ctx.metric("lost_out", c.lost_out);
  ctx.metric("other_frames", c.other_frames), ctx.metric("bad_frames", c.bad_frames);
  for (std::size_t i = 0; i < vi::kRaptorCommands.size(); ++i) {
    const std::string n = vi::raptor_name(vi::kRaptorCommands[i]);
    ctx.metric(n + "_received", c.received[i]), ctx.metric(n + "_counter_skips", c.skips[i]), ctx.metric(n + "_counter_repeats", c.repeats[i]);
  }
  ctx.metric("timeouts", c.timeouts), ctx.metric("heartbeat_losses", c.heartbeat_losses);
  if (stop.stood() || stop.measuring())
    ctx.metric("stop_from_speed_mps", stop.from_speed_mps()), ctx.metric("stop_distance_m", stop.distance_m());
  ctx.metric("stop_stood", stop.stood() ? 1.0 : 0.0);
  ctx.metric("track_cond_ack", dbw.setpoint().track_ack), ctx.metric("veh_sig_ack", dbw.setpoint().vehicle_ack);  // the last ct_report's
}

}  // namespace brickyard::sim
