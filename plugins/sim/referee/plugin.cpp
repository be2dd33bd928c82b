// sim.referee: judges the run from ground truth. Its metrics (names fixed by contract) are what
// later issues and their checks read from summary.json under the node named `referee`.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/plugin.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "vehicle_param.hpp"
#include "sim/common/race_judge.hpp"
#include "sim/referee/referee_report.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  RaceRules rules;
  // The car's rectangle: the vehicle file's unless the graph overrides it (NaN: off).
  std::optional<double> car_front, car_rear, car_half_width;
};

ParamBinding<Settings> bindings() {
  using R = RaceRules;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: its rectangle around base_link");
  b.bind("crash_ends_run", &Settings::rules, &R::crash_ends_run).doc("a wall contact fails the run (exit 1)");
  b.bind("obstacle_clearance_required", &Settings::rules, &R::obstacle_clearance_required).in_unit("m").range(-100, 100)
      .doc("passing an obstacle nearer than this (its surface to the car's) fails the run (exit 1); negative: off (hits are counted only)");
  b.bind("laps", &Settings::rules, &R::laps).range(0, 1000)
      .doc("a race of this many laps: finished when they are done, failed (did not finish) when the run ends before; 0: no race");
  b.bind("stopped_timeout_s", &Settings::rules, &R::stopped_timeout_s).in_unit("s").range(0, 3600)
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
  std::array<Input<msgs::VehicleState>, kOtherCars> others;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world").depth(1);
  b.input("truth", &Ports::truth).doc("ground truth").depth(1024).steps();
  b.input("estimate", &Ports::estimate).doc("a localization estimate to score (optional)").optional().depth(1024);
  b.inputs("other", &Ports::others).doc("another car's truth (other0 to other3): contacts and gaps, each the same model").required_first(0).depth(1);
  return b;
}

class RefereeNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.referee", "1.0.0")
        .describe("Laps, lap times, speed, wall contacts, track limits, clearances, localization error, contacts with other cars")
        .with_ports(ports())
        .parameters(bindings())
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    rules_ = s.rules;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    fp_.front = s.car_front.value_or(car.front);
    fp_.rear = s.car_rear.value_or(car.rear);
    fp_.half_width = s.car_half_width.value_or(car.half_width);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!judge_) {
      auto w = newest(io_.world);
      if (!w) return;
      track_ = std::make_unique<Track>(from_message(*w));
      judge_ = std::make_unique<RaceJudge>(*track_, fp_, rules_);
    }
    for (const auto& s : io_.truth.take())
      say(ctx, judge_->update({static_cast<double>(stamp(*s)) * 1e-9, s->x(), s->y(), s->yaw(), std::hypot(s->vx(), s->vy())}));
    for (std::size_t i = 0; i < others_.size(); ++i)
      if (auto o = newest(io_.others[i])) others_[i] = CarBox{o->x(), o->y(), o->yaw(), fp_};
    if (rivals()) say(ctx, judge_->other_cars(others_));
    score_estimates();
  }

  void deactivate(Context& ctx) override {
    if (!judge_) {
      if (auto why = RaceJudge::world_never_seen(rules_.laps)) ctx.fail(*why);
      return;
    }
    score_estimates();
    say(ctx, judge_->run_ended());
    report_metrics(ctx, *judge_, rivals());
  }

 private:
  bool rivals() const {
    return std::any_of(io_.others.begin(), io_.others.end(), [](const auto& in) { return in.connected(); });
  }
  void score_estimates() {
    for (const auto& e : io_.estimate.take())
      judge_->referee().localization(static_cast<double>(e->header().stamp_ns()) * 1e-9, e->x(), e->y());
  }

  RaceRules rules_;
  Footprint fp_;
  std::unique_ptr<Track> track_;
  std::unique_ptr<RaceJudge> judge_;
  std::vector<std::optional<CarBox>> others_ = std::vector<std::optional<CarBox>>(kOtherCars);
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(RefereeNode)
