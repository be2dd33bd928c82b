// estimation.resilient_fusion, estimation.ekf_naive, estimation.ekf_gated: one pose filter
// (common/pose_filter) predicted by the IMU's yaw rate and the rear wheel speeds, corrected by two
// GNSS receivers; the three differ only in how an epoch of fixes is used
// (common/update_selection) — same ports and params, so a graph swaps them by plugin name.
// Each publishes a LocalizationEstimate per IMU sample (the pose at the step's time) and the
// localization manager's ModeStatus.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/plugin.hpp>

#include "estimation/common/estimator_report.hpp"
#include "estimation/common/sample_feed.hpp"
#include "params.hpp"
#include "ports.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::estimation;

template <class T> double stamp_s(const T& m) { return static_cast<double>(m.header().stamp_ns()) * 1e-9; }

template <Policy P> class Estimator : public Plugin {
 public:
  static Manifest manifest() {
    const bool resilient = P == Policy::resilient, gated = P == Policy::gated;
    const char* name = resilient ? "estimation.resilient_fusion" : gated ? "estimation.ekf_gated" : "estimation.ekf_naive";
    const char* about =
        resilient ? "multi-GNSS Kalman filter with the paper's Bayesian update selection (eps, delta) and the localization manager"
        : gated   ? "baseline: the same filter with a per-receiver chi-square gate (robot_localization style)"
                  : "baseline: the same filter fusing every fix";
    return Manifest(name, "1.0.0").describe(about).with_ports(ports()).plays(roles::estimator).parameters(bindings<P>())
        .check(&plugins::check_vehicle_file<&bindings<P>, &Settings::vehicle>);
  }

  void configure(Context& ctx) override {
    const Settings set = bindings<P>().read(ctx.params());
    LocalizerParams lp = set.loc;
    place_antennas(ctx, set, lp.lever);
    selection_ = lp.selection;
    carry_max_s_ = set.carry_max_s;
    io_ = ports().connect(ctx);
    lp.manager.receivers = io_.gnss[1].connected() ? 2 : 1;
    receivers_ = {lp.manager.receivers, {lp.lever[0], lp.lever[1]}};
    // On the sim clock a step sees every fix stamped up to now: an epoch is whole within a step.
    if (!ctx.sim_clock() && receivers_.count == 2) gather_.emplace(receivers_.count, set.epoch_pair_s, set.epoch_wait_s);
    loc_.emplace(lp);
  }

  void step(Context& ctx) override {
    std::vector<ImuSample> imu;
    for (auto& m : io_.imu.take()) imu.push_back({stamp_s(*m), m->gyro_z(), m->accel_y()});
    std::vector<GnssSample> gnss;
    for (int r = 0; r < receivers_.count; ++r)
      for (auto& f : io_.gnss[r].take())
        gnss.push_back({stamp_s(*f), f->valid(), receivers_.fix(f->receiver_id(), {f->x(), f->y()}, f->sigma_x(), f->sigma_y())});
    for (auto& w : io_.wheels.take()) loc_->speed(0.5 * (w->rear_left() + w->rear_right()));
    feed_in_time_order(*loc_, gather_ ? &*gather_ : nullptr, imu, gnss);
    std::vector<ScanPoseSample> scan;
    for (auto& s : io_.scan_pose.take()) {
      const auto& c = s->covariance();  // row-major over x, y, yaw: its x, y block
      scan.push_back({stamp_s(*s), s->update_case(), {s->x(), s->y()}, (Eigen::Matrix2d() << c[0], c[1], c[3], c[4]).finished()});
    }
    feed_scan_poses(*loc_, scan);
    if (!mismatch_said_ && (mismatch_said_ = loc_->witness().mismatch()))
      ctx.log(LogLevel::error, "the map does not match the track (never located on it in agreement with GNSS): not used, the car stays on GNSS");
    const Status s = loc_->status(ctx.now_s());
    publish_mode(ctx, s);
    if (loc_->filter().initialized()) publish_estimate(ctx, s);
  }

  void deactivate(Context& ctx) override {
    for (const auto& [name, value] : summary_metrics(*loc_, modes_, P, io_.scan_pose.connected(), selection_)) ctx.metric(name, value);
    ctx.metric("estimates_carried", static_cast<double>(carried_));
    ctx.metric("estimate_carried_max_s", carried_max_s_);
  }

 private:
  void publish_mode(Context& ctx, Status s) {
    const ModeDue due = modes_.step(ctx.now_s(), s);
    if (!due.publish) return;
    msgs::ModeStatus m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(due.seq);
    m.mode(static_cast<std::uint8_t>(s));
    m.mode_name(status_name(s));
    if (due.announce) ctx.status("localization", status_name(s));
    m.reason(loc_->filter().initialized() ? loc_->manager().reason() : "initializing: waiting for the car to move");
    io_.mode.publish(std::move(m));
  }

  void publish_estimate(Context& ctx, Status s) {
    msgs::LocalizationEstimate e;
    const Localizer::Pose pose = loc_->pose_at(ctx.now_s(), carry_max_s_);
    carried_max_s_ = std::max(carried_max_s_, pose.carried_s);
    carried_ += pose.carried_s > 0;
    e.header().stamp_ns(ctx.now_ns() - std::llround(pose.short_s * 1e9));
    e.header().seq(seq_++);
    e.header().frame_id("map");
    const auto& x = loc_->filter().state();
    const auto& cov = loc_->filter().cov();
    e.x(pose.x);
    e.y(pose.y);
    e.yaw(pose.yaw);
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
  Receivers receivers_;
  PolicyParams selection_;
  ModeCadence modes_;
  std::uint32_t seq_ = 0;
  double carry_max_s_ = 0, carried_max_s_ = 0;  // the first set by configure
  std::uint64_t carried_ = 0;
  bool mismatch_said_ = false;
  Ports io_;
};

using ResilientFusion = Estimator<Policy::resilient>;
using EkfNaive = Estimator<Policy::naive>;
using EkfGated = Estimator<Policy::gated>;

}  // namespace

BRICKYARD_PLUGINS(ResilientFusion, EkfNaive, EkfGated)
