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

#include "../common/localizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::estimation;

template <class T> double stamp_s(const T& m) { return static_cast<double>(m.header().stamp_ns()) * 1e-9; }

Manifest common_manifest(Manifest m) {
  return m.input<msgs::Imu>("imu", "IMU: the yaw rate drives the prediction", true, 256)
      .input<msgs::WheelSpeeds>("wheels", "wheel speeds: the rear axle's speed drives the prediction", true, 256)
      .input<msgs::GnssFix>("gnss0", "fixes of the first receiver", true, 64)
      .input<msgs::GnssFix>("gnss1", "fixes of the second receiver (optional)", false, 64)
      .output<msgs::LocalizationEstimate>("estimate", "pose, covariance, the update case, delta per receiver, status")
      .output<msgs::ModeStatus>("mode", "the localization manager's status, on change and at 10 Hz")
      .param(ParamSpec::numbers("antenna0", {1.606, 0.05, 1.0}).doc("first receiver's antenna in base_link, m (x, y, z)"))
      .param(ParamSpec::numbers("antenna1", {1.606, -0.05, 1.0}).doc("second receiver's antenna in base_link, m (x, y, z)"))
      .param(ParamSpec::number("roll_filter_s", 1.0).in_unit("s").at_least(0).doc("time constant of the roll taken from the IMU; 0: roll not used"))
      .param(ParamSpec::number("speed_sigma", 0.05).in_unit("m/s").at_least(0).doc("wheel speed input noise"))
      .param(ParamSpec::number("gyro_sigma", 0.002).in_unit("rad/s").at_least(0).doc("yaw rate input noise"))
      .param(ParamSpec::number("process_position", 0.05).in_unit("m/sqrt(s)").at_least(0))
      .param(ParamSpec::number("process_yaw", 0.002).in_unit("rad/sqrt(s)").at_least(0))
      .param(ParamSpec::number("process_slip_gain", 1e-4).in_unit("s^2/m/sqrt(s)").at_least(0))
      .param(ParamSpec::number("init_distance", 5).in_unit("m").at_least(0.5).doc("travel before the heading is taken from the fixes"))
      .param(ParamSpec::number("emergency_after_s", 0.3).in_unit("s").at_least(0).doc("every receiver rejected or silent this long: EMERGENCY"))
      .param(ParamSpec::number("recover_after_s", 1.0).in_unit("s").at_least(0).doc("hysteresis: a level clears after this long without its cause"))
      .param(ParamSpec::number("fix_timeout_s", 0.25).in_unit("s").at_least(0.01).doc("a receiver silent this long counts as rejected"))
      .on_input("imu");
}

template <Policy P> class Estimator : public Plugin {
 public:
  static Manifest manifest() {
    if constexpr (P == Policy::resilient)
      return common_manifest(Manifest("estimation.resilient_fusion", "1.0.0")
                                 .describe("multi-GNSS Kalman filter with the paper's Bayesian update selection (eps, delta) and the localization manager"))
          .param(ParamSpec::number("epsilon_m", 0.2).in_unit("m").at_least(0).doc("every fix within this: all qualified (weighting paper: the closest one alone)"))
          .param(ParamSpec::number("delta_m", 5.0).in_unit("m").at_least(0).doc("fixes beyond this are rejected"))
          .param(ParamSpec::string("weighting", "likelihood").one_of({"likelihood", "paper"})
                     .doc("weights: likelihood (exp(-max(0, d^2 - 9)/2), d Mahalanobis) or paper (1 - delta/sum); docs/algorithms.md"));
    else if constexpr (P == Policy::gated)
      return common_manifest(Manifest("estimation.ekf_gated", "1.0.0")
                                 .describe("baseline: the same filter with a per-receiver chi-square gate (robot_localization style)"))
          .param(ParamSpec::number("gate_chi2", 13.816).at_least(0).doc("squared Mahalanobis threshold (2 dof; 13.8 = 99.9 %)"));
    else
      return common_manifest(Manifest("estimation.ekf_naive", "1.0.0").describe("baseline: the same filter fusing every fix"));
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    LocalizerParams lp;
    lp.policy = P;
    for (int r = 0; r < 2; ++r) {
      const auto& a = p.numbers(r == 0 ? "antenna0" : "antenna1");
      if (a.size() != 3) throw BadInput(std::string("parameter 'antenna") + char('0' + r) + "': needs 3 numbers (x, y, z)");
      lp.lever[r] = {a[0], a[1], a[2]};
    }
    lp.noise.speed = p.number("speed_sigma");
    lp.noise.yaw_rate = p.number("gyro_sigma");
    lp.noise.position = p.number("process_position");
    lp.noise.yaw = p.number("process_yaw");
    lp.noise.slip_gain = p.number("process_slip_gain");
    lp.init_distance = p.number("init_distance");
    lp.roll_filter_s = p.number("roll_filter_s");
    if constexpr (P == Policy::resilient) {
      lp.selection.epsilon = p.number("epsilon_m");
      lp.selection.delta = p.number("delta_m");
      epsilon_ = lp.selection.epsilon;
      delta_ = lp.selection.delta;
      if (lp.selection.epsilon > lp.selection.delta)
        throw BadInput("parameter 'epsilon_m' (" + std::to_string(lp.selection.epsilon) + ") must not exceed 'delta_m' (" +
                       std::to_string(lp.selection.delta) + ")");
      lp.selection.weighting = p.string("weighting") == "paper" ? Weighting::paper : Weighting::likelihood;
    }
    if constexpr (P == Policy::gated) lp.selection.gate_chi2 = p.number("gate_chi2");
    imu_ = ctx.input<msgs::Imu>("imu");
    wheels_ = ctx.input<msgs::WheelSpeeds>("wheels");
    gnss_[0] = ctx.input<msgs::GnssFix>("gnss0");
    gnss_[1] = ctx.input<msgs::GnssFix>("gnss1");
    receivers_ = gnss_[1].connected() ? 2 : 1;
    lp.manager.receivers = receivers_;
    lp.manager.emergency_after_s = p.number("emergency_after_s");
    lp.manager.recover_after_s = p.number("recover_after_s");
    lp.manager.fix_timeout_s = p.number("fix_timeout_s");
    loc_.emplace(lp);
    for (int r = 0; r < 2; ++r) lever_[r] = lp.lever[r];
    estimate_ = ctx.output<msgs::LocalizationEstimate>("estimate");
    mode_ = ctx.output<msgs::ModeStatus>("mode");
  }

  void step(Context& ctx) override {
    // Events in time order: IMU samples and epochs of fixes (one stamp each).
    std::multimap<double, Event> events;
    for (auto& m : imu_.take()) events.emplace(stamp_s(*m), Event{m, {}});
    for (int r = 0; r < receivers_; ++r)
      for (auto& f : gnss_[r].take()) events.emplace(stamp_s(*f), Event{nullptr, f});
    for (auto& w : wheels_.take()) loc_->speed(0.5 * (w->rear_left() + w->rear_right()));
    std::vector<Fix> epoch;
    double epoch_t = -1;
    for (auto& [t, e] : events) {
      if (e.imu) {
        loc_->fixes(epoch_t, epoch);
        epoch.clear();
        loc_->imu(t, e.imu->gyro_z(), e.imu->accel_y());
        continue;
      }
      if (t != epoch_t) {
        loc_->fixes(epoch_t, epoch);
        epoch.clear();
      }
      epoch_t = t;
      if (!e.fix->valid()) continue;  // "no fix": the receiver counts as silent
      Fix f;
      f.receiver = e.fix->receiver_id() < 2 && receivers_ == 2 ? e.fix->receiver_id() : 0;
      f.antenna = {e.fix->x(), e.fix->y()};
      f.lever = lever_[f.receiver];
      f.sigma = std::max(e.fix->sigma_x(), e.fix->sigma_y());
      epoch.push_back(f);
    }
    loc_->fixes(epoch_t, epoch);
    publish(ctx);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("epochs", static_cast<double>(loc_->epochs()));
    ctx.metric("fixes_rejected", static_cast<double>(loc_->rejected()));
    ctx.metric("epochs_single", static_cast<double>(loc_->epochs_of(UpdateCase::single)));
    ctx.metric("epochs_weighted", static_cast<double>(loc_->epochs_of(UpdateCase::weighted)));
    ctx.metric("epochs_partial", static_cast<double>(loc_->epochs_of(UpdateCase::partial)));
    ctx.metric("epochs_rejected", static_cast<double>(loc_->epochs_of(UpdateCase::rejected)));
    ctx.metric("time_warning_s", time_in_[1]);
    ctx.metric("time_emergency_s", time_in_[2]);
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
      mode_.publish(std::move(m));
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
    estimate_.publish(std::move(e));
  }

  std::optional<Localizer> loc_;
  Eigen::Vector3d lever_[2];
  int receivers_ = 2;
  double time_in_[3] = {0, 0, 0}, last_publish_ = -1, last_mode_ = -1;
  Status last_status_ = Status::normal;
  double epsilon_ = 0, delta_ = 0;
  std::uint32_t seq_ = 0, mode_seq_ = 0;
  Input<msgs::Imu> imu_;
  Input<msgs::WheelSpeeds> wheels_;
  Input<msgs::GnssFix> gnss_[2];
  Output<msgs::LocalizationEstimate> estimate_;
  Output<msgs::ModeStatus> mode_;
};

using ResilientFusion = Estimator<Policy::resilient>;
using EkfNaive = Estimator<Policy::naive>;
using EkfGated = Estimator<Policy::gated>;

}  // namespace

BRICKYARD_PLUGINS(ResilientFusion, EkfNaive, EkfGated)
