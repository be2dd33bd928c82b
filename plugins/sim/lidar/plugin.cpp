// sim.lidar: one LiDAR (Luminar Hydra on the AV-21 by default) ray casting the world from the
// vehicle's ground-truth pose; points in the sensor frame, the sensor's mount in the message.
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"
#include "../common/digest.hpp"
#include "../common/lidar.hpp"
#include "../sensor_faults.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

constexpr double kDeg = M_PI / 180.0;

// The fault windows a LiDAR takes, over (range).
const std::vector<std::string> kFaultTypes = {"noise", "frame_loss", "freeze", "dropout"};

struct Settings {
  std::uint8_t sensor_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "lidar_front";
  std::vector<double> mount, mount_rpy_deg;  // empty: the vehicle file's mount
  double h_fov_deg = 120;
  int rows = 32;
  double v_min_deg = -15, v_max_deg = 15;
  std::string row_spacing = "horizon";
  double horizon_exponent = 2.0;
  std::vector<double> row_angles_deg;
  LidarSpec spec;  // columns, ranges, noise and dropout; the rest is computed in configure
  FaultSchedule faults{"[]", 1, kFaultTypes};  // as declared: no window
};

ParamBinding<Settings> bindings() {
  using L = LidarSpec;
  ParamBinding<Settings> b;
  b.bind("sensor_id", &Settings::sensor_id).range(0, 255);
  b.declare(ParamSpec::number("rate_hz", 20).in_unit("Hz").range(0.1, 1000));  // the host's trigger only
  // The host's too (Manifest::delivered_after): a frame is delivered once its sweep is over.
  b.declare(ParamSpec::number("latency_s", 0.05).in_unit("s").range(0, 10)
                .doc("a frame, stamped at its scan, is delivered this long after it (sim clock): a sweep, 1 / rate_hz, "
                     "as a spinning LiDAR's frame is ready when its sweep ends; at most 1 / rate_hz"));
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its LiDARs sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the sensor's mount in the vehicle file");
  b.bind("mount", &Settings::mount).in_unit("m").range(-100, 100)
      .doc("sensor position in base_link, m (x, y, z); empty: vehicle_mount's");
  b.bind("mount_rpy_deg", &Settings::mount_rpy_deg).in_unit("deg").range(-360, 360)
      .doc("sensor roll, pitch, yaw in base_link, deg; empty: vehicle_mount's");
  b.bind("h_fov_deg", &Settings::h_fov_deg).in_unit("deg").range(1, 360);
  b.bind("columns", &Settings::spec, &L::columns).range(1, 100000);
  b.bind("rows", &Settings::rows).range(1, 1024);
  b.bind("v_min_deg", &Settings::v_min_deg).in_unit("deg").range(-90, 90);
  b.bind("v_max_deg", &Settings::v_max_deg).in_unit("deg").range(-90, 90);
  b.bind("row_spacing", &Settings::row_spacing).one_of({"horizon", "uniform"})
      .doc("horizon: rows concentrated near 0 deg as on the Hydra; uniform: evenly spaced");
  b.bind("horizon_exponent", &Settings::horizon_exponent).range(1, 10).doc("horizon spacing: elevation ~ |u|^exponent");
  b.bind("row_angles_deg", &Settings::row_angles_deg).in_unit("deg").range(-90, 90)
      .doc("explicit row elevations, deg; overrides rows and spacing");
  b.bind("min_range", &Settings::spec, &L::min_range).in_unit("m").range(0, 1000);
  b.bind("max_range", &Settings::spec, &L::max_range).in_unit("m").range(1, 1000);
  b.bind("range_noise", &Settings::spec, &L::range_noise).in_unit("m").range(0, 100).doc("1 sigma");
  b.bind("dropout", &Settings::spec, &L::dropout).range(0, 1).doc("probability that a return is lost");
  b.bind("threads", &Settings::spec, &L::threads).range(1, 2)
      .doc("threads the columns are marched on (the AVX2 path); the frame is the same bit for bit");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]").doc("windows: noise (range sigma x factor), frame_loss, freeze, dropout"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 1, kFaultTypes); });
  b.below("v_min_deg", "v_max_deg");
  return b;
}

struct Ports {
  Input<msgs::TrackWorld> world;
  Input<msgs::VehicleState> truth;
  Output<msgs::PointCloud> cloud;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world to scan").depth(1);
  b.input("truth", &Ports::truth).doc("vehicle pose").depth(1);
  b.output("cloud", &Ports::cloud).doc("points in the sensor frame");
  return b;
}

class Lidar : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.lidar", "1.0.0")
        .describe("LiDAR by ray casting against the banked road, walls and pylons; range noise, dropout, frame loss")
        .with_ports(ports())
        .plays(roles::lidar_driver)
        .parameters(bindings())
        .periodic("rate_hz")
        .delivered_after("latency_s");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.sensor_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto m = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount, "mount");
    const auto r = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount_rpy_deg, "mount_rpy_deg", true);
    spec_ = s.spec;
    spec_.mount = {m[0], m[1], m[2]};
    spec_.roll = r[0] * kDeg;
    spec_.pitch = r[1] * kDeg;
    spec_.yaw = r[2] * kDeg;
    spec_.h_fov = s.h_fov_deg * kDeg;
    if (!s.row_angles_deg.empty()) {
      for (double a : s.row_angles_deg) spec_.elevations.push_back(a * kDeg);
    } else {
      spec_.elevations = row_elevations(s.rows, s.v_min_deg, s.v_max_deg, s.row_spacing, s.horizon_exponent);
    }
    faults_ = s.faults;
    rng_ = Rng(ctx.seed());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!caster_) {
      auto w = newest(io_.world);
      if (!w) return;
      track_ = std::make_unique<Track>(from_message(*w));
      caster_ = std::make_unique<LidarCaster>(*track_, spec_);
    }
    auto s = newest(io_.truth);
    if (!s) return;
    FaultEffect e = faults_.at(ctx.now_s(), rng_);
    if (e.drop) { ++lost_; return; }
    if (e.freeze && last_) {
      auto m = std::make_shared<msgs::PointCloud>(*last_);
      m->header().stamp_ns(ctx.now_ns());
      m->header().seq(seq_++);
      io_.cloud.publish(std::shared_ptr<const msgs::PointCloud>(m));
      return;
    }
    auto m = std::make_shared<msgs::PointCloud>();
    m->header().stamp_ns(ctx.now_ns());
    m->header().seq(seq_++);
    m->header().frame_id("lidar_" + std::to_string(id_));
    m->sensor_id(id_);
    m->sensor_x(spec_.mount.x()); m->sensor_y(spec_.mount.y()); m->sensor_z(spec_.mount.z());
    m->sensor_roll(spec_.roll); m->sensor_pitch(spec_.pitch); m->sensor_yaw(spec_.yaw);
    buf_.clear();
    hint_ = track_->project(s->x(), s->y(), hint_).seg;
    rays_ += caster_->scan(body_pose(*s), hint_, rng_, e.noise_factor, buf_);
    points_ += buf_.x.size();
    for (const auto* v : {&buf_.x, &buf_.y, &buf_.z, &buf_.intensity}) digest_.add(v->data(), v->size() * sizeof(float));
    // The buffers move into the message (no copy); scan reserves them again next frame.
    m->x(std::move(buf_.x)); m->y(std::move(buf_.y)); m->z(std::move(buf_.z)); m->intensity(std::move(buf_.intensity));
    ++frames_;
    last_ = m;
    io_.cloud.publish(std::shared_ptr<const msgs::PointCloud>(m));
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("frames_lost", static_cast<double>(lost_));
    ctx.metric("rays", static_cast<double>(rays_));
    ctx.metric("digest", digest_.hex());
    ctx.metric("points_per_frame", frames_ ? static_cast<double>(points_) / frames_ : 0.0);
  }

 private:
  std::uint8_t id_ = 0;
  Digest digest_;
  LidarSpec spec_;
  FaultSchedule faults_;
  Rng rng_;
  std::unique_ptr<Track> track_;
  std::unique_ptr<LidarCaster> caster_;
  PointBuffers buf_;
  int hint_ = -1;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, lost_ = 0, rays_ = 0, points_ = 0;
  std::shared_ptr<const msgs::PointCloud> last_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Lidar)
