#pragma once
// What the referee node says and reports (plugin.cpp): the judge's notices through the run's
// context, in their order, and the referee's figures as the node's metrics (names fixed by
// contract: later issues and their checks read them from summary.json).
#include <brickyard/plugin.hpp>

#include "sim/common/race_judge.hpp"

#include <vector>

namespace brickyard::sim {

// What the judge says, through the run's context and in its order.
inline void say(Context& ctx, const std::vector<RefereeNotice>& notices) {
  using K = RefereeNotice::Kind;
  for (const RefereeNotice& n : notices) {
    switch (n.kind) {
      case K::status: ctx.status(n.field, n.text); break;
      case K::info: ctx.log(LogLevel::info, n.text); break;
      case K::warn: ctx.log(LogLevel::warn, n.text); break;
      case K::finish: ctx.finish(n.text); break;
      case K::fail: ctx.fail(n.text); break;
    }
  }
}

// The other cars' figures only when there are other cars (`with_others`).
inline void report_metrics(Context& ctx, const RaceJudge& judge, bool with_others) {
  const Referee& r = judge.referee();
  ctx.metric("laps_completed", static_cast<double>(r.laps_completed()));
  ctx.metric("lap_times_s", r.lap_times());
  ctx.metric("max_speed_mps", r.max_speed());
  ctx.metric("wall_contacts", static_cast<double>(r.wall_contacts()));
  ctx.metric("track_violations", static_cast<double>(r.track_violations()));
  ctx.metric("min_wall_clearance_m", r.min_wall_clearance());
  ctx.metric("min_wall_clearance_s_m", r.min_wall_clearance_s());
  ctx.metric("obstacles_hit", static_cast<double>(r.obstacles_hit()));
  ctx.metric("obstacle_min_clearance_m", r.obstacle_min_clearance());
  ctx.metric("localization_rmse_m", r.localization_rmse());
  ctx.metric("localization_max_error_m", r.localization_max_error());
  ctx.metric("localization_samples", static_cast<double>(r.localization_samples()));
  if (!with_others) return;
  ctx.metric("car_contacts", static_cast<double>(judge.car_contacts().contacts()));
  ctx.metric("min_car_gap_m", judge.car_contacts().min_gap());
  ctx.metric("passes", static_cast<double>(judge.order().passes()));
  ctx.metric("passed_by", static_cast<double>(judge.order().passed_by()));
  ctx.metric("position", static_cast<double>(judge.order().position()));
}

}  // namespace brickyard::sim
