// estimation.resilient_fusion, estimation.ekf_naive, estimation.ekf_gated: one pose filter
// (common/pose_filter) predicted by the IMU's yaw rate and the rear wheel speeds, corrected by two
// GNSS receivers; the three differ only in how an epoch of fixes is used
// (common/update_selection) — same ports and params, so a graph swaps them by plugin name.
// Each publishes a LocalizationEstimate per IMU sample and the localization manager's ModeStatus.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "../common/epoch_gather.hpp"
#include "../common/localizer.hpp"
#include "vehicle_param.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::estimation;

template <class T> double stamp_s(const T& m) { return static_cast<double>(m.header().stamp_ns()) * 1e-9; }

// One binding for the three estimators: their ports are the same.
struct Ports {
  Input<msgs::Imu> imu;
  Input<msgs::WheelSpeeds> wheels;
  std::array<Input<msgs::GnssFix>, 2> gnss;
  Input<msgs::LocalizationEstimate> scan_pose;
  Output<msgs::LocalizationEstimate> estimate;
  Output<msgs::ModeStatus> mode;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("imu", &Ports::imu).doc("IMU: the yaw rate drives the prediction").depth(256).steps();
  b.input("wheels", &Ports::wheels).doc("wheel speeds: the rear axle's speed drives the prediction").depth(256);
  b.inputs("gnss", &Ports::gnss).doc("fixes of one receiver each: gnss0 the first, gnss1 the second (optional)")
      .required_first(1).depth(64);
  b.input("scan_pose", &Ports::scan_pose)
      .doc("a second estimate of the pose (the scan mapper's), taken while GNSS is degraded (optional)").optional();
  b.output("estimate", &Ports::estimate).doc("pose, covariance, the update case, delta per receiver, status");
  b.output("mode", &Ports::mode).doc("the localization manager's status, on change and at 10 Hz");
  return b;
}

// What the graph says: the car's file and where on it the antennas sit, and the filter's own
// parameters.
struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  std::vector<double> antenna0, antenna1;  // empty: the mount's place in the vehicle file
  std::string antenna0_mount = "gnss_left", antenna1_mount = "gnss_right";
  double epoch_pair_s = 0.01, epoch_wait_s = 0.05;
  LocalizerParams loc;
};

// The three estimators' parameters: the common ones, then their policy's.
template <Policy P> ParamBinding<Settings> bindings() {
  using L = LocalizerParams;
  using N = FilterNoise;
  using M = ManagerParams;
  using S = PolicyParams;
  Settings defaults;
  defaults.loc.policy = P;
  ParamBinding<Settings> b(defaults);
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its GNSS antennas sit");
  b.bind("antenna0", &Settings::antenna0).in_unit("m").range(-100, 100).doc("first receiver's antenna in base_link, m (x, y, z); empty: antenna0_mount's");
  b.bind("antenna1", &Settings::antenna1).in_unit("m").range(-100, 100).doc("second receiver's antenna in base_link, m (x, y, z); empty: antenna1_mount's");
  b.bind("antenna0_mount", &Settings::antenna0_mount).doc("the first receiver's mount in the vehicle file");
  b.bind("antenna1_mount", &Settings::antenna1_mount).doc("the second receiver's mount in the vehicle file");
  b.bind("roll_filter_s", &Settings::loc, &L::roll_filter_s).in_unit("s").range(0, 3600).doc("time constant of the roll taken from the IMU; 0: roll not used");
  b.bind("speed_sigma", &Settings::loc, &L::noise, &N::speed).in_unit("m/s").range(0, 100)
      .doc("wheel speed input noise");
  b.bind("gyro_sigma", &Settings::loc, &L::noise, &N::yaw_rate).in_unit("rad/s").range(0, 10).doc("yaw rate input noise");
  b.bind("process_position", &Settings::loc, &L::noise, &N::position).in_unit("m/sqrt(s)").range(0, 100);
  b.bind("process_yaw", &Settings::loc, &L::noise, &N::yaw).in_unit("rad/sqrt(s)").range(0, 10);
  b.bind("process_slip_gain", &Settings::loc, &L::noise, &N::slip_gain).in_unit("s^2/m/sqrt(s)").range(0, 10);
  b.bind("scan_pose", &Settings::loc, &L::scan_pose)
      .doc("with scan_pose wired: its registered poses are position updates while no fix has been accepted for scan_after_s (docs/mapping.md)");
  b.bind("scan_after_s", &Settings::loc, &L::scan_after_s).in_unit("s").range(0, 3600).doc("GNSS degraded: no fix accepted for this long");
  b.bind("scan_min_sigma", &Settings::loc, &L::scan_min_sigma).in_unit("m").range(0.001, 100).doc("floor on a scan pose's spread");
  b.bind("epoch_pair_s", &Settings::epoch_pair_s).in_unit("s").range(0, 1)
      .doc("real clock: two receivers' fixes stamped this close are one epoch (each carried from its own stamp)");
  b.bind("epoch_wait_s", &Settings::epoch_wait_s).in_unit("s").range(0, 1)
      .doc("real clock: how long a receiver's fix waits for the other receiver's of its epoch");
  b.bind("init_distance", &Settings::loc, &L::init_distance).in_unit("m").range(0.5, 1000).doc("travel before the heading is taken from the fixes");
  b.bind("emergency_after_s", &Settings::loc, &L::manager, &M::emergency_after_s).in_unit("s").range(0, 3600)
      .doc("every receiver rejected or silent this long: EMERGENCY");
  b.bind("recover_after_s", &Settings::loc, &L::manager, &M::recover_after_s).in_unit("s").range(0, 3600)
      .doc("hysteresis: a level clears after this long without its cause");
  b.bind("fix_timeout_s", &Settings::loc, &L::manager, &M::fix_timeout_s).in_unit("s").range(0.01, 3600).doc("a receiver silent this long counts as rejected");
  if constexpr (P == Policy::resilient) {
    b.bind("epsilon_m", &Settings::loc, &L::selection, &S::epsilon).in_unit("m").range(0, 1000)
        .doc("every fix within this: all qualified (weighting paper: the closest one alone)");
    b.bind("delta_m", &Settings::loc, &L::selection, &S::delta).in_unit("m").range(0, 1000).doc("fixes beyond this are rejected");
    b.bind_choice("weighting", {{"likelihood", Weighting::likelihood}, {"paper", Weighting::paper}}, &Settings::loc, &L::selection, &S::weighting)
        .doc("weights: likelihood (exp(-max(0, d^2 - 9)/2), d Mahalanobis) or paper (1 - delta/sum); docs/algorithms.md");
    using R = ReacquireParams;
    b.bind("reacquire", &Settings::loc, &L::reacquire, &R::enabled)
        .doc("after an outage that left every fix beyond delta: take the fixes' position (and the heading the fit finds) again once the receivers agree with each other and with the motion model (docs/algorithms.md)");
    b.bind("reacquire_agree_m", &Settings::loc, &L::reacquire, &R::agree_m).in_unit("m").range(0.01, 100)
        .doc("the receivers' base_link positions within this of each other");
    b.bind("reacquire_motion_m", &Settings::loc, &L::reacquire, &R::motion_m).in_unit("m").range(0.01, 100)
        .doc("the dead-reckoned path, moved and turned onto the fixes' path, within this of it at every epoch of the window");
    b.bind("reacquire_max_turn", &Settings::loc, &L::reacquire, &R::max_turn).in_unit("rad").range(0, 3.14)
        .doc("the largest heading error the fit may correct");
    b.bind("reacquire_min_span_m", &Settings::loc, &L::reacquire, &R::min_span_m).in_unit("m").range(0.1, 1000)
        .doc("below this much travel in the window the turn cannot be told: taken as zero");
    b.bind("reacquire_window_s", &Settings::loc, &L::reacquire, &R::window_s).in_unit("s").range(0.05, 60)
        .doc("both held this long before the position is taken");
    b.not_above("epsilon_m", "delta_m");
  } else if constexpr (P == Policy::gated) {
    b.bind("gate_chi2", &Settings::loc, &L::selection, &S::gate_chi2).range(0, 1e6).doc("squared Mahalanobis threshold (2 dof; 13.8 = 99.9 %)");
  }
  return b;
}

template <Policy P> class Estimator : public Plugin {
 public:
  static Manifest manifest() {
    if constexpr (P == Policy::resilient)
      return Manifest("estimation.resilient_fusion", "1.0.0")
          .describe("multi-GNSS Kalman filter with the paper's Bayesian update selection (eps, delta) and the localization manager")
          .with_ports(ports())
          .plays(roles::estimator)
          .parameters(bindings<P>());
    else if constexpr (P == Policy::gated)
      return Manifest("estimation.ekf_gated", "1.0.0")
          .describe("baseline: the same filter with a per-receiver chi-square gate (robot_localization style)")
          .with_ports(ports())
          .plays(roles::estimator)
          .parameters(bindings<P>());
    else
      return Manifest("estimation.ekf_naive", "1.0.0")
          .describe("baseline: the same filter fusing every fix")
          .with_ports(ports())
          .plays(roles::estimator)
          .parameters(bindings<P>());
  }

  void configure(Context& ctx) override {
    const Settings set = bindings<P>().read(ctx.params());
    LocalizerParams lp = set.loc;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, set.vehicle);
    for (int r = 0; r < 2; ++r) {
      const std::string which = std::string("antenna") + char('0' + r);
      const auto a = plugins::sensor_place(car, set.vehicle, r == 0 ? set.antenna0_mount : set.antenna1_mount, which + "_mount",
                                           r == 0 ? set.antenna0 : set.antenna1, which);
      lp.lever[r] = {a[0], a[1], a[2]};
    }
    epsilon_ = lp.selection.epsilon;
    delta_ = lp.selection.delta;
    io_ = ports().connect(ctx);
    receivers_ = io_.gnss[1].connected() ? 2 : 1;
    // On the sim clock a step sees every fix stamped up to now: an epoch is whole within a step.
    if (!ctx.sim_clock() && receivers_ == 2) gather_.emplace(receivers_, set.epoch_pair_s, set.epoch_wait_s);
    lp.manager.receivers = receivers_;
    loc_.emplace(lp);
    for (int r = 0; r < 2; ++r) lever_[r] = lp.lever[r];
  }

  void step(Context& ctx) override {
    // Events in time order: IMU samples and epochs of fixes (one stamp each).
    std::multimap<double, Event> events;
    for (auto& m : io_.imu.take()) events.emplace(stamp_s(*m), Event{m, {}});
    for (int r = 0; r < receivers_; ++r)
      for (auto& f : io_.gnss[r].take()) events.emplace(stamp_s(*f), Event{nullptr, f});
    for (auto& w : io_.wheels.take()) loc_->speed(0.5 * (w->rear_left() + w->rear_right()));
    auto fix_of = [&](const msgs::GnssFix& m) {
      Fix f;
      f.receiver = m.receiver_id() < 2 && receivers_ == 2 ? m.receiver_id() : 0;
      f.antenna = {m.x(), m.y()};
      f.lever = lever_[f.receiver];
      f.sigma = std::max(m.sigma_x(), m.sigma_y());
      return f;
    };
    std::vector<Fix> epoch;
    double epoch_t = -1, latest = -1;
    for (auto& [t, e] : events) {
      latest = std::max(latest, t);
      if (e.imu) {
        loc_->fixes(epoch_t, epoch);
        epoch.clear();
        loc_->imu(t, e.imu->gyro_z(), e.imu->accel_y());
        continue;
      }
      if (!e.fix->valid()) continue;  // "no fix": the receiver counts as silent
      if (gather_) {  // the real clock: the epoch's other receiver may come in a later step
        gather_->add(t, fix_of(*e.fix));  // finite: the stamp is whole nanoseconds
        continue;
      }
      if (t != epoch_t) {
        loc_->fixes(epoch_t, epoch);
        epoch.clear();
      }
      epoch_t = t;
      epoch.push_back(fix_of(*e.fix));
    }
    loc_->fixes(epoch_t, epoch);
    if (gather_)
      for (auto& e : gather_->release(latest)) loc_->fixes(e.t, e.fixes);
    // The scan mapper's poses, each of a LiDAR frame a sweep and a registration ago: only those
    // it registered (update case 2), moved to now by dead reckoning's motion since.
    for (auto& s : io_.scan_pose.take()) {
      if (s->update_case() != 2) continue;
      Eigen::Matrix2d cov;
      cov << s->covariance()[0], s->covariance()[1], s->covariance()[3], s->covariance()[4];
      loc_->scan_pose(stamp_s(*s), {s->x(), s->y()}, cov);
    }
    publish(ctx);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("epochs", static_cast<double>(loc_->epochs()));
    ctx.metric("fixes_rejected", static_cast<double>(loc_->rejected()));
    ctx.metric("malformed_samples", static_cast<double>(loc_->malformed()));
    ctx.metric("fixes_late", static_cast<double>(loc_->late()));
    ctx.metric("fixes_too_late", static_cast<double>(loc_->too_late()));
    ctx.metric("fix_late_max_s", loc_->late_max_s());
    ctx.metric("epochs_single", static_cast<double>(loc_->epochs_of(UpdateCase::single)));
    ctx.metric("epochs_weighted", static_cast<double>(loc_->epochs_of(UpdateCase::weighted)));
    ctx.metric("epochs_partial", static_cast<double>(loc_->epochs_of(UpdateCase::partial)));
    ctx.metric("epochs_rejected", static_cast<double>(loc_->epochs_of(UpdateCase::rejected)));
    ctx.metric("time_warning_s", time_in_[1]);
    ctx.metric("time_emergency_s", time_in_[2]);
    if constexpr (P == Policy::resilient) ctx.metric("reacquisitions", static_cast<double>(loc_->reacquisitions()));
    if (io_.scan_pose.connected()) {
      ctx.metric("scan_updates", static_cast<double>(loc_->scan_updates()));
      ctx.metric("scan_refused", static_cast<double>(loc_->scan_refused()));
    }
    if constexpr (P == Policy::resilient) {  // the thresholds, for the report's Δk figure
      ctx.metric("epsilon_m", epsilon_);
      ctx.metric("delta_m", delta_);
    }
  }

 private:
  struct Event {
    std::shared_ptr<const msgs::Imu> imu;
    std::shared_ptr<const msgs::GnssFix> fix;
  };

  void publish(Context& ctx) {
    const double now = ctx.now_s();
    const Status s = loc_->status(now);
    const PoseFilter& filter = loc_->filter();
    if (last_publish_ >= 0) time_in_[static_cast<int>(s)] += now - last_publish_;
    last_publish_ = now;
    if (s != last_status_ || now - last_mode_ >= 0.1 - 1e-9) {
      msgs::ModeStatus m;
      m.header().stamp_ns(ctx.now_ns());
      m.header().seq(mode_seq_++);
      m.mode(static_cast<std::uint8_t>(s));
      m.mode_name(status_name(s));
      if (s != last_status_ || mode_seq_ == 1) ctx.status("localization", status_name(s));
      m.reason(filter.initialized() ? loc_->manager().reason() : "initializing: waiting for the car to move");
      io_.mode.publish(std::move(m));
      last_mode_ = now;
      last_status_ = s;
    }
    if (!filter.initialized()) return;
    msgs::LocalizationEstimate e;
    e.header().stamp_ns(ctx.now_ns());
    e.header().seq(seq_++);
    e.header().frame_id("map");
    const auto& x = filter.state();
    const auto& cov = filter.cov();
    e.x(x(PoseFilter::X));
    e.y(x(PoseFilter::Y));
    e.yaw(x(PoseFilter::YAW));
    e.speed(x(PoseFilter::SPEED));
    e.yaw_rate(x(PoseFilter::YAW_RATE));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) e.covariance()[3 * i + j] = cov(i, j);
    auto [which, delta] = loc_->take_epoch_summary();
    e.update_case(static_cast<std::uint8_t>(which));
    e.delta(delta);
    e.status(static_cast<std::uint8_t>(s));
    io_.estimate.publish(std::move(e));
  }

  std::optional<Localizer> loc_;
  std::optional<EpochGather> gather_;  // the real clock only
  Eigen::Vector3d lever_[2];
  int receivers_ = 2;
  double time_in_[3] = {0, 0, 0}, last_publish_ = -1, last_mode_ = -1;
  Status last_status_ = Status::normal;
  double epsilon_ = 0, delta_ = 0;
  std::uint32_t seq_ = 0, mode_seq_ = 0;
  Ports io_;
};

using ResilientFusion = Estimator<Policy::resilient>;
using EkfNaive = Estimator<Policy::naive>;
using EkfGated = Estimator<Policy::gated>;

}  // namespace

BRICKYARD_PLUGINS(ResilientFusion, EkfNaive, EkfGated)
