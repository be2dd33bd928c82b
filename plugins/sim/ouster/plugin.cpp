// sim.ouster: an Ouster LiDAR on its wire. Across each rotation, a packet's columns are cast
// against the world from the car's true pose when they are measured, pixel by pixel in the
// directions the sensor's metadata JSON gives (common/ouster_emulator.hpp), written as a lidar
// packet of the metadata's profile and sent down a UDP port, as the sensor sends them:
// drivers.ouster_lidar on the other end reads them as it reads the sensor. The sensor's clock is
// the run's. docs/simulator.md, "An Ouster on its wire".
#include <brickyard/plugin.hpp>

#include "drivers/common/ouster_packet_encode.hpp"
#include "sim/common/ouster_emulator.hpp"
#include "sim/ouster/params.hpp"
#include "sim/world_msg.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Ports {
  Input<msgs::TrackWorld> world;
  Input<msgs::VehicleState> truth;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world to scan").depth(1);
  b.input("truth", &Ports::truth).doc("the car's pose").depth(1);
  return b;
}

class Ouster : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.ouster", "1.0.0")
        .describe("an Ouster LiDAR from its metadata JSON: rotations cast against the world, sent as its lidar packets over UDP")
        .with_ports(ports())
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    metadata_ = read_setup(ctx, s);
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto m = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount, "mount");
    const auto r = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.mount_rpy_deg, "mount_rpy_deg", true);
    params_ = s.sensor;
    constexpr double kDeg = M_PI / 180;
    params_.body_from_sensor = Eigen::Translation3d(m[0], m[1], m[2]) * Eigen::AngleAxisd(r[2] * kDeg, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(r[1] * kDeg, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(r[0] * kDeg, Eigen::Vector3d::UnitX());
    std::string error;
    sink_ = drivers::open_sink(*drivers::parse_source(s.sink).spec, error);
    if (!sink_) throw BadInput("parameter 'sink': " + error);
    rng_ = Rng(ctx.seed());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!sensor_) {
      const auto w = newest(io_.world);
      if (!w) return;
      track_ = std::make_unique<Track>(from_message(*w));
      sensor_.emplace(*track_, metadata_, params_);
    }
    const auto car = newest(io_.truth);
    if (!car) return;
    const std::int64_t now = ctx.now_ns();
    // Every packet due is measured and sent (a slow step: several, of rotations back to back).
    for (;;) {
      if (packet_ == packets_) {
        if (now < next_rotation_ns_) break;
        begin_rotation(now);
      }
      if (due_ns(packet_) > now) break;
      send_packet(*car);
    }
    if (!sink_->error().empty() && !error_logged_) ctx.log(LogLevel::error, "sink " + sink_->error()), error_logged_ = true;
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("packets_sent", static_cast<double>(sent_));
    ctx.metric("bytes_dropped", static_cast<double>(sink_ ? sink_->dropped() : 0));
    ctx.metric("rays", static_cast<double>(rays_));
  }

 private:
  // A rotation at the sensor's own pace (the first when a pose is known).
  void begin_rotation(std::int64_t now) {
    rotation_start_ns_ = next_rotation_ns_ < 0 ? now : next_rotation_ns_;
    next_rotation_ns_ = rotation_start_ns_ + std::llround(1e9 / metadata_.frames_per_second);
    sensor_->begin(static_cast<std::uint64_t>(rotation_start_ns_), frame_id_++, frame_);
    packets_ = drivers::ouster_packets_per_frame(metadata_), packet_ = 0;
    ++frames_;
  }

  // The window's columns of packet k.
  int first_column(int k) const { return k * metadata_.columns_per_packet; }
  int end_column(int k) const { return std::min(first_column(k + 1), metadata_.columns_in_window()); }
  // Packet k goes when its last column has been measured.
  std::int64_t due_ns(int k) const { return rotation_start_ns_ + std::llround(sensor_->column_end_ns(end_column(k) - 1)); }

  // The next packet's columns cast from where the car is now, and the packet sent.
  void send_packet(const msgs::VehicleState& car) {
    rays_ += sensor_->cast_columns(body_pose(car), car.x(), car.y(), first_column(packet_), end_column(packet_), rng_, frame_);
    const std::vector<std::uint8_t> packet = drivers::encode_ouster_packet(frame_, metadata_, packet_++);
    if (sink_->send(packet.data(), packet.size())) ++sent_;
  }

  drivers::OusterMetadata metadata_;
  OusterEmulatorParams params_;
  std::unique_ptr<Track> track_;
  std::optional<OusterEmulator> sensor_;
  drivers::OusterFrame frame_;
  int packets_ = 0, packet_ = 0;  // of the rotation in progress: all sent when equal
  std::int64_t rotation_start_ns_ = 0;
  std::unique_ptr<drivers::ByteSink> sink_;
  Rng rng_;
  std::int64_t next_rotation_ns_ = -1;
  std::uint16_t frame_id_ = 0;
  std::uint64_t frames_ = 0, sent_ = 0, rays_ = 0;
  bool error_logged_ = false;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Ouster)
