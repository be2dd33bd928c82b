// drivers.ouster_imu: an Ouster sensor's IMU on its wire (the IMU port's packets, or a pcap
// capture's, the sensor's metadata for the IMU's axes) to Imu in the vehicle frame, through the
// sensor's mount on the car. The sensor sends a packet every 10 ms; on the real clock the node
// wakes as packets arrive (and polls the port each period besides); a capture replays at its pace.
// A sensor silent for longer than `silent_after_s` is reported. Formats: docs/drivers-formats.md
// ("IMU packets"); the devices: docs/drivers-transports.md.
#include <brickyard/msgs/Imu.h>
#include <brickyard/plugin.hpp>

#include "drivers/common/raw_imu.hpp"
#include "drivers/device_failure.hpp"
#include "drivers/driver_metrics.hpp"
#include "drivers/ouster_imu_source.hpp"
#include "drivers/ouster_metadata_param.hpp"
#include "drivers/silence_watch.hpp"
#include "drivers/source_param.hpp"
#include "vehicle_param.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::drivers;

struct Settings {
  std::string source = "udp://0.0.0.0:7503";
  std::string metadata;
  std::uint8_t sensor_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "lidar_front";
  std::vector<double> mount_rpy_deg;  // empty: the vehicle file's mount
  bool device_time = true;
  double silent_after_s = 0.1;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("source", &Settings::source).doc(kSourceDoc);
  b.bind_required("metadata", &Settings::metadata).doc("the sensor's metadata JSON (its IMU's axes in the sensor's, its IMU port)");
  b.bind("sensor_id", &Settings::sensor_id).range(0, 255);
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its sensors sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the sensor's mount in the vehicle file (the IMU is inside the sensor)");
  b.bind("mount_rpy_deg", &Settings::mount_rpy_deg).in_unit("deg").range(-360, 360).doc("sensor roll, pitch, yaw, deg; empty: vehicle_mount's");
  b.bind("device_time", &Settings::device_time).doc("stamp each sample at its accelerometer read by the sensor's clock (else at receipt)");
  b.bind("silent_after_s", &Settings::silent_after_s).in_unit("s").range(0.01, 60).doc("no sample for this long: the IMU is reported silent");
  b.declare(ParamSpec::number("rate_hz", 1000).in_unit("Hz").range(1, 10000).doc("how often the port is polled (on the real clock the node also wakes as packets arrive)"));
  return b;
}

template <class Files> OusterImuSourceSettings source_settings(const Files& files, const Settings& s, const std::array<double, 3>& rpy_deg) {
  OusterImuSourceSettings o;
  read_ouster_wire(files, s.source, s.metadata, "an Ouster sensor's IMU", o);
  o.sensor_to_vehicle = imu_mount(rpy_deg[0], rpy_deg[1], rpy_deg[2]);
  o.device_time = s.device_time;
  return o;
}

void check(const CheckView& v) { source_settings(v, bindings().read(v.params()), {0, 0, 0}); }

struct Ports {
  Output<msgs::Imu> imu;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("imu", &Ports::imu).doc("specific force and angular rate in the vehicle frame, one sample a packet");
  return b;
}

class OusterImu : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("drivers.ouster_imu", "1.0.0")
        .describe("an Ouster sensor's IMU on its wire (UDP IMU packets or a pcap capture, the sensor's metadata) to Imu in the vehicle frame")
        .with_ports(ports())
        .plays(roles::imu_driver)
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.sensor_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto rpy = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount_rpy_deg, "mount_rpy_deg", true);
    silence_ = SilenceWatch("lidar" + std::to_string(id_) + "_imu", s.silent_after_s);
    try {
      source_.emplace(source_settings(ctx, s, rpy));
    } catch (const std::runtime_error& e) {
      throw BadInput("parameter 'source': " + std::string(e.what()));
    }
    io_ = ports().connect(ctx);
    device_failure_.watch(ctx, source_->fd(), source_->reopens());
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    for (const StampedOusterImu& sample : source_->poll(now)) publish(ctx, sample), silence_.heard(now);
    device_failure_.check(ctx, source_->device_error(), source_->fd(), "samples");
    silence_.check(ctx, now, !source_->replay_finished());
  }

  void deactivate(Context& ctx) override { report_ouster_imu(ctx, *source_, samples_, silence_.silences(), wire_); }

 private:
  void publish(Context& ctx, const StampedOusterImu& v) {
    msgs::Imu m;
    m.header().stamp_ns(v.stamp_ns), m.header().seq(samples_++), m.header().frame_id("base_link");
    m.accel_x(v.accel.x()), m.accel_y(v.accel.y()), m.accel_z(v.accel.z());
    m.gyro_x(v.gyro.x()), m.gyro_y(v.gyro.y()), m.gyro_z(v.gyro.z());
    wire_.add(ctx.now_ns(), v.arrival_ns);  // as it is handed to its port (LatencySpread)
    io_.imu.publish(std::move(m));
  }

  std::uint8_t id_ = 0;
  std::optional<OusterImuSource> source_;
  Ports io_;
  std::uint32_t samples_ = 0;
  SilenceWatch silence_;
  LatencySpread wire_;
  DeviceFailure device_failure_;
};

}  // namespace

BRICKYARD_PLUGINS(OusterImu)
