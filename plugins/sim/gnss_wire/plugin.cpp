// sim.gnss_wire: the simulator's receiver speaking its real wire. Each fix of a simulated
// receiver (sim.gnss, map frame) goes out as the NovAtel OEM7 BESTPOS binary log a receiver would
// send (latitude and longitude by the datum, its sigmas, its fix type; the header's GPS time the
// fix's measurement time plus `gps_start_s`; with `bestvel` and `inspvax` its BESTVEL and the SPAN
// INS's INSPVAX beside it, the car's motion from `truth`), and each sample of a simulated IMU (sim.imu, when
// wired) as the RAWIMUSX log a SPAN receiver sends (its counts by the `imu_*` scale), down the
// `sink`: a UDP port or a TCP listener. drivers.gnss on the other end reads them as it reads a
// car's receiver (docs/drivers.md).
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/plugin.hpp>

#include "drivers/common/gnss_report.hpp"
#include "drivers/common/novatel_oem7.hpp"
#include "newest.hpp"
#include "sim/gnss_wire/params.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::drivers;

struct Ports {
  Input<msgs::GnssFix> fix;
  Input<msgs::Imu> imu;
  Input<msgs::VehicleState> truth;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("fix", &Ports::fix).doc("the simulated receiver's fixes, map frame").depth(64).steps();
  b.input("imu", &Ports::imu).doc("the simulated IMU's samples, vehicle frame (needs the imu_* scale)").optional().depth(64).steps();
  b.input("truth", &Ports::truth).doc("the car's motion, for BESTVEL and INSPVAX (their parameters)").optional().depth(1);
  return b;
}

class GnssWire : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.gnss_wire", "1.0.0")
        .describe("a simulated receiver's fixes sent as NovAtel OEM7 BESTPOSB logs (and BESTVELB, INSPVAXB) down a UDP port or a TCP listener, as a car's receiver sends them")
        .with_ports(ports())
        .parameters(bindings())
        .check(&check);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    datum_.emplace(read_datum_param(s.datum));
    gps_start_ms_ = std::llround(s.gps_start_s * 1000);
    imu_ = s.imu, imu_type_ = static_cast<std::uint8_t>(s.imu_type);
    std::string error;
    sink_ = open_sink(*parse_source(s.sink).spec, error);
    if (!sink_) throw BadInput("parameter 'sink': " + error);
    io_ = ports().connect(ctx);
    if (io_.imu.connected() && !imu_.set()) throw BadInput("parameter 'imu_accel_per_count': the imu input is wired: imu_accel_per_count, imu_gyro_per_count and imu_rate_hz are needed");
    bestvel_ = s.bestvel, inspvax_ = s.inspvax;
    if ((bestvel_ || inspvax_) && !io_.truth.connected())
      throw BadInput(std::string("parameter '") + (bestvel_ ? "bestvel" : "inspvax") + "': needs the car's motion: wire its input 'truth'");
  }

  void step(Context& ctx) override {
    for (const auto& f : io_.fix.take()) send(*f);
    for (const auto& v : io_.imu.take()) send(*v);
    if (!sink_->error().empty() && !error_logged_) ctx.log(LogLevel::error, "sink " + sink_->error()), error_logged_ = true;
  }

  void deactivate(Context& ctx) override {
    ctx.metric("logs_sent", static_cast<double>(sent_));
    ctx.metric("bytes_dropped", static_cast<double>(sink_->dropped()));
  }

 private:
  void send(const msgs::GnssFix& f) {
    const std::int64_t ms = gps_start_ms_ + f.header().stamp_ns() / 1000000;
    const GpsTime t{static_cast<std::uint32_t>(ms / 604800000), static_cast<double>(ms % 604800000) / 1000};
    GnssFixValues v;
    v.x = f.x(), v.y = f.y(), v.z = f.z();
    v.sigma_x = f.sigma_x(), v.sigma_y = f.sigma_y(), v.sigma_z = f.sigma_z();
    v.fix_type = f.fix_type(), v.valid = f.valid();
    send_log(encode_oem7_binary(bestpos_of(v, *datum_, t)));
    if (!bestvel_ && !inspvax_) return;
    const auto car = plugins::newest(io_.truth);
    if (!car) return;  // (no motion known yet: the fix alone)
    // (from the newest truth at the fix's step; an antenna's velocity differs by the yaw rate times
    // its lever arm, up to 0.5 m/s in a turn: left out)
    const MotionValues m = motion_of_car(car->vx(), car->vy(), car->yaw(), car->roll(), car->pitch());
    if (bestvel_) send_log(encode_oem7_binary(bestvel_of(v, m, t)));
    if (inspvax_) send_log(encode_oem7_binary(inspvax_of(v, m, *datum_, t)));
  }

  void send_log(const std::vector<std::uint8_t>& log) {
    if (sink_->send(log.data(), log.size())) ++sent_;
  }

  void send(const msgs::Imu& m) {
    ImuValues v;
    v.accel = {m.accel_x(), m.accel_y(), m.accel_z()};
    v.gyro = {m.gyro_x(), m.gyro_y(), m.gyro_z()};
    v.device_time_ns = gps_start_ms_ * 1000000 + m.header().stamp_ns();
    send_log(encode_oem7_binary(raw_imu_of(v, imu_, imu_type_)));
  }

  std::optional<LocalDatum> datum_;
  std::int64_t gps_start_ms_ = 0;
  RawImuScale imu_;
  std::uint8_t imu_type_ = 0;
  std::unique_ptr<ByteSink> sink_;
  Ports io_;
  std::uint64_t sent_ = 0;
  bool error_logged_ = false, bestvel_ = false, inspvax_ = false;
};

}  // namespace

BRICKYARD_PLUGINS(GnssWire)
