// sim.referee: judges the run from ground truth. Its metrics (names fixed by contract) are what
// later issues and their checks read from summary.json under the node named `referee`.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/plugin.hpp>

#include <cmath>
#include <cstdio>
#include <optional>

#include "vehicle_param.hpp"
#include "../common/referee.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  bool crash_ends_run = true;
  // A race requires a clearance to every pylon: a pass nearer than this, or a hit, fails the run.
  double obstacle_clearance_required = 0.5;
  std::int64_t laps = 0;
  double stopped_timeout_s = 10;
  // The car's rectangle: the vehicle file's unless the graph overrides it (NaN: off).
  std::optional<double> car_front, car_rear, car_half_width;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: its rectangle around base_link");
  b.bind("crash_ends_run", &Settings::crash_ends_run).doc("a wall contact fails the run (exit 1)");
  b.bind("obstacle_clearance_required", &Settings::obstacle_clearance_required).in_unit("m").range(-100, 100)
      .doc("passing an obstacle nearer than this (its surface to the car's) fails the run (exit 1); negative: off (hits are counted only)");
  b.bind("laps", &Settings::laps).range(0, 1000)
      .doc("a race of this many laps: finished when they are done, failed (did not finish) when the run ends before; 0: no race");
  b.bind("stopped_timeout_s", &Settings::stopped_timeout_s).in_unit("s").range(0, 3600)
      .doc("in a race, a car standing this long short of its laps fails the run at once (did not finish); 0: only at the end");
  b.bind("car_front", &Settings::car_front).in_unit("m").range(0, 20)
      .doc("car ahead of base_link (the rear axle); default: the vehicle file's");
  b.bind("car_rear", &Settings::car_rear).in_unit("m").range(0, 20).doc("car behind base_link; default: the vehicle file's");
  b.bind("car_half_width", &Settings::car_half_width).in_unit("m").range(0, 10)
      .doc("half the car's width; default: the vehicle file's");
  return b;
}

struct Ports {
  Input<msgs::TrackWorld> world;
  Input<msgs::VehicleState> truth;
  Input<msgs::LocalizationEstimate> estimate;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world").depth(1);
  b.input("truth", &Ports::truth).doc("ground truth").depth(1024).steps();
  b.input("estimate", &Ports::estimate).doc("a localization estimate to score (optional)").optional().depth(1024);
  return b;
}

class RefereeNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.referee", "1.0.0")
        .describe("Laps, lap times, speed, wall contacts, track limits, clearances and localization error")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    crash_ends_ = s.crash_ends_run;
    laps_ = s.laps;
    stopped_timeout_ = s.stopped_timeout_s;
    clearance_required_ = s.obstacle_clearance_required;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    fp_.front = s.car_front.value_or(car.front);
    fp_.rear = s.car_rear.value_or(car.rear);
    fp_.half_width = s.car_half_width.value_or(car.half_width);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!ref_) {
      auto w = newest(io_.world);
      if (!w) return;
      track_ = std::make_unique<Track>(from_message(*w));
      ref_ = std::make_unique<Referee>(*track_, fp_);
    }
    for (const auto& s : io_.truth.take()) {
      TruthSample t{static_cast<double>(stamp(*s)) * 1e-9, s->x(), s->y(), s->yaw(), std::hypot(s->vx(), s->vy())};
      auto ev = ref_->update(t);
      char buf[160];
      if (++samples_ % 100 == 0 || ev.lap_completed) {  // the progress line: a few times a second of sim time
        std::snprintf(buf, sizeof buf, "%.1f m/s", t.speed);
        ctx.status("speed", buf);
        std::snprintf(buf, sizeof buf, "%d%s", ref_->laps_completed() + 1, laps_ > 0 ? ("/" + std::to_string(laps_)).c_str() : "");
        ctx.status("lap", buf);
      }
      if (ev.lap_completed) {
        std::snprintf(buf, sizeof buf, "lap %d: %.3f s", ref_->laps_completed(), ref_->lap_times().back());
        ctx.log(LogLevel::info, buf);
        if (laps_ > 0 && ref_->laps_completed() >= laps_) ctx.finish(std::to_string(laps_) + " laps completed");
      }
      if (ev.track_violation) {
        std::snprintf(buf, sizeof buf, "track limits: car left the track at s = %.1f m", ref_->s());
        ctx.log(LogLevel::warn, buf);
      }
      if (ev.obstacle_hit) {
        std::snprintf(buf, sizeof buf, "obstacle hit at s = %.1f m", ref_->s());
        ctx.log(LogLevel::warn, buf);
      }
      if (clearance_required_ >= 0 && ref_->obstacle_min_clearance() < clearance_required_) {
        std::snprintf(buf, sizeof buf, "obstacle passed %.2f m off at s = %.1f m (at least %.2f m required)",
                      ref_->obstacle_min_clearance(), ref_->s(), clearance_required_);
        clearance_required_ = -1;  // once
        fail(ctx, buf);
      }
      if (laps_ > 0 && stopped_timeout_ > 0 && !failed_ && ref_->stopped_for() >= stopped_timeout_) {
        std::snprintf(buf, sizeof buf, "did not finish: %d of %lld laps; the car stopped at s = %.1f m and stood %.1f s",
                      ref_->laps_completed(), static_cast<long long>(laps_), ref_->s(), ref_->stopped_for());
        fail(ctx, buf);
      }
      if (ev.wall_contact) {
        std::snprintf(buf, sizeof buf, "wall contact at s = %.1f m, t = %.3f s, %.1f m/s", ref_->s(), t.t, t.speed);
        if (crash_ends_) fail(ctx, std::string("crash: ") + buf);
        else ctx.log(LogLevel::warn, buf);
      }
    }
    score_estimates();
  }

  void deactivate(Context& ctx) override {
    if (!ref_) {
      if (laps_ > 0) ctx.fail("did not finish: 0 of " + std::to_string(laps_) + " laps; the referee never saw the world");
      return;
    }
    score_estimates();
    // A race that ended before its laps did not do its job, however it ended (duration, a stop).
    // (Once: a race this referee has already failed — a crash, a stop — says so once.)
    if (laps_ > 0 && ref_->laps_completed() < laps_ && !failed_) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "did not finish: %d of %lld laps; the run ended at t = %.1f s with the car at s = %.1f m",
                    ref_->laps_completed(), static_cast<long long>(laps_), ref_->t(), ref_->s());
      fail(ctx, buf);
    }
    ctx.metric("laps_completed", static_cast<double>(ref_->laps_completed()));
    ctx.metric("lap_times_s", ref_->lap_times());
    ctx.metric("max_speed_mps", ref_->max_speed());
    ctx.metric("wall_contacts", static_cast<double>(ref_->wall_contacts()));
    ctx.metric("track_violations", static_cast<double>(ref_->track_violations()));
    ctx.metric("min_wall_clearance_m", ref_->min_wall_clearance());
    ctx.metric("min_wall_clearance_s_m", ref_->min_wall_clearance_s());
    ctx.metric("obstacles_hit", static_cast<double>(ref_->obstacles_hit()));
    ctx.metric("obstacle_min_clearance_m", ref_->obstacle_min_clearance());
    ctx.metric("localization_rmse_m", ref_->localization_rmse());
    ctx.metric("localization_max_error_m", ref_->localization_max_error());
    ctx.metric("localization_samples", static_cast<double>(ref_->localization_samples()));
  }

 private:
  void fail(Context& ctx, const std::string& why) {
    failed_ = true;
    ctx.fail(why);
  }

  void score_estimates() {
    for (const auto& e : io_.estimate.take())
      ref_->localization(static_cast<double>(e->header().stamp_ns()) * 1e-9, e->x(), e->y());
  }

  bool crash_ends_ = true;
  std::int64_t laps_ = 0;
  double stopped_timeout_ = 10;
  bool failed_ = false;  // this referee has failed the run: one reason is enough
  double clearance_required_ = -1;
  std::uint64_t samples_ = 0;
  Footprint fp_;
  std::unique_ptr<Track> track_;
  std::unique_ptr<Referee> ref_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(RefereeNode)
