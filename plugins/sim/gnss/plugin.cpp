// sim.gnss: one GNSS receiver. Samples the ground truth at its antenna (lever arm from base_link),
// adds RTK noise, reports a sigma, and applies the fault windows of its `faults` parameter.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/plugin.hpp>

#include <optional>

#include "vehicle_param.hpp"
#include "sim/common/gnss_receiver.hpp"
#include "sim/sensor_faults.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::uint8_t receiver_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "gnss_left";
  std::vector<double> antenna;  // empty: the vehicle file's mount
  GnssNoise noise;
  FaultSchedule faults{"[]", 3, kGnssFaultTypes};  // as declared: no window
};

ParamBinding<Settings> bindings() {
  using N = GnssNoise;
  ParamBinding<Settings> b;
  b.bind("receiver_id", &Settings::receiver_id).range(0, 255);
  b.declare(ParamSpec::number("rate_hz", 20).in_unit("Hz").range(0.1, 1000));  // the host's trigger only
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its antennas sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the antenna's mount in the vehicle file");
  b.bind("antenna", &Settings::antenna).in_unit("m").range(-100, 100)
      .doc("antenna position in base_link, m (x, y, z); empty: the vehicle file's vehicle_mount");
  b.bind("sigma_m", &Settings::noise, &N::sigma_m).in_unit("m").range(0, 100).doc("horizontal noise, 1 sigma (RTK fixed: 1-2 cm)");
  b.bind("sigma_z_m", &Settings::noise, &N::sigma_z_m).in_unit("m").range(0, 100);
  b.bind("reported_sigma_m", &Settings::noise, &N::reported_sigma_m).in_unit("m").range(-100, 100)
      .doc("sigma the receiver reports; < 0: sigma_m");
  b.bind("fix_type", &Settings::noise, &N::fix_type).range(0, 3).doc("0 none, 1 single, 2 float RTK, 3 fixed RTK");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]")
                  .doc("fault windows: bias, drift, noise, freeze, dropout, spikes, sigma (see docs/simulator.md)"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 3, kGnssFaultTypes); });
  return b;
}

struct Ports {
  Input<msgs::VehicleState> truth;
  Output<msgs::GnssFix> fix;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("ground truth").depth(1);
  b.output("fix", &Ports::fix).doc("position fixes in the map frame");
  return b;
}

class Gnss : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.gnss", "1.0.0")
        .describe("GNSS receiver (NovAtel PwrPak7 on the AV-21): antenna position with RTK noise and fault windows")
        .with_ports(ports())
        .plays(roles::gnss_driver)
        .parameters(bindings())
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.receiver_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto a = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.antenna, "antenna");
    receiver_.emplace(Eigen::Vector3d(a[0], a[1], a[2]), s.noise, s.faults, Rng(ctx.seed()));
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    auto s = newest(io_.truth);
    if (!s) return;
    const BodyState truth{s->x(), s->y(), s->z(), s->yaw(), s->pitch(), s->roll(), s->vx(), s->vy(), s->yaw_rate()};
    const std::int64_t stamp_ns = ctx.now_ns();
    const GnssReceiver::Epoch e = receiver_->epoch(stamp_ns, truth, stamp(*s), run_.start_ns(ctx));
    if (e == GnssReceiver::Epoch::frozen) publish(*last_, stamp_ns);
    if (e != GnssReceiver::Epoch::fresh) return;
    const GnssFixValues& f = receiver_->fix();
    msgs::GnssFix m;
    m.header().frame_id("map");
    m.receiver_id(id_);
    m.x(f.x);
    m.y(f.y);
    m.z(f.z);
    m.sigma_x(f.sigma_x);
    m.sigma_y(f.sigma_y);
    m.sigma_z(f.sigma_z);
    m.fix_type(static_cast<std::uint8_t>(f.fix_type));
    m.valid(f.valid);
    last_ = std::make_shared<msgs::GnssFix>(publish(std::move(m), stamp_ns));
  }

  void deactivate(Context& ctx) override {
    ctx.metric("fixes", static_cast<double>(receiver_->fixes()));
    ctx.metric("digest", receiver_->digest());
  }

 private:
  // The fix goes out stamped and numbered; returns what went out.
  msgs::GnssFix publish(msgs::GnssFix m, std::int64_t stamp_ns) {
    m.header().stamp_ns(stamp_ns);
    m.header().seq(seq_++);
    io_.fix.publish(m);
    return m;
  }

  std::uint8_t id_ = 0;
  std::optional<GnssReceiver> receiver_;
  std::uint32_t seq_ = 0;
  std::shared_ptr<msgs::GnssFix> last_;
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(Gnss)
