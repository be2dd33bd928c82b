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

#include "../common/localization_manager.hpp"
#include "../common/update_selection.hpp"

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
          .param(ParamSpec::number("epsilon_m", 0.2).in_unit("m").at_least(0).doc("every fix within this: use one"))
          .param(ParamSpec::number("delta_m", 5.0).in_unit("m").at_least(0).doc("fixes beyond this are rejected"))
          .param(ParamSpec::string("weighting", "likelihood").one_of({"likelihood", "paper"})
                     .doc("weighted cases: likelihood (exp(-d^2/2), d Mahalanobis) or paper (1 - delta/sum); see docs/algorithms.md"));
    else if constexpr (P == Policy::gated)
      return common_manifest(Manifest("estimation.ekf_gated", "1.0.0")
                                 .describe("baseline: the same filter with a per-receiver chi-square gate (robot_localization style)"))
          .param(ParamSpec::number("gate_chi2", 13.816).at_least(0).doc("squared Mahalanobis threshold (2 dof; 13.8 = 99.9 %)"));
    else
      return common_manifest(Manifest("estimation.ekf_naive", "1.0.0").describe("baseline: the same filter fusing every fix"));
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    for (int r = 0; r < 2; ++r) {
      const auto& a = p.numbers(r == 0 ? "antenna0" : "antenna1");
      if (a.size() != 3) throw BadInput(std::string("parameter 'antenna") + char('0' + r) + "': needs 3 numbers (x, y, z)");
      lever_[r] = {a[0], a[1], a[2]};
    }
    FilterNoise n;
    n.speed = p.number("speed_sigma");
    n.yaw_rate = p.number("gyro_sigma");
    n.position = p.number("process_position");
    n.yaw = p.number("process_yaw");
    n.slip_gain = p.number("process_slip_gain");
    filter_ = PoseFilter(n);
    init_distance_ = p.number("init_distance");
    roll_tau_ = p.number("roll_filter_s");
    if constexpr (P == Policy::resilient) {
      policy_.epsilon = p.number("epsilon_m");
      policy_.delta = p.number("delta_m");
      policy_.weighting = p.string("weighting") == "likelihood" ? Weighting::likelihood : Weighting::paper;
      if (policy_.epsilon > policy_.delta)
        throw BadInput("parameter 'epsilon_m' (" + std::to_string(policy_.epsilon) + ") must not exceed 'delta_m' (" +
                       std::to_string(policy_.delta) + ")");
    }
    if constexpr (P == Policy::gated) policy_.gate_chi2 = p.number("gate_chi2");
    imu_ = ctx.input<msgs::Imu>("imu");
    wheels_ = ctx.input<msgs::WheelSpeeds>("wheels");
    gnss_[0] = ctx.input<msgs::GnssFix>("gnss0");
    gnss_[1] = ctx.input<msgs::GnssFix>("gnss1");
    receivers_ = gnss_[1].connected() ? 2 : 1;
    ManagerParams mp;
    mp.receivers = receivers_;
    mp.emergency_after_s = p.number("emergency_after_s");
    mp.recover_after_s = p.number("recover_after_s");
    mp.fix_timeout_s = p.number("fix_timeout_s");
    manager_.emplace(mp);
    estimate_ = ctx.output<msgs::LocalizationEstimate>("estimate");
    mode_ = ctx.output<msgs::ModeStatus>("mode");
  }

  void step(Context& ctx) override {
    // Events in time order: an IMU sample moves the filter to its stamp and sets the yaw rate;
    // an epoch of fixes (one stamp) is applied at its stamp.
    std::multimap<double, Event> events;
    for (auto& m : imu_.take()) events.emplace(stamp_s(*m), Event{m, {}});
    for (int r = 0; r < receivers_; ++r)
      for (auto& f : gnss_[r].take()) events.emplace(stamp_s(*f), Event{nullptr, f});
    for (auto& w : wheels_.take()) speed_ = 0.5 * (w->rear_left() + w->rear_right());
    std::vector<Fix> epoch;
    double epoch_t = -1;
    auto flush = [&] {
      if (epoch.empty()) return;
      advance(epoch_t);
      apply(epoch, epoch_t);
      epoch.clear();
    };
    for (auto& [t, e] : events) {
      if (e.imu) {
        flush();
        advance(t);
        yaw_rate_ = e.imu->gyro_z();
        have_imu_ = true;
        update_roll(*e.imu, t);
      } else {
        if (!epoch.empty() && t != epoch_t) flush();
        epoch_t = t;
        if (!e.fix->valid()) continue;  // "no fix": the receiver counts as silent
        Fix f;
        f.receiver = e.fix->receiver_id() < 2 && receivers_ == 2 ? e.fix->receiver_id() : 0;
        f.antenna = {e.fix->x(), e.fix->y()};
        f.lever = lever_[f.receiver];
        f.sigma = std::max(e.fix->sigma_x(), e.fix->sigma_y());
        epoch.push_back(f);
      }
    }
    flush();
    publish(ctx);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("epochs", static_cast<double>(epochs_));
    ctx.metric("fixes_rejected", static_cast<double>(rejected_));
    ctx.metric("epochs_single", static_cast<double>(cases_[1]));
    ctx.metric("epochs_weighted", static_cast<double>(cases_[2]));
    ctx.metric("epochs_partial", static_cast<double>(cases_[3]));
    ctx.metric("epochs_rejected", static_cast<double>(cases_[4]));
    ctx.metric("time_warning_s", time_in_[1]);
    ctx.metric("time_emergency_s", time_in_[2]);
  }

 private:
  struct Event {
    std::shared_ptr<const msgs::Imu> imu;
    std::shared_ptr<const msgs::GnssFix> fix;
  };

  void advance(double t) {
    if (t_ < 0) t_ = t;
    if (t > t_ && have_imu_) filter_.predict(t - t_, speed_, yaw_rate_);
    t_ = std::max(t_, t);
  }

  // Roll from the lateral specific force of a car cornering in the plane of a banked road:
  // f_y = v * yaw rate + dvy/dt + g sin(roll). dvy/dt is not measured and swings by metres per
  // second squared through a turn's entry and exit, so the estimate is low-passed (roll_filter_s).
  void update_roll(const msgs::Imu& m, double t) {
    if (roll_tau_ <= 0) return;
    const double s = std::clamp((m.accel_y() - speed_ * yaw_rate_) / 9.81, -0.5, 0.5);
    sin_roll_ += (s - sin_roll_) * std::min(1.0, (t - roll_t_) / roll_tau_);
    roll_t_ = t;
    filter_.set_roll(std::asin(sin_roll_));
  }

  void apply(const std::vector<Fix>& epoch, double t) {
    if (!filter_.initialized()) {
      initialize(epoch);
      for (const auto& f : epoch) manager_->on_fix(f.receiver, t, true);
      return;
    }
    EpochResult r = apply_fixes(filter_, epoch, P, policy_);
    ++epochs_;
    ++cases_[static_cast<int>(r.which)];
    last_case_ = r.which;
    last_delta_.assign(receivers_, -1.0);
    for (std::size_t i = 0; i < epoch.size(); ++i) {
      last_delta_[epoch[i].receiver] = r.delta[i];
      manager_->on_fix(epoch[i].receiver, t, r.accepted[i]);
      rejected_ += !r.accepted[i];
    }
  }

  // Position from the fixes; heading from the direction of travel once the car has moved.
  void initialize(const std::vector<Fix>& epoch) {
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    for (const auto& f : epoch) p += f.antenna;
    p /= static_cast<double>(epoch.size());
    if (!first_) {
      first_ = p;
      return;
    }
    const Eigen::Vector2d d = p - *first_;
    if (d.norm() < init_distance_) return;
    const double yaw = std::atan2(d.y(), d.x());
    filter_.init(p.x(), p.y(), yaw, 0.1, 0.05);
    const Eigen::Vector3d lever = 0.5 * (lever_[0] + lever_[receivers_ - 1]);
    const Eigen::Vector2d base = filter_.base_from_antenna(p, lever);
    filter_.init(base.x(), base.y(), yaw, 0.1, 0.05);
  }

  void publish(Context& ctx) {
    const double now = ctx.now_s();
    const Status s = filter_.initialized() ? manager_->update(now) : Status::warning;
    if (last_publish_ >= 0) time_in_[static_cast<int>(s)] += now - last_publish_;
    last_publish_ = now;
    if (s != last_status_ || now - last_mode_ >= 0.1 - 1e-9) {
      msgs::ModeStatus m;
      m.header().stamp_ns(ctx.now_ns());
      m.header().seq(mode_seq_++);
      m.mode(static_cast<std::uint8_t>(s));
      m.mode_name(status_name(s));
      m.reason(filter_.initialized() ? manager_->reason() : "initializing: waiting for the car to move");
      mode_.publish(std::move(m));
      last_mode_ = now;
      last_status_ = s;
    }
    if (!filter_.initialized()) return;
    msgs::LocalizationEstimate e;
    e.header().stamp_ns(ctx.now_ns());
    e.header().seq(seq_++);
    e.header().frame_id("map");
    const auto& x = filter_.state();
    const auto& cov = filter_.cov();
    e.x(x(PoseFilter::X));
    e.y(x(PoseFilter::Y));
    e.yaw(x(PoseFilter::YAW));
    e.speed(x(PoseFilter::SPEED));
    e.yaw_rate(x(PoseFilter::YAW_RATE));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) e.covariance()[3 * i + j] = cov(i, j);
    e.update_case(static_cast<std::uint8_t>(last_case_));
    e.delta(last_delta_);
    e.status(static_cast<std::uint8_t>(s));
    last_case_ = UpdateCase::predict_only;
    last_delta_.assign(receivers_, -1.0);
    estimate_.publish(std::move(e));
  }

  PoseFilter filter_;
  PolicyParams policy_;
  std::optional<LocalizationManager> manager_;
  Eigen::Vector3d lever_[2];
  int receivers_ = 2;
  double init_distance_ = 5, roll_tau_ = 1, sin_roll_ = 0, roll_t_ = 0;
  std::optional<Eigen::Vector2d> first_;
  double t_ = -1, speed_ = 0, yaw_rate_ = 0;
  bool have_imu_ = false;
  UpdateCase last_case_ = UpdateCase::predict_only;
  std::vector<double> last_delta_;
  std::uint64_t epochs_ = 0, rejected_ = 0, cases_[5] = {0, 0, 0, 0, 0};
  double time_in_[3] = {0, 0, 0}, last_publish_ = -1, last_mode_ = -1;
  Status last_status_ = Status::normal;
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
