// drivers.gnss: a GNSS receiver on its wire (NovAtel OEM7 logs, binary or ASCII, or NMEA 0183) to
// GnssFix in the map frame. The device is polled without blocking each period (`rate_hz` bounds
// the delay a fix waits); a recorded log replays at its own pace. A receiver silent for longer
// than `silent_after_s` is reported (the estimator sees no fix: the receiver is lost to it).
// Formats, the datum and the time rule: docs/drivers-formats.md; the devices: docs/drivers-transports.md.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/plugin.hpp>

#include "drivers/driver_metrics.hpp"
#include "drivers/gnss_source.hpp"
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
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind_required("source", &Settings::source).doc(kSourceDoc);
  b.bind_choice("protocol", {{"novatel_oem7", GnssProtocol::novatel_oem7}, {"nmea0183", GnssProtocol::nmea0183}}, &Settings::protocol);
  b.bind_choice("position_log", {{"BESTPOS", Oem7PositionLog::bestpos}, {"INSPVAX", Oem7PositionLog::inspvax}}, &Settings::position_log)
      .doc("OEM7: the receiver's position (BESTPOS) or the INS's (INSPVAX)");
  b.bind("receiver_id", &Settings::receiver_id).range(0, 255);
  b.bind_required("datum", &Settings::datum).doc("the map frame's origin: latitude, longitude (deg, WGS84), height above the ellipsoid (m)");
  b.bind("device_time", &Settings::device_time).doc("stamp each fix at its measurement by the receiver's time (else at receipt)");
  b.bind("silent_after_s", &Settings::silent_after_s).in_unit("s").range(0.01, 60).doc("no fix for this long: the receiver is reported silent");
  b.declare(ParamSpec::number("rate_hz", 500).in_unit("Hz").range(1, 10000).doc("how often the device is polled"));
  return b;
}

// The settings checked, the files found: at validation and at configure alike.
template <class Files> GnssSourceSettings source_settings(const Files& files, const Settings& s) {
  GnssSourceSettings g;
  g.source = parse_source_param(s.source);
  if (g.source.kind == SourceSpec::Kind::pcap) throw BadInput("parameter 'source': " + s.source + ": a GNSS log is read with file://, not pcap://");
  if (g.source.kind == SourceSpec::Kind::file) g.file_path = files.find_file(g.source.path);
  if (s.datum.size() != 3) throw BadInput("parameter 'datum': " + std::to_string(s.datum.size()) + " numbers, not 3 (latitude, longitude, height)");
  g.stream.datum = {s.datum[0], s.datum[1], s.datum[2]};
  if (const std::string why = datum_problem(g.stream.datum); !why.empty()) throw BadInput("parameter 'datum': " + why);
  g.stream.protocol = s.protocol;
  g.stream.position_log = s.position_log;
  g.device_time = s.device_time;
  return g;
}

void check(const CheckView& v) { source_settings(v, bindings().read(v.params())); }

struct Ports {
  Output<msgs::GnssFix> fix;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("fix", &Ports::fix).doc("position fixes in the map frame, stamped at their measurement");
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
    silent_after_ns_ = static_cast<std::int64_t>(s.silent_after_s * 1e9);
    try {
      source_.emplace(source_settings(ctx, s));
    } catch (const std::runtime_error& e) {
      throw BadInput("parameter 'source': " + std::string(e.what()));
    }
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    if (first_step_ns_ < 0) first_step_ns_ = now;
    for (const StampedFix& f : source_->poll(now)) publish(f, now);
    if (!source_->device_error().empty() && !device_error_logged_) {
      ctx.log(LogLevel::error, "source " + source_->device_error() + ": no more fixes from it");
      device_error_logged_ = true;
    }
    watch_silence(ctx, now);
  }

  void deactivate(Context& ctx) override { report_gnss(ctx, *source_, fixes_, silences_); }

 private:
  void publish(const StampedFix& f, std::int64_t now) {
    msgs::GnssFix m;
    m.header().stamp_ns(f.stamp_ns);
    m.header().seq(fixes_++);
    m.header().frame_id("map");
    m.receiver_id(id_);
    m.x(f.fix.x), m.y(f.fix.y), m.z(f.fix.z);
    m.sigma_x(f.fix.sigma_x), m.sigma_y(f.fix.sigma_y), m.sigma_z(f.fix.sigma_z);
    m.fix_type(f.fix.fix_type);
    m.valid(f.fix.valid);
    io_.fix.publish(std::move(m));
    last_fix_ns_ = now;
    silent_ = false;
  }

  // Silent: no fix for silent_after_s since the last one (or since the start): said once a silence.
  void watch_silence(Context& ctx, std::int64_t now) {
    const std::int64_t since = last_fix_ns_ >= 0 ? last_fix_ns_ : first_step_ns_;
    if (silent_ || source_->replay_finished() || now - since < silent_after_ns_) return;
    silent_ = true;
    ++silences_;
    ctx.log(LogLevel::warn, "receiver " + std::to_string(id_) + " silent: no fix for " + std::to_string((now - since) / 1000000) + " ms");
    ctx.status("gnss" + std::to_string(id_), "silent");
  }

  std::uint8_t id_ = 0;
  std::optional<GnssSource> source_;
  Ports io_;
  std::uint32_t fixes_ = 0;
  std::int64_t silent_after_ns_ = 0, last_fix_ns_ = -1, first_step_ns_ = -1;
  bool silent_ = false, device_error_logged_ = false;
  std::uint64_t silences_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(GnssDriver)
