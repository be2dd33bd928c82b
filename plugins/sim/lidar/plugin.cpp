// sim.lidar: one LiDAR (Luminar Hydra on the AV-21 by default) ray casting the world from the
// vehicle's ground-truth pose; points in the sensor frame, the sensor's mount in the message.
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"
#include "sim/common/scanner.hpp"
#include "sim/sensor_faults.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::uint8_t sensor_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "lidar_front";
  std::vector<double> mount, mount_rpy_deg;  // empty: the vehicle file's mount
  LidarRowsDeg rows;
  LidarSpec spec;  // columns, ranges, noise and dropout; the rest is computed in configure
  FaultSchedule faults{"[]", 1, kLidarFaultTypes};  // as declared: no window
};

ParamBinding<Settings> bindings() {
  using L = LidarSpec;
  using R = LidarRowsDeg;
  ParamBinding<Settings> b;
  b.bind("sensor_id", &Settings::sensor_id).range(0, 255);
  b.declare(ParamSpec::number("rate_hz", 20).in_unit("Hz").range(0.1, 1000));  // the host's trigger only
  // The host's too (Manifest::delivered_after): a frame is delivered once its sweep is over.
  b.declare(ParamSpec::number("latency_s", 0.05).in_unit("s").range(0, 10)
                .doc("a frame, stamped at its scan, is delivered this long after it (sim clock): a sweep, 1 / rate_hz, "
                     "as a spinning LiDAR's frame is ready when its sweep ends; at most 1 / rate_hz"));
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its LiDARs sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the sensor's mount in the vehicle file");
  b.bind("mount", &Settings::mount).in_unit("m").range(-100, 100).doc("sensor position in base_link, m (x, y, z); empty: vehicle_mount's");
  b.bind("mount_rpy_deg", &Settings::mount_rpy_deg).in_unit("deg").range(-360, 360)
      .doc("sensor roll, pitch, yaw in base_link, deg; empty: vehicle_mount's");
  b.bind("h_fov_deg", &Settings::rows, &R::h_fov_deg).in_unit("deg").range(1, 360);
  b.bind("columns", &Settings::spec, &L::columns).range(1, 100000);
  b.bind("rows", &Settings::rows, &R::rows).range(1, 1024);
  b.bind("v_min_deg", &Settings::rows, &R::v_min_deg).in_unit("deg").range(-90, 90);
  b.bind("v_max_deg", &Settings::rows, &R::v_max_deg).in_unit("deg").range(-90, 90);
  b.bind("row_spacing", &Settings::rows, &R::row_spacing).one_of({"horizon", "uniform"})
      .doc("horizon: rows concentrated near 0 deg as on the Hydra; uniform: evenly spaced");
  b.bind("horizon_exponent", &Settings::rows, &R::horizon_exponent).range(1, 10).doc("horizon spacing: elevation ~ |u|^exponent");
  b.bind("row_angles_deg", &Settings::rows, &R::row_angles_deg).in_unit("deg").range(-90, 90)
      .doc("explicit row elevations, deg; overrides rows and spacing");
  b.bind("min_range", &Settings::spec, &L::min_range).in_unit("m").range(0, 1000);
  b.bind("max_range", &Settings::spec, &L::max_range).in_unit("m").range(1, 1000);
  b.bind("range_noise", &Settings::spec, &L::range_noise).in_unit("m").range(0, 100).doc("1 sigma");
  b.bind("dropout", &Settings::spec, &L::dropout).range(0, 1).doc("probability that a return is lost");
  b.bind("threads", &Settings::spec, &L::threads).range(1, 2).doc("threads the columns are marched on (AVX2); the same bits");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]").doc("windows: noise (range sigma x factor), frame_loss, freeze, dropout"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 1, kLidarFaultTypes); });
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
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>)
        .periodic("rate_hz")
        .delivered_after("latency_s");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.sensor_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto m = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount, "mount");
    const auto r = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount_rpy_deg, "mount_rpy_deg", true);
    scanner_ = Scanner(placed_spec(s.spec, m, r, s.rows), s.faults, Rng(ctx.seed()));
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!scanner_.started()) {
      auto w = newest(io_.world);
      if (!w) return;
      scanner_.start(from_message(*w));
    }
    auto s = newest(io_.truth);
    if (!s) return;
    const Scanner::Frame f = scanner_.frame(run_.now_s(ctx), body_pose(*s), s->x(), s->y());
    if (f == Scanner::Frame::lost) return;
    // A frozen sensor sends its last frame again, stamped now (a published one is shared: left as it is).
    auto m = f == Scanner::Frame::fresh ? fresh_cloud() : std::make_shared<msgs::PointCloud>(*last_);
    m->header().stamp_ns(ctx.now_ns());
    m->header().seq(seq_++);
    if (f == Scanner::Frame::fresh) last_ = m;
    io_.cloud.publish(m);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(scanner_.frames()));
    ctx.metric("frames_lost", static_cast<double>(scanner_.frames_lost()));
    ctx.metric("rays", static_cast<double>(scanner_.rays()));
    ctx.metric("digest", scanner_.digest());
    ctx.metric("points_per_frame", scanner_.points_per_frame());
  }

 private:
  // The scanner's fresh points in a message; the buffers move into it (no copy).
  std::shared_ptr<msgs::PointCloud> fresh_cloud() {
    const LidarSpec& spec = scanner_.spec();
    auto m = std::make_shared<msgs::PointCloud>();
    m->header().frame_id("lidar_" + std::to_string(id_));
    m->sensor_id(id_);
    m->sensor_x(spec.mount.x()); m->sensor_y(spec.mount.y()); m->sensor_z(spec.mount.z());
    m->sensor_roll(spec.roll); m->sensor_pitch(spec.pitch); m->sensor_yaw(spec.yaw);
    PointBuffers& p = scanner_.points();
    m->x(std::move(p.x)); m->y(std::move(p.y)); m->z(std::move(p.z)); m->intensity(std::move(p.intensity));
    return m;
  }

  std::uint8_t id_ = 0;
  Scanner scanner_;
  std::uint32_t seq_ = 0;
  std::shared_ptr<const msgs::PointCloud> last_;  // the last fresh frame, as published
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(Lidar)
