// sim.race_control: the simulated race control on the car's CAN bus. It plays a script of flags
// as base_to_car_summary frames (the car's DBC, the vehicle interface's codes) in cannelloni
// datagrams over UDP, each with its heartbeat, the car's laps counted from the truth; silences
// stop the frames. From the truth it judges whether the car did what each flag asks within the
// distance it needs (common/flag_judge.hpp), and fails the run when not. docs/race-control.md.
#include <brickyard/plugin.hpp>

#include "sim/race_control/params.hpp"
#include "sim/run_time.hpp"
#include "sim/world_msg.hpp"

#include <cmath>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Ports {
  Input<msgs::VehicleState> truth;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("the car: its station along the track (laps) and its path and speed (the judge)").depth(1024);
  return b;
}

class RaceControlNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.race_control", "1.0.0")
        .describe("the simulated race control: a script of flags as base_to_car_summary frames over UDP; judges the car's slow-downs and stops")
        .with_ports(ports())
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    Setup setup = read_setup(ctx, s);
    std::string error;
    bus_ = vi::open_udp_sender(setup.send_to, error);
    if (!bus_) throw BadInput("parameter 'send_to': " + error);
    dbc_ = std::move(setup.dbc);
    rc_.emplace(std::move(setup.script), s.frame_hz, s.rank);
    judge_.emplace(s.judge);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (const auto& s : io_.truth.take()) {
      const double t = run_.of(ctx, stamp(*s));
      rc_->station(s->s());
      say(ctx, judge_->truth(t, s->x(), s->y(), std::hypot(s->vx(), s->vy())));
      if (rc_->laps() != laps_) say(ctx, judge_->lap(t, laps_ = rc_->laps()));
    }
    const SimRaceControl::Tick tick = rc_->step(run_.now_ns(ctx));
    if (tick.began) {
      ctx.log(LogLevel::info, "race control: " + tick.began->text);
      say(ctx, judge_->flag(run_.now_s(ctx), *tick.began));
    }
    if (!tick.frame) return;
    const vi::PackResult p = dbc_->pack(*tick.frame);
    if (!p.ok() || !bus_->send({p.frame})) failed(ctx, p.ok() ? bus_->error() : p.error);
    frames_ += p.ok();
  }

  void deactivate(Context& ctx) override {
    if (!judge_) return;
    say(ctx, judge_->run_ended(run_.now_s(ctx)));
    ctx.metric("frames_sent", static_cast<double>(frames_));
    ctx.metric("laps", rc_->laps());
    ctx.metric("flags_judged", judge_->judged());
    ctx.metric("last_distance_m", judge_->last_distance_m());
    ctx.metric("last_allowed_m", judge_->last_allowed_m());
  }

 private:
  static void say(Context& ctx, const std::vector<JudgeNotice>& notices) {
    for (const JudgeNotice& n : notices) {
      if (n.fail) ctx.fail(n.text);
      else ctx.log(LogLevel::info, n.text);
    }
  }

  void failed(Context& ctx, const std::string& why) {
    if (!error_logged_) ctx.log(LogLevel::error, "race control's frames: " + why);
    error_logged_ = true;
  }

  std::optional<vi::RaceControlDbc> dbc_;
  std::optional<SimRaceControl> rc_;
  std::optional<FlagJudge> judge_;
  std::unique_ptr<vi::CanBus> bus_;
  Ports io_;
  RunTime run_;
  int laps_ = 0;
  std::uint64_t frames_ = 0;
  bool error_logged_ = false;
};

}  // namespace

BRICKYARD_PLUGINS(RaceControlNode)
