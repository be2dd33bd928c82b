// control.wall_follower: the paper's wall command u_w = w_θ y′(L) + w_d (d_w − d_gap) from the
// wall detector's estimate, with a speed policy (common/wall_follower.hpp); or, law offset_line,
// the line a gap inside the nearer of two walls followed by the path tracker's LQR
// (common/wall_line.hpp).
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "../command_msg.hpp"
#include "common/wall_follower.hpp"
#include "common/mapped_wall.hpp"
#include "common/wall_line.hpp"
#include "map_msg.hpp"
#include "control/vehicle_tracking.hpp"
#include "vehicle_param.hpp"

#include <cmath>
#include <cstdlib>
#include <deque>
#include <memory>

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::control;

// What the graph says: the law's parameters, and the car whose steering limit it keeps.
struct Settings {
  WallFollowerParams law;
  bool offset_line = false;         // the law: the paper's, or the offset line
  WallLineParams line;
  double r_steer = 200;             // offset_line: the LQR's steering cost (the car stack's, docs/control.md)
  double steer_margin = 0.8;        // offset_line: the line asks at most this share of the steering limit
  std::string vehicle = plugins::default_vehicle_file;
  std::optional<double> max_steer;  // NaN: the vehicle file's
};

ParamBinding<Settings> bindings() {
  using P = WallFollowerParams;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: its steering limit");
  b.bind_choice("side", {{"right", -1}, {"left", 1}}, &Settings::law, &P::side).doc("the wall followed");
  b.bind("w_theta", &Settings::law, &P::w_theta).range(-10, 10)
      .doc("rad of steer per unit of the wall's slope at the look-ahead");
  b.bind("w_d", &Settings::law, &P::w_d).in_unit("rad/m").range(-10, 10).doc("rad of steer per m of gap error");
  b.bind("gap", &Settings::law, &P::gap).in_unit("m").range(0, 100).doc("distance kept to the wall");
  b.bind("lookahead", &Settings::law, &P::lookahead).in_unit("m").range(0, 1000);
  b.bind("max_steer", &Settings::max_steer).in_unit("rad").range(0.01, 1.5).doc("steering limit; default: the vehicle file's");
  b.bind("schedule_above", &Settings::law, &P::schedule_above).in_unit("m/s").range(0, 200)
      .doc("above this speed the look-ahead grows and the gains shrink with speed as a pure pursuit's; 0: fixed");
  b.bind_choice("speed_policy", {{"reduce", true}, {"hold", false}}, &Settings::law, &P::reduce_speed)
      .doc("while following: slow to fallback_speed, or hold");
  b.bind("fallback_speed", &Settings::law, &P::fallback_speed).in_unit("m/s").range(0, 200);
  b.bind("decel", &Settings::law, &P::decel).in_unit("m/s^2").range(0.1, 100);
  b.bind("restart_speed", &Settings::law, &P::restart_speed).in_unit("m/s").range(0, 200)
      .doc("taking over slower than this (a car that had stopped), the speed it drives off to");
  b.bind("a_lat", &Settings::law, &P::a_lat).in_unit("m/s^2").range(0, 100).doc("the wall's bend caps the speed at sqrt(a_lat / curvature); 0: off");
  b.bind("speed_gain", &Settings::law, &P::speed_gain).range(0, 100);
  b.bind_choice("law", {{"paper", false}, {"offset_line", true}}, &Settings::offset_line)
      .doc("paper: u_w on the one wall wired to 'wall'; offset_line: the path tracker's LQR on a line placed by the nearer valid "
           "wall of 'wall_left' and 'wall_right' — the planner's path or the map's edge laid onto the wall, else a gap inside it "
           "(docs/algorithms.md)");
  using W = WallLineParams;
  b.bind("min_gap", &Settings::line, &W::min_gap).in_unit("m").range(0, 100)
      .doc("offset_line: never closer to the wall");
  b.bind("max_gap", &Settings::line, &W::max_gap).in_unit("m").range(0, 100)
      .doc("offset_line: the most kept; the gap is the car's distance to the wall when it takes it, within [min_gap, max_gap]");
  b.bind("hold_s", &Settings::line, &W::hold_s).in_unit("s").range(0, 60)
      .doc("offset_line: a lost wall's last line, carried by wheel speed and yaw rate, is followed this long while either wall may come back");
  b.bind("r_steer", &Settings::r_steer).in_unit("1/rad^2").range(1e-6, 1e6).doc("offset_line: the LQR's cost of the steering");
  b.bind("steer_margin", &Settings::steer_margin).range(0.1, 1).doc("offset_line: the line is never tighter than this share of the steering limit turns");
  b.not_above("min_gap", "max_gap");
  return b;
}

struct Ports {
  Input<msgs::WallEstimate> wall, wall_left, wall_right;
  Input<msgs::WheelSpeeds> wheels;
  Input<msgs::Imu> imu;
  Input<msgs::ModeStatus> mode;
  Input<msgs::TrackMap> map;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::Path> path;
  Output<msgs::ControlCommand> command;
  Output<msgs::WallEstimate> followed;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("wall", &Ports::wall)
      .doc("the wall detector's estimate of the wall on 'side' (law paper: required)").optional().depth(4).steps();
  b.input("wall_left", &Ports::wall_left).doc("offset_line: the left wall's estimate").optional().depth(4).steps();
  b.input("wall_right", &Ports::wall_right).doc("offset_line: the right wall's estimate").optional().depth(4).steps();
  b.input("wheels", &Ports::wheels).doc("speed, independent of GNSS");
  b.input("imu", &Ports::imu).doc("offset_line: the yaw rate that carries the car along the line between wall frames (optional)")
      .optional().depth(32).steps();
  b.input("mode", &Ports::mode).doc("the system manager's mode: taking over starts the speed policy (optional)")
      .optional().depth(8);
  b.input("map", &Ports::map).doc("offset_line: the track, whose edge on the wall's side gives the wall's shape ahead (optional)")
      .optional().depth(1);
  b.input("estimate", &Ports::estimate)
      .doc("offset_line with a map: the pose that places the map's edge round the car (optional)")
      .optional().depth(8);
  b.input("path", &Ports::path)
      .doc("offset_line with a map: the planner's path; where the wall and the map agree, the car follows it, "
           "placed by the wall (optional)")
      .optional().depth(2);
  b.output("command", &Ports::command).doc("steer and pedals, source \"wall_follower\"");
  b.output("followed", &Ports::followed)
      .doc("offset_line: the wall followed, every wall frame (valid while there is a line to follow, a held one included)");
  return b;
}

class WallFollowerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("control.wall_follower", "1.0.0")
        .describe("the paper's wall-following command u_w = w_theta y'(L) + w_d (d_w - d_gap), holding or reducing speed")
        .with_ports(ports())
        .plays(roles::fallback_controller)
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    WallFollowerParams law = s.law;
    law.max_steer = s.max_steer.value_or(car.max_steer);
    follower_ = WallFollower(law);
    line_mode_ = s.offset_line;
    io_ = ports().connect(ctx);
    if (!line_mode_ && !io_.wall.connected())
      throw BadInput("law paper follows the wall wired to input 'wall', which is not wired");
    if (line_mode_ && !io_.wall.connected() && !io_.wall_left.connected() && !io_.wall_right.connected())
      throw BadInput("law offset_line needs a wall: wire 'wall_left', 'wall_right' or 'wall'");
    if (line_mode_) {
      TrackerParams tp;
      control::apply_vehicle(tp, car);
      tp.max_steer = law.max_steer;
      tp.steer_law = SteerLaw::lqr;
      tp.lqr.r_steer = s.r_steer;
      tp.speed_gain = law.speed_gain;
      tp.decel = law.decel;
      tp.pedal_law = PedalLaw::feedforward;  // within the friction circle: it brakes in turns
      WallLineParams line = s.line;
      line.a_lat = law.a_lat;
      line.max_curvature = std::tan(s.steer_margin * law.max_steer) / car.wheelbase;
      line_ = WallLineFollower(line, law, tp);
      line_params_ = line;
    }
  }

  void step(Context& ctx) override {
    for (auto& w : io_.wheels.take()) speed_ = 0.5 * (w->rear_left() + w->rear_right());
    const double t = ctx.now_s();
    for (auto& m : io_.mode.take()) {
      path_mode_ = m->active_controller() == "path_tracker";
      const bool active = m->active_controller() == "wall_follower";
      if (active && !active_) {
        follower_.engage(t, speed_);
        line_.engage(t, speed_);
        ++engaged_;
      }
      active_ = active;
    }
    if (line_mode_) return step_line(ctx, t);
    for (auto& w : io_.wall.take()) {
      if (!io_.mode.connected() && !engaged_) {  // no manager to say when: from the first estimate
        follower_.engage(t, speed_);
        ++engaged_;
      }
      // Not driving yet: the speed policy starts from now, so the command the manager forwards at
      // the handover holds the car's speed instead of braking for a stale target.
      if (io_.mode.connected() && !active_) follower_.engage(t, speed_);
      const Command c = follower_.control(t, seen(*w), speed_);
      io_.command.publish(command_message(c, "wall_follower", w->header().stamp_ns(), seq_++));
      invalid_ += !w->valid();
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("commands", static_cast<double>(seq_));
    ctx.metric("engaged", static_cast<double>(engaged_));
    ctx.metric("invalid_walls", static_cast<double>(invalid_));
    if (line_mode_) {
      ctx.metric("wall_switches", static_cast<double>(line_.switches()));
      ctx.metric("frames_left", static_cast<double>(frames_[0]));
      ctx.metric("frames_right", static_cast<double>(frames_[1]));
      ctx.metric("frames_held", static_cast<double>(held_));
      ctx.metric("lines_planned", static_cast<double>(line_.planned_lines()));
      ctx.metric("wall_bins_learnt", static_cast<double>(line_.learnt_bins()));
      ctx.metric("lines_mapped", static_cast<double>(line_.mapped_lines()));
      ctx.metric("lines_polynomial", static_cast<double>(line_.polynomial_lines()));
    }
  }

 private:
  static WallView seen(const msgs::WallEstimate& w) { return {w.coefficients(), w.valid(), w.x_min(), w.x_max()}; }

  // law offset_line: the newest estimate of each side; the IMU carries the car between frames.
  void step_line(Context& ctx, double t) {
    for (auto& m : io_.map.take()) {
      // The map source republishes the same map every second: a track is built again only for
      // another one.
      if (track_) {
        const auto& g = track_->geometry().line;
        if (m->x() == g.x && m->y() == g.y && m->width_left() == g.width_left && m->width_right() == g.width_right) continue;
      }
      try {
        track_ = std::make_unique<track::Track>(plugins::from_message(*m));
        hint_ = -1;
      } catch (const std::exception& e) {
        ctx.log(LogLevel::warn, std::string("map ignored: ") + e.what());
      }
    }
    for (auto& e : io_.estimate.take()) {
      pose_ = e;
      poses_.push_back(e);
      if (poses_.size() > kHistory) poses_.pop_front();
    }
    for (auto& p : io_.path.take()) planned_path_ = p;
    for (auto& m : io_.imu.take()) {
      const double ts = static_cast<double>(m->header().stamp_ns()) * 1e-9;
      if (imu_t_ >= 0 && ts > imu_t_) {
        line_.moved(ts - imu_t_, speed_, m->gyro_z());
        motion_.add(ts, ts - imu_t_, speed_, m->gyro_z());
      }
      imu_t_ = ts;
      yaw_rate_ = m->gyro_z();
    }
    bool fresh = false;
    std::int64_t stamp = 0;
    const int single = follower_.params().side > 0 ? 0 : 1;  // where 'wall' stands in
    for (int i = 0; i < 2; ++i) {
      auto& side = i == 0 ? io_.wall_left : io_.wall_right;
      auto& in = side.connected() ? side : (i == single ? io_.wall : side);
      for (auto& w : in.take()) {
        last_[i] = seen(*w);
        last_[i].valid = last_[i].valid && std::isfinite(w->distance());
        stamp = std::max(stamp, w->header().stamp_ns());
        fresh = true;
      }
    }
    if (fresh) {
      // A wall frame is the car's surroundings at its stamp, which may be some time ago (a
      // LiDAR's frame is delivered when its sweep is over, docs/architecture.md): the map's edges
      // and the path are placed with the estimate of that stamp, and the line, once set, is
      // carried by the motion since (below).
      const std::shared_ptr<const msgs::LocalizationEstimate> pose = pose_at(stamp);
      std::vector<EdgePoint> edges[2];
      const bool mapped = track_ && pose;
      if (mapped) {
        const WallLineParams& lp = line_params_;
        for (int i = 0; i < 2; ++i)
          edges[i] = mapped_edge(*track_, i == 0 ? 1 : -1, pose->x(), pose->y(), pose->yaw(), lp.map_behind, lp.map_ahead, hint_);
      }
      std::vector<PathPoint> planned;  // the planner's path in the vehicle frame of the estimate
      if (mapped && planned_path_) {
        const auto& poses = planned_path_->poses();
        const auto& speeds = planned_path_->speed();
        for (std::size_t i = 0; i < poses.size(); ++i)
          planned.push_back({poses[i].x(), poses[i].y(), i < speeds.size() ? speeds[i] : 0.0});
        planned = in_vehicle_frame(std::move(planned), pose->x(), pose->y(), pose->yaw());
      }
      // The car's place along the map, and whether localization is good (the manager drives the
      // path): the follower learns there where the walls stand from the edges.
      const double s_car = mapped ? track_->project(pose->x(), pose->y(), hint_).s : 0.0;
      const bool calibrating = mapped && io_.mode.connected() && !active_ && path_mode_;
      line_.walls(t, last_[0], last_[1], mapped ? &edges[0] : nullptr, mapped ? &edges[1] : nullptr,
                  planned.size() >= 2 ? &planned : nullptr, s_car, calibrating);
      motion_.since(static_cast<double>(stamp) * 1e-9, [&](double dt, double v, double w) { line_.moved(dt, v, w); });
      const bool line = line_.has_line(t);
      if (line && line_.side() != 0) ++frames_[line_.side() > 0 ? 0 : 1];
      held_ += line && !last_[line_.side() > 0 ? 0 : 1].valid;
      invalid_ += !line;
      msgs::WallEstimate f;
      f.header().stamp_ns(stamp);
      f.header().seq(seq_);
      f.header().frame_id("vehicle");
      if (line_.side() != 0) f.coefficients(last_[line_.side() > 0 ? 0 : 1].coefficients);
      f.distance(line_.side() == 0 ? NAN : line_.side() * line_.gap());
      f.valid(line);
      io_.followed.publish(std::move(f));
    }
    // Drive at the IMU's rate while taking part, at the walls' otherwise.
    if (fresh || (imu_t_ >= 0 && (active_ || !io_.mode.connected()))) {
      if (!io_.mode.connected() && !engaged_) {
        line_.engage(t, speed_);
        ++engaged_;
      }
      if (io_.mode.connected() && !active_) line_.engage(t, speed_);
      const Command c = line_.control(t, speed_, yaw_rate_);
      io_.command.publish(command_message(c, "wall_follower", ctx.now_ns(), seq_++));
    }
  }

  // The estimate nearest a stamp (the newest when there is none).
  std::shared_ptr<const msgs::LocalizationEstimate> pose_at(std::int64_t stamp) const {
    std::shared_ptr<const msgs::LocalizationEstimate> best = pose_;
    for (const auto& e : poses_)
      if (std::llabs(e->header().stamp_ns() - stamp) < std::llabs(best->header().stamp_ns() - stamp)) best = e;
    return best;
  }

  static constexpr std::size_t kHistory = 64;
  std::deque<std::shared_ptr<const msgs::LocalizationEstimate>> poses_;
  MotionHistory motion_{kHistory};  // to carry a line from its wall frame's stamp on
  WallFollower follower_;
  WallLineFollower line_;
  bool line_mode_ = false;
  std::unique_ptr<track::Track> track_;
  std::shared_ptr<const msgs::LocalizationEstimate> pose_;
  std::shared_ptr<const msgs::Path> planned_path_;
  WallLineParams line_params_;
  int hint_ = -1;
  WallView last_[2];
  double imu_t_ = -1, yaw_rate_ = 0;
  std::uint64_t frames_[2] = {0, 0}, held_ = 0;
  Ports io_;
  double speed_ = 0;
  bool active_ = false;
  bool path_mode_ = false;  // the manager drives the path: localization is good
  std::uint32_t seq_ = 0;
  std::uint64_t engaged_ = 0, invalid_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(WallFollowerNode)
