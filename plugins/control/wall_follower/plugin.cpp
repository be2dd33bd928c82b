// control.wall_follower: the paper's wall command u_w = w_θ y′(L) + w_d (d_w − d_gap) from the
// wall detector's estimate, with a speed policy (common/wall_follower.hpp); or, law offset_line,
// the line a gap inside the nearer of two walls followed by the path tracker's LQR
// (common/wall_line_run.hpp). When it takes over: common/engagement.hpp.
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "control/command_msg.hpp"
#include "control/common/engagement.hpp"
#include "control/common/wall_line_run.hpp"
#include "map_msg.hpp"
#include "params.hpp"
#include "ports.hpp"

#include <optional>
#include <string>
#include <vector>

namespace {

using namespace brickyard;
using namespace brickyard::control;

WallView seen(const msgs::WallEstimate& w) { return {w.coefficients(), w.valid(), w.x_min(), w.x_max()}; }

// The planner's path (map frame) with its speeds (0 where it has none).
std::vector<PathPoint> path_points(const msgs::Path& p) {
  std::vector<PathPoint> out;
  for (std::size_t i = 0; i < p.poses().size(); ++i)
    out.push_back({p.poses()[i].x(), p.poses()[i].y(), i < p.speed().size() ? p.speed()[i] : 0.0});
  return out;
}

class WallFollowerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("control.wall_follower", "1.0.0")
        .describe("the paper's wall-following command u_w = w_theta y'(L) + w_d (d_w - d_gap), holding or reducing speed")
        .with_ports(ports())
        .plays(roles::fallback_controller)
        .parameters(bindings())
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>);
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
    if (line_mode_) line_ = WallLineRun(s.line, law, s.r_steer, s.steer_margin, car);
    engagement_ = Engagement(io_.mode.connected());
  }

  void step(Context& ctx) override {
    for (auto& w : io_.wheels.take()) speed_ = 0.5 * (w->rear_left() + w->rear_right());
    const double t = ctx.now_s();
    for (auto& m : io_.mode.take())
      if (engagement_.mode(m->active_controller())) {
        follower_.engage(t, speed_);
        line_.engage(t, speed_);
      }
    if (line_mode_) return step_line(ctx, t);
    for (auto& w : io_.wall.take()) {
      if (engagement_.before_command()) follower_.engage(t, speed_);
      const Command c = follower_.control(t, seen(*w), speed_);
      io_.command.publish(command_message(c, "wall_follower", w->header().stamp_ns(), seq_++));
      invalid_ += !w->valid();
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("commands", static_cast<double>(seq_));
    ctx.metric("engaged", static_cast<double>(engagement_.engaged()));
    ctx.metric("invalid_walls", static_cast<double>(invalid_));
    if (line_mode_)
      for (const auto& [name, value] : line_.metrics()) ctx.metric(name, value);
  }

 private:
  // law offset_line: the newest estimate of each side; the IMU carries the car between frames.
  void step_line(Context& ctx, double t) {
    for (auto& m : io_.map.take())
      if (const std::string problem = line_.map(plugins::from_message(*m)); !problem.empty()) ctx.log(LogLevel::warn, problem);
    for (auto& e : io_.estimate.take()) line_.estimate(e->header().stamp_ns(), {e->x(), e->y(), e->yaw()});
    for (auto& p : io_.path.take()) line_.path(path_points(*p));
    for (auto& m : io_.imu.take()) line_.imu(m->header().stamp_ns(), m->gyro_z(), speed_);
    const int single = follower_.params().side > 0 ? 0 : 1;  // where 'wall' stands in
    for (int i = 0; i < 2; ++i) {
      auto& side = i == 0 ? io_.wall_left : io_.wall_right;
      auto& in = side.connected() ? side : (i == single ? io_.wall : side);
      for (auto& w : in.take()) line_.wall(i, seen(*w), w->distance(), w->header().stamp_ns());
    }
    const std::optional<FollowedWall> f = line_.frame(t, engagement_.calibrating());
    if (f) {
      invalid_ += !f->valid;
      io_.followed.publish(followed_message(*f));
    }
    // Drive at the IMU's rate while taking part, at the walls' otherwise.
    if (f || (line_.moving() && engagement_.taking_part())) {
      if (engagement_.before_command()) line_.engage(t, speed_);
      io_.command.publish(command_message(line_.control(t, speed_), "wall_follower", ctx.now_ns(), seq_++));
    }
  }

  msgs::WallEstimate followed_message(const FollowedWall& w) const {
    msgs::WallEstimate f;
    f.header().stamp_ns(w.stamp_ns);
    f.header().seq(seq_);
    f.header().frame_id("vehicle");
    f.coefficients(w.coefficients);
    f.distance(w.distance);
    f.valid(w.valid);
    return f;
  }

  WallFollower follower_;
  WallLineRun line_;
  Engagement engagement_;
  bool line_mode_ = false;
  Ports io_;
  double speed_ = 0;
  std::uint32_t seq_ = 0;
  std::uint64_t invalid_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(WallFollowerNode)
