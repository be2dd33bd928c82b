// sim.imu: specific force and angular rate in the vehicle frame, with white noise, constant bias
// and fault windows. Mounted at base_link (lever-arm effects are not modelled).
#include <brickyard/msgs/Imu.h>
#include <brickyard/plugin.hpp>

#include "sim/common/digest.hpp"
#include "sim/common/rng.hpp"
#include "sim/sensor_faults.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

// The fault windows an IMU takes, over (ax, ay, az, gx, gy, gz).
const std::vector<std::string> kFaultTypes = {"bias", "drift", "noise", "freeze", "dropout", "spikes"};

struct Settings {
  double accel_noise = 0.05, gyro_noise = 0.002;
  std::vector<double> accel_bias = {0.02, -0.01, 0.0}, gyro_bias = {0.0005, -0.0003, 0.0002};
  FaultSchedule faults{"[]", 6, kFaultTypes};  // as declared: no window
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.declare(ParamSpec::number("rate_hz", 125).in_unit("Hz").range(1, 10000));  // the host's trigger only
  b.bind("accel_noise", &Settings::accel_noise).in_unit("m/s^2").range(0, 100);
  b.bind("gyro_noise", &Settings::gyro_noise).in_unit("rad/s").range(0, 10);
  b.bind("accel_bias", &Settings::accel_bias).in_unit("m/s^2").range(-100, 100).doc("m/s^2, x y z");
  b.bind("gyro_bias", &Settings::gyro_bias).in_unit("rad/s").range(-10, 10).doc("rad/s, x y z");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]")
                  .doc("windows over (ax, ay, az, gx, gy, gz): bias, drift, noise, freeze, dropout, spikes"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 6, kFaultTypes); });
  return b;
}

struct Ports {
  Input<msgs::VehicleState> truth;
  Output<msgs::Imu> imu;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("ground truth").depth(1);
  b.output("imu", &Ports::imu).doc("measurements in the vehicle frame (x forward, y left, z up)");
  return b;
}

class ImuSensor : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.imu", "1.0.0")
        .describe("IMU: specific force (accelerometer) and angular rate (gyro) with noise, bias and fault windows")
        .with_ports(ports())
        .plays(roles::imu_driver)
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    an_ = s.accel_noise;
    gn_ = s.gyro_noise;
    if (s.accel_bias.size() != 3) throw BadInput("parameter 'accel_bias': needs 3 numbers");
    if (s.gyro_bias.size() != 3) throw BadInput("parameter 'gyro_bias': needs 3 numbers");
    for (int i = 0; i < 3; ++i) {
      bias_[i] = s.accel_bias[i];
      bias_[3 + i] = s.gyro_bias[i];
    }
    faults_ = s.faults;
    rng_ = Rng(ctx.seed());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    auto s = newest(io_.truth);
    if (!s) return;
    double n[6];
    for (double& v : n) v = rng_.normal();
    FaultEffect e = faults_.at(run_.now_s(ctx), rng_);
    if (e.drop) return;
    msgs::Imu m;
    if (e.freeze && last_) {
      m = *last_;
    } else {
      // Specific force = acceleration - gravity, in body axes; the car moves in the road plane.
      const Eigen::Matrix3d R = body_pose(*s).linear();
      const Eigen::Vector3d f = Eigen::Vector3d(s->ax(), s->ay(), 0.0) - R.transpose() * Eigen::Vector3d(0, 0, -9.81);
      const double truth[6] = {f.x(), f.y(), f.z(), 0.0, 0.0, s->yaw_rate()};
      double v[6];
      for (int i = 0; i < 6; ++i) v[i] = truth[i] + bias_[i] + e.offset[i] + (i < 3 ? an_ : gn_) * e.noise_factor * n[i];
      m.accel_x(v[0]); m.accel_y(v[1]); m.accel_z(v[2]);
      m.gyro_x(v[3]); m.gyro_y(v[4]); m.gyro_z(v[5]);
    }
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.header().frame_id("vehicle");
    for (double v : {m.accel_x(), m.accel_y(), m.accel_z(), m.gyro_z()}) digest_.add(v);
    last_ = std::make_shared<msgs::Imu>(m);
    io_.imu.publish(std::move(m));
  }

  void deactivate(Context& ctx) override { ctx.metric("digest", digest_.hex()); }

 private:
  Digest digest_;
  double an_ = 0, gn_ = 0, bias_[6] = {};
  FaultSchedule faults_;
  Rng rng_;
  std::uint32_t seq_ = 0;
  std::shared_ptr<msgs::Imu> last_;
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(ImuSensor)
