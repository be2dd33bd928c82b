// sim.lidar: one LiDAR (Luminar Hydra on the AV-21 by default) ray casting the world from the
// vehicle's ground-truth pose; points in the sensor frame, the sensor's mount in the message.
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "lidar_settings.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Ports {
  Input<msgs::TrackWorld> world;
  Input<msgs::VehicleState> truth;
  std::array<Input<msgs::VehicleState>, kOtherCars> others;
  Output<msgs::PointCloud> cloud;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world to scan").depth(1);
  b.input("truth", &Ports::truth).doc("vehicle pose").depth(1);
  b.inputs("other", &Ports::others).doc("another car's truth (other0 to other3): seen as a box over its footprint")
      .required_first(0).depth(1);
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
        .parameters(lidar_bindings())
        .check(&plugins::check_vehicle_file<&lidar_bindings, &LidarSettings::vehicle>)
        .periodic("rate_hz")
        .delivered_after("latency_s");
  }

  void configure(Context& ctx) override {
    const LidarSettings s = lidar_bindings().read(ctx.params());
    id_ = s.sensor_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto m = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount, "mount");
    const auto r = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount_rpy_deg, "mount_rpy_deg", true);
    scanner_ = Scanner(placed_spec(s.spec, m, r, s.rows), s.faults, Rng(ctx.seed()));
    other_car_.front = car.front;
    other_car_.rear = car.rear;
    other_car_.half_width = car.half_width;
    other_car_.top = s.other_car_height;
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
    const Scanner::Frame f = scanner_.frame(run_.now_s(ctx), body_pose(*s), s->x(), s->y(), other_cars());
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

  // Where the other cars are now (those heard from).
  const std::vector<CarBody>& other_cars() {
    cars_.clear();
    for (auto& in : io_.others)
      if (auto o = newest(in)) {
        cars_.push_back(other_car_);
        cars_.back().world_from_body = body_pose(*o);
      }
    return cars_;
  }

  std::uint8_t id_ = 0;
  Scanner scanner_;
  CarBody other_car_;
  std::vector<CarBody> cars_;
  std::uint32_t seq_ = 0;
  std::shared_ptr<const msgs::PointCloud> last_;  // the last fresh frame, as published
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(Lidar)
