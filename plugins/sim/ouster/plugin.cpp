// sim.ouster: an Ouster LiDAR on its wire. Each rotation is cast against the world from the car's
// true pose, pixel by pixel in the directions the sensor's metadata JSON gives
// (common/ouster_emulator.hpp), written as the lidar packets of the metadata's profile, and sent
// down a UDP port across the rotation, a packet when its columns are measured, as the sensor sends
// them: drivers.ouster_lidar on the other end reads them as it reads the sensor. The sensor's
// clock is the run's. docs/simulator.md, "An Ouster on its wire".
#include <brickyard/plugin.hpp>

#include "drivers/common/ouster_packet_encode.hpp"
#include "sim/common/ouster_emulator.hpp"
#include "sim/ouster/params.hpp"
#include "sim/world_msg.hpp"

#include <deque>
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
    const std::int64_t now = ctx.now_ns();
    if (now >= next_rotation_ns_) cast_rotation(now);
    while (!due_.empty() && due_.front().first <= now) {
      const std::vector<std::uint8_t>& packet = due_.front().second;
      if (sink_->send(packet.data(), packet.size())) ++sent_;
      due_.pop_front();
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
  // A rotation from the newest pose, at the sensor's own pace (the first when a pose is known), its
  // packets due as their last column is measured.
  void cast_rotation(std::int64_t now) {
    const auto s = newest(io_.truth);
    if (!s) return;
    const std::int64_t t0 = next_rotation_ns_ < 0 ? now : next_rotation_ns_;
    const double rotation_ns = 1e9 / metadata_.frames_per_second;
    next_rotation_ns_ = t0 + std::llround(rotation_ns);
    rays_ += sensor_->scan(body_pose(*s), s->x(), s->y(), static_cast<std::uint64_t>(t0), frame_id_++, rng_, frame_);
    std::vector<std::vector<std::uint8_t>> packets;
    drivers::encode_ouster_packets(frame_, metadata_, packets);
    const double packet_ns = rotation_ns / static_cast<double>(packets.size());
    for (std::size_t k = 0; k < packets.size(); ++k)
      due_.emplace_back(t0 + std::llround((k + 1) * packet_ns), std::move(packets[k]));
    ++frames_;
  }

  drivers::OusterMetadata metadata_;
  OusterEmulatorParams params_;
  std::unique_ptr<Track> track_;
  std::optional<OusterEmulator> sensor_;
  drivers::OusterFrame frame_;
  std::deque<std::pair<std::int64_t, std::vector<std::uint8_t>>> due_;
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
