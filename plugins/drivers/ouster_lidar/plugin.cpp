// drivers.ouster_lidar: an Ouster sensor on its wire (lidar packets of any profile, the sensor's
// metadata JSON for its geometry) to one PointCloud per rotation, in the sensor frame with the
// sensor's mount on the car. On the real clock the node wakes as packets arrive (and polls the
// port each period besides); a packet capture (pcap) replays at its pace. A sensor silent for longer than `silent_after_s` is reported.
// Formats: docs/drivers-formats.md; the devices: docs/drivers-transports.md.
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "drivers/device_failure.hpp"
#include "drivers/driver_metrics.hpp"
#include "drivers/ouster_metadata_param.hpp"
#include "drivers/ouster_source.hpp"
#include "drivers/silence_watch.hpp"
#include "drivers/source_param.hpp"
#include "vehicle_param.hpp"

#include <cmath>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::drivers;

struct Settings {
  std::string source = "udp://0.0.0.0:7502";
  std::string metadata;
  std::uint8_t sensor_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "lidar_front";
  std::vector<double> mount, mount_rpy_deg;  // empty: the vehicle file's mount
  bool second_return = false, device_time = true;
  double silent_after_s = 0.3;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("source", &Settings::source).doc(kSourceDoc);
  b.bind_required("metadata", &Settings::metadata).doc("the sensor's metadata JSON (its geometry and packet format)");
  b.bind("sensor_id", &Settings::sensor_id).range(0, 255);
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its sensors sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the sensor's mount in the vehicle file");
  b.bind("mount", &Settings::mount).in_unit("m").range(-100, 100).doc("sensor position in base_link, m (x, y, z); empty: vehicle_mount's");
  b.bind("mount_rpy_deg", &Settings::mount_rpy_deg).in_unit("deg").range(-360, 360).doc("sensor roll, pitch, yaw, deg; empty: vehicle_mount's");
  b.bind("second_return", &Settings::second_return).doc("dual-return profile: the second return's points");
  b.bind("device_time", &Settings::device_time).doc("stamp each frame at its measurement by the sensor's clock (else at receipt)");
  b.bind("silent_after_s", &Settings::silent_after_s).in_unit("s").range(0.01, 60).doc("no frame for this long: the sensor is reported silent");
  b.declare(ParamSpec::number("rate_hz", 1000).in_unit("Hz").range(1, 10000).doc("how often the port is polled (on the real clock the node also wakes as packets arrive)"));
  return b;
}

template <class Files> OusterSourceSettings source_settings(const Files& files, const Settings& s) {
  OusterSourceSettings o;
  read_ouster_wire(files, s.source, s.metadata, "an Ouster sensor", o);
  o.second_return = s.second_return;
  if (s.second_return && o.metadata.profile != OusterProfile::dual_return)
    throw BadInput("parameter 'second_return': " + files.find_file(s.metadata) + ": the profile " + to_string(o.metadata.profile) + " has one return");
  o.device_time = s.device_time;
  return o;
}

void check(const CheckView& v) { source_settings(v, bindings().read(v.params())); }

struct Ports {
  Output<msgs::PointCloud> cloud;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("cloud", &Ports::cloud).doc("one frame a rotation, sensor frame, the mount in the message");
  return b;
}

class OusterLidar : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("drivers.ouster_lidar", "1.0.0")
        .describe("an Ouster LiDAR on its wire (UDP lidar packets or a pcap capture, the sensor's metadata) to one cloud a rotation")
        .with_ports(ports())
        .plays(roles::lidar_driver)
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.sensor_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    xyz_ = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount, "mount");
    rpy_ = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount_rpy_deg, "mount_rpy_deg", true);
    silence_ = SilenceWatch("lidar" + std::to_string(id_), s.silent_after_s);
    try {
      source_.emplace(source_settings(ctx, s));
    } catch (const std::runtime_error& e) {
      throw BadInput("parameter 'source': " + std::string(e.what()));
    }
    io_ = ports().connect(ctx);
    device_failure_.watch(ctx, source_->fd(), source_->reopens());
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    for (StampedCloud& c : source_->poll(now)) publish(ctx, std::move(c)), silence_.heard(now);
    device_failure_.check(ctx, source_->device_error(), source_->fd(), "frames");
    silence_.check(ctx, now, !source_->replay_finished());
  }

  void deactivate(Context& ctx) override { report_ouster(ctx, *source_, frames_, silence_.silences(), wire_); }

 private:
  void publish(Context& ctx, StampedCloud c) {
    constexpr double kDeg = M_PI / 180;
    auto m = std::make_shared<msgs::PointCloud>();
    m->header().stamp_ns(c.stamp_ns);
    m->header().seq(frames_++);
    m->header().frame_id("lidar_" + std::to_string(id_));
    m->sensor_id(id_);
    m->sensor_x(xyz_[0]), m->sensor_y(xyz_[1]), m->sensor_z(xyz_[2]);
    m->sensor_roll(rpy_[0] * kDeg), m->sensor_pitch(rpy_[1] * kDeg), m->sensor_yaw(rpy_[2] * kDeg);
    m->x(std::move(c.cloud.x)), m->y(std::move(c.cloud.y)), m->z(std::move(c.cloud.z)), m->intensity(std::move(c.cloud.intensity));
    m->time_offset(std::move(c.time_offset_s));
    wire_.add(ctx.now_ns(), c.arrival_ns);  // as it is handed to its port (LatencySpread)
    io_.cloud.publish(std::shared_ptr<const msgs::PointCloud>(std::move(m)));
  }

  std::uint8_t id_ = 0;
  std::array<double, 3> xyz_{}, rpy_{};
  std::optional<OusterSource> source_;
  Ports io_;
  std::uint32_t frames_ = 0;
  SilenceWatch silence_;
  LatencySpread wire_;
  DeviceFailure device_failure_;
};

}  // namespace

BRICKYARD_PLUGINS(OusterLidar)
