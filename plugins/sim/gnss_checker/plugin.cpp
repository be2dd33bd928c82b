// sim.gnss_checker: an assertion node for tests. Checks every GNSS fix against the ground truth
// at the same instant: fix = antenna position + the expected fault offset (bias / drift windows,
// same syntax as sim.gnss faults), within a tolerance. Fails the run on the first mismatch. With
// `stamp_tolerance_s`, a fix that crossed a wire (drivers.gnss) is held against the truth within
// that much of its stamp that it matches best, and how far its stamp was off is measured.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/plugin.hpp>

#include <cmath>
#include <cstdio>
#include <map>

#include "vehicle_param.hpp"
#include "sim/common/rng.hpp"
#include "sim/sensor_faults.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

// The windows whose offsets are expected, over (x, y, z).
const std::vector<std::string> kFaultTypes = {"bias", "drift"};

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "gnss_left";
  std::vector<double> antenna;  // empty: the vehicle file's mount
  FaultSchedule faults{"[]", 3, kFaultTypes};  // as declared: no window
  double tolerance_m = 1e-9;
  std::int64_t min_checked = 1;
  double stamp_tolerance_s = 0;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its antennas sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the antenna's mount in the vehicle file");
  b.bind("antenna", &Settings::antenna).in_unit("m").range(-100, 100).doc("the receiver's antenna in base_link, m; empty: the vehicle file's vehicle_mount");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]").doc("expected offsets: bias and drift windows as given to sim.gnss"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 3, kFaultTypes); });
  b.bind("tolerance_m", &Settings::tolerance_m).in_unit("m").range(0, 100);
  b.bind("min_checked", &Settings::min_checked).range(0, 1e9);
  b.bind("stamp_tolerance_s", &Settings::stamp_tolerance_s).in_unit("s").range(0, 1)
      .doc("0: the truth at the fix's stamp; else the truth within this of it that the fix matches best (its stamp's error measured)");
  return b;
}

struct Ports {
  Input<msgs::VehicleState> truth;
  Input<msgs::GnssFix> fix;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("ground truth").depth(4096);
  b.input("fix", &Ports::fix).doc("fixes to check").depth(64).steps();
  return b;
}

class GnssChecker : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.gnss_checker", "1.0.0")
        .describe("Test assertion: GNSS fixes equal the antenna's true position plus the expected fault offset")
        .with_ports(ports())
        .parameters(bindings())
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const auto a = plugins::sensor_place(car, s.vehicle, s.vehicle_mount, "vehicle_mount", s.antenna, "antenna");
    antenna_ = {a[0], a[1], a[2]};
    expect_ = s.faults;
    tol_ = s.tolerance_m;
    min_checked_ = s.min_checked;
    stamp_tol_ns_ = std::llround(s.stamp_tolerance_s * 1e9);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (const auto& s : io_.truth.take()) {
      truth_at_[stamp(*s)] = s;
      if (truth_at_.size() > 512) truth_at_.erase(truth_at_.begin());
    }
    for (const auto& f : io_.fix.take()) check(ctx, *f);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("checked", static_cast<double>(checked_));
    ctx.metric("checked_in_windows", static_cast<double>(in_window_));
    ctx.metric("max_error_m", max_err_);
    ctx.metric("max_stamp_error_s", static_cast<double>(max_stamp_err_ns_) * 1e-9);
    if (checked_ < min_checked_)
      ctx.fail("checked " + std::to_string(checked_) + " fixes, expected at least " + std::to_string(min_checked_));
  }

 private:
  // The fix against the truth at its stamp (or, within stamp_tol_ns_, where it matches best).
  void check(Context& ctx, const msgs::GnssFix& f) {
    const std::int64_t at = f.header().stamp_ns();
    double err = INFINITY;
    std::int64_t best = at;
    for (auto it = truth_at_.lower_bound(at - stamp_tol_ns_); it != truth_at_.end() && it->first <= at + stamp_tol_ns_; ++it) {
      const double e = error_at(f, *it->second, static_cast<double>(it->first) * 1e-9);
      if (e < err) err = e, best = it->first;
    }
    if (!std::isfinite(err)) return;
    max_err_ = std::max(max_err_, err);
    max_stamp_err_ns_ = std::max<std::int64_t>(max_stamp_err_ns_, std::llabs(at - best));
    ++checked_;
    const double t = static_cast<double>(at) * 1e-9;
    bool in_window = false;
    for (const auto& w : expect_.windows()) in_window = in_window || w.active(t);
    if (in_window) ++in_window_;
    if (err > tol_) {
      char b[200];
      std::snprintf(b, sizeof b, "fix at t = %.3f s is %.3g m from the expected position (tolerance %.3g m)", t, err, tol_);
      ctx.fail(b);
    }
  }

  double error_at(const msgs::GnssFix& f, const msgs::VehicleState& truth, double t) const {
    Rng unused;
    const FaultEffect e = expect_.at(t, unused);
    const Eigen::Vector3d want = body_pose(truth) * antenna_ + Eigen::Vector3d(e.offset[0], e.offset[1], e.offset[2]);
    return (Eigen::Vector3d(f.x(), f.y(), f.z()) - want).norm();
  }

  Eigen::Vector3d antenna_;
  FaultSchedule expect_;
  double tol_ = 1e-9, max_err_ = 0;
  std::int64_t min_checked_ = 1, checked_ = 0, in_window_ = 0, stamp_tol_ns_ = 0, max_stamp_err_ns_ = 0;
  std::map<std::int64_t, std::shared_ptr<const msgs::VehicleState>> truth_at_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(GnssChecker)
