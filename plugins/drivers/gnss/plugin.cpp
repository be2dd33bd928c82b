// drivers.gnss: a GNSS receiver on its wire (NovAtel OEM7 logs, binary or ASCII, or NMEA 0183) to
// GnssFix in the map frame, and a SPAN receiver's RAWIMUSX to Imu in the vehicle frame. On the real
// clock the node wakes as the device has bytes (and polls it each period besides); a recorded log
// replays at its own pace. A receiver silent for `silent_after_s` is reported (the estimator sees
// no fix: it is lost to it). Formats, the datum, the IMU's scale, the time rule: docs/drivers.md.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/plugin.hpp>

#include "drivers/datum_param.hpp"
#include "drivers/device_failure.hpp"
#include "drivers/driver_metrics.hpp"
#include "drivers/gnss_source.hpp"
#include "drivers/silence_watch.hpp"
#include "drivers/source_param.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::drivers;

struct Settings {
  std::string source;
  GnssProtocol protocol = GnssProtocol::novatel_oem7;
  Oem7PositionLog position_log = Oem7PositionLog::bestpos;
  std::uint8_t receiver_id = 0;
  std::vector<double> datum;
  bool device_time = true;
  double silent_after_s = 0.25;
  RawImuScale imu;
  std::vector<double> imu_rpy_deg{0, 0, 0};
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind_required("source", &Settings::source).doc(kSourceDoc);
  b.bind_choice("protocol", {{"novatel_oem7", GnssProtocol::novatel_oem7}, {"nmea0183", GnssProtocol::nmea0183}}, &Settings::protocol);
  b.bind_choice("position_log", {{"BESTPOS", Oem7PositionLog::bestpos}, {"INSPVAX", Oem7PositionLog::inspvax}}, &Settings::position_log)
      .doc("OEM7: the receiver's position (BESTPOS) or the INS's (INSPVAX)");
  b.bind("receiver_id", &Settings::receiver_id).range(0, 255);
  b.bind_required("datum", &Settings::datum).range(-1000, 10000).doc("the map frame's origin: latitude, longitude (deg, WGS84), height above the ellipsoid (m)");
  b.bind("device_time", &Settings::device_time).doc("stamp each message at its measurement by the receiver's time (else at receipt)");
  b.bind("silent_after_s", &Settings::silent_after_s).in_unit("s").range(0.01, 60).doc("no fix for this long: the receiver is reported silent");
  b.bind("imu_accel_per_count", &Settings::imu, &RawImuScale::accel_per_count).in_unit("m/s").range(0, 1)
      .doc("RAWIMUSX: the IMU's velocity scale factor (NovAtel's Raw IMU Scale Factors table); 0: IMU samples dropped");
  b.bind("imu_gyro_per_count", &Settings::imu, &RawImuScale::gyro_per_count).in_unit("rad").range(0, 1).doc("RAWIMUSX: the angle scale factor");
  b.bind("imu_rate_hz", &Settings::imu, &RawImuScale::rate_hz).in_unit("Hz").range(0, 10000).doc("RAWIMUSX: the IMU's output rate");
  b.bind("imu_rpy_deg", &Settings::imu_rpy_deg).in_unit("deg").range(-360, 360).doc("the IMU body frame's roll, pitch, yaw in the vehicle's");
  b.declare(ParamSpec::number("rate_hz", 500).in_unit("Hz").range(1, 10000).doc("how often the device is polled (on the real clock the node also wakes as bytes arrive)"));
  return b;
}

// The settings checked, the files found: at validation and at configure alike.
template <class Files> GnssSourceSettings source_settings(const Files& files, const Settings& s) {
  GnssSourceSettings g;
  g.source = parse_source_param(s.source);
  if (g.source.kind == SourceSpec::Kind::pcap) throw BadInput("parameter 'source': " + s.source + ": a GNSS log is read with file://, not pcap://");
  if (g.source.kind == SourceSpec::Kind::file) g.file_path = files.find_file(g.source.path);
  g.stream.datum = read_datum_param(s.datum);
  if (s.imu_rpy_deg.size() != 3) throw BadInput("parameter 'imu_rpy_deg': needs 3 numbers (roll, pitch, yaw)");
  g.stream.imu = s.imu;
  g.stream.imu.imu_to_vehicle = imu_mount(s.imu_rpy_deg[0], s.imu_rpy_deg[1], s.imu_rpy_deg[2]);
  g.stream.protocol = s.protocol, g.stream.position_log = s.position_log, g.device_time = s.device_time;
  return g;
}

void check(const CheckView& v) { source_settings(v, bindings().read(v.params())); }

struct Ports {
  Output<msgs::GnssFix> fix;
  Output<msgs::Imu> imu;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("fix", &Ports::fix).doc("position fixes in the map frame, stamped at their measurement");
  b.output("imu", &Ports::imu).doc("RAWIMUSX samples in the vehicle frame (needs the imu_* scale parameters)");
  return b;
}

class GnssDriver : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("drivers.gnss", "1.0.0")
        .describe("a GNSS receiver on its wire (NovAtel OEM7 or NMEA 0183; serial, UDP, TCP or a recorded log) to fixes in the map frame")
        .with_ports(ports())
        .plays(roles::gnss_driver)
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.receiver_id;
    silence_ = SilenceWatch("gnss" + std::to_string(id_), s.silent_after_s);
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
    const GnssPoll got = source_->poll(now);
    for (const StampedFix& f : got.fixes) publish(ctx, f), silence_.heard(now);
    for (const StampedImu& v : got.imu) publish(ctx, v);
    device_failure_.check(ctx, source_->device_error(), source_->fd(), "fixes");
    silence_.check(ctx, now, !source_->replay_finished());
  }

  void deactivate(Context& ctx) override { report_gnss(ctx, *source_, fixes_, silence_.silences(), wire_); }

 private:
  void publish(Context& ctx, const StampedFix& f) {
    msgs::GnssFix m;
    m.header().stamp_ns(f.stamp_ns), m.header().seq(fixes_++), m.header().frame_id("map");
    m.receiver_id(id_), m.x(f.fix.x), m.y(f.fix.y), m.z(f.fix.z);
    m.sigma_x(f.fix.sigma_x), m.sigma_y(f.fix.sigma_y), m.sigma_z(f.fix.sigma_z);
    m.fix_type(f.fix.fix_type), m.valid(f.fix.valid);
    wire_.add(ctx.now_ns(), f.arrival_ns);  // as it is handed to its port (LatencySpread)
    io_.fix.publish(std::move(m));
  }

  void publish(Context& ctx, const StampedImu& v) {
    msgs::Imu m;
    m.header().stamp_ns(v.stamp_ns), m.header().seq(imu_samples_++), m.header().frame_id("base_link");
    m.accel_x(v.imu.accel.x()), m.accel_y(v.imu.accel.y()), m.accel_z(v.imu.accel.z());
    m.gyro_x(v.imu.gyro.x()), m.gyro_y(v.imu.gyro.y()), m.gyro_z(v.imu.gyro.z());
    wire_.add(ctx.now_ns(), v.arrival_ns);
    io_.imu.publish(std::move(m));
  }

  std::uint8_t id_ = 0;
  std::optional<GnssSource> source_;
  Ports io_;
  SilenceWatch silence_;
  LatencySpread wire_;
  std::uint32_t fixes_ = 0, imu_samples_ = 0;
  DeviceFailure device_failure_;
};

}  // namespace

BRICKYARD_PLUGINS(GnssDriver)
