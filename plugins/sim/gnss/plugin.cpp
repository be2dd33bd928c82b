// sim.gnss: one GNSS receiver. Samples the ground truth at its antenna (lever arm from base_link),
// adds RTK noise, reports a sigma, and applies the fault windows of its `faults` parameter.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"
#include "../common/digest.hpp"
#include "../common/rng.hpp"
#include "../sensor_faults.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

// The fault windows a receiver takes, over (x, y, z).
const std::vector<std::string> kFaultTypes = {"bias", "drift", "noise", "freeze", "dropout", "spikes", "sigma"};

struct Settings {
  std::uint8_t receiver_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "gnss_left";
  std::vector<double> antenna;  // empty: the vehicle file's mount
  double sigma_m = 0.015, sigma_z_m = 0.03, reported_sigma_m = -1;
  int fix_type = 3;
  FaultSchedule faults{"[]", 3, kFaultTypes};  // as declared: no window
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("receiver_id", &Settings::receiver_id).range(0, 255);
  b.declare(ParamSpec::number("rate_hz", 20).in_unit("Hz").range(0.1, 1000));  // the host's trigger only
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its antennas sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the antenna's mount in the vehicle file");
  b.bind("antenna", &Settings::antenna).in_unit("m").range(-100, 100)
      .doc("antenna position in base_link, m (x, y, z); empty: the vehicle file's vehicle_mount");
  b.bind("sigma_m", &Settings::sigma_m).in_unit("m").range(0, 100).doc("horizontal noise, 1 sigma (RTK fixed: 1-2 cm)");
  b.bind("sigma_z_m", &Settings::sigma_z_m).in_unit("m").range(0, 100);
  b.bind("reported_sigma_m", &Settings::reported_sigma_m).in_unit("m").range(-100, 100)
      .doc("sigma the receiver reports; < 0: sigma_m");
  b.bind("fix_type", &Settings::fix_type).range(0, 3).doc("0 none, 1 single, 2 float RTK, 3 fixed RTK");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]")
                  .doc("fault windows: bias, drift, noise, freeze, dropout, spikes, sigma (see docs/simulator.md)"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 3, kFaultTypes); });
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
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    id_ = s.receiver_id;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto a = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.antenna, "antenna");
    antenna_ = {a[0], a[1], a[2]};
    sigma_ = s.sigma_m;
    sigma_z_ = s.sigma_z_m;
    reported_ = s.reported_sigma_m < 0 ? sigma_ : s.reported_sigma_m;
    fix_type_ = s.fix_type;
    faults_ = s.faults;
    rng_ = Rng(ctx.seed());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    auto s = newest(io_.truth);
    if (!s) return;
    // The position at the fix's stamp. On the sim clock the newest truth is of this instant; on
    // the real clock it is a millisecond or two old (the car's step ran before), and the car moves
    // 8 cm in 2 ms at 40 m/s: the truth is carried to the stamp by the car's motion.
    const std::int64_t stamp_ns = ctx.now_ns();
    if (const double dt = static_cast<double>(stamp_ns - stamp(*s)) * 1e-9; dt != 0) {
      auto at = std::make_shared<msgs::VehicleState>(*s);
      const double c = std::cos(s->yaw()), sn = std::sin(s->yaw());
      at->x(s->x() + (c * s->vx() - sn * s->vy()) * dt);
      at->y(s->y() + (sn * s->vx() + c * s->vy()) * dt);
      at->yaw(s->yaw() + s->yaw_rate() * dt);
      s = at;
    }
    const double t = ctx.now_s();
    // Noise is drawn every epoch, faulty or not, so a fault window leaves the rest of the run's
    // noise sequence as it would have been.
    const double n[3] = {rng_.normal(), rng_.normal(), rng_.normal()};
    FaultEffect e = faults_.at(t, rng_);
    if (e.drop) return;
    if (e.freeze && last_) {
      msgs::GnssFix m = *last_;
      m.header().stamp_ns(stamp_ns);
      m.header().seq(seq_++);
      io_.fix.publish(std::move(m));
      return;
    }
    const Eigen::Vector3d p = body_pose(*s) * antenna_;
    msgs::GnssFix m;
    m.header().stamp_ns(stamp_ns);
    m.header().seq(seq_++);
    m.header().frame_id("map");
    m.receiver_id(id_);
    m.x(p.x() + e.offset[0] + sigma_ * e.noise_factor * n[0]);
    m.y(p.y() + e.offset[1] + sigma_ * e.noise_factor * n[1]);
    m.z(p.z() + e.offset[2] + sigma_z_ * e.noise_factor * n[2]);
    m.sigma_x(reported_ * e.sigma_factor);
    m.sigma_y(reported_ * e.sigma_factor);
    m.sigma_z(reported_ * e.sigma_factor * (sigma_ > 0 ? sigma_z_ / sigma_ : 1.0));
    int ft = e.fix_type.value_or(fix_type_);
    m.fix_type(static_cast<std::uint8_t>(ft));
    m.valid(ft > 0);
    for (double v : {m.x(), m.y(), m.z(), m.sigma_x()}) digest_.add(v);
    last_ = std::make_shared<msgs::GnssFix>(m);
    ++fixes_;
    io_.fix.publish(std::move(m));
  }

  void deactivate(Context& ctx) override {
    ctx.metric("fixes", static_cast<double>(fixes_));
    ctx.metric("digest", digest_.hex());
  }

 private:
  std::uint8_t id_ = 0;
  Digest digest_;
  std::uint64_t fixes_ = 0;
  Eigen::Vector3d antenna_;
  double sigma_ = 0, sigma_z_ = 0, reported_ = 0;
  int fix_type_ = 3;
  FaultSchedule faults_;
  Rng rng_;
  std::uint32_t seq_ = 0;
  std::shared_ptr<msgs::GnssFix> last_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Gnss)
