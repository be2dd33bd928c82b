#include "localizer.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace brickyard::estimation {

Localizer::Localizer(LocalizerParams p)
    : p_(p), filter_(p.noise), manager_(p.manager), last_delta_(std::max(p.manager.receivers, 1), -1.0),
      reacquisition_(p.reacquire), witness_(p.witness), motion_(p.motion) {}

void Localizer::advance(double t) {
  if (t_ < 0) t_ = t;
  if (t > t_ && have_imu_) {
    const double dt = t - t_;
    filter_.predict(dt, speed_ * wheel_scale(), yaw_rate_);
    reckon_with_sideslip(dt);
    // Dead reckoning alone, never corrected: the motion between two times that a late fix or
    // pose is carried by. The filter's own poses would carry the corrections made since as well
    // and count them twice (a 0.2 s late fix in a turn rocks the heading back and forth).
    const double mid = odo_.yaw + 0.5 * yaw_rate_ * dt;
    odo_.x += speed_ * std::cos(mid) * dt;
    odo_.y += speed_ * std::sin(mid) * dt;
    odo_.yaw += yaw_rate_ * dt;
  }
  t_ = std::max(t_, t);
  odo_.t = t_;
  constexpr std::size_t kPast = 200;
  if (past_.size() < kPast) {
    past_.push_back(odo_);
  } else {
    past_[past_next_] = odo_;
    past_next_ = (past_next_ + 1) % kPast;
  }
}

double Localizer::wheel_scale() const { return p_.witness.enabled ? motion_.wheel_scale() : 1.0; }

void Localizer::reckon_with_sideslip(double dt) {
  const double mid = dr_.yaw + 0.5 * yaw_rate_ * dt;
  const double vy = -filter_.state()(PoseFilter::SLIP) * speed_ * speed_ * yaw_rate_;
  const double c = std::cos(mid), s = std::sin(mid);
  dr_.x += (c * speed_ - s * vy) * dt;
  dr_.y += (s * speed_ + c * vy) * dt;
  dr_.yaw += yaw_rate_ * dt;
}

std::optional<Localizer::Motion> Localizer::motion_since(double stamp) const {
  // Dead reckoning's pose at the stamp: the two kept around it, interpolated.
  const Past* before = nullptr;
  const Past* after = nullptr;
  for (const Past& q : past_) {
    if (q.t <= stamp && (!before || q.t > before->t)) before = &q;
    if (q.t >= stamp && (!after || q.t < after->t)) after = &q;
  }
  if (!before || !after) return std::nullopt;  // older than the history, or from the future
  const double f = after->t > before->t ? (stamp - before->t) / (after->t - before->t) : 0.0;
  const Eigen::Vector2d then(before->x + f * (after->x - before->x), before->y + f * (after->y - before->y));
  const double yaw_then = before->yaw + f * (after->yaw - before->yaw);
  // Dead reckoning's frame laid on the filter's now: the filter's position then is its position
  // now less the dead-reckoned travel since, turned by the two frames' heading difference.
  const Eigen::Rotation2Dd align(filter_.state()(PoseFilter::YAW) - odo_.yaw);
  const Eigen::Vector2d travel = Eigen::Vector2d(odo_.x, odo_.y) - then;
  return Motion{filter_.position() - align * travel, odo_.yaw - yaw_then};
}

Eigen::Vector2d Localizer::Motion::carry(const Eigen::Vector2d& p, const Eigen::Vector2d& now) const {
  return now + Eigen::Rotation2Dd(turn) * (p - then);
}

bool Localizer::scan_pose(double stamp, const Eigen::Vector2d& xy, const Eigen::Matrix2d& cov) {
  if (!p_.scan_pose || !filter_.initialized()) return false;
  if (!xy.allFinite() || !cov.allFinite() || !std::isfinite(stamp)) return false;
  // The pose carried by the motion since: the offset from the filter's pose then, turned by the
  // turn since and put at the filter's pose now.
  const auto m = motion_since(stamp);
  if (!m) return false;
  const Eigen::Rotation2Dd r(m->turn);
  const Eigen::Vector2d z = m->carry(xy, filter_.position());
  const Eigen::Matrix2d turned = r.toRotationMatrix() * cov * r.toRotationMatrix().transpose();
  const Eigen::Matrix2d R = with_floor(turned, p_.scan_min_sigma);
  const Eigen::Vector2d e = z - filter_.position();
  if (p_.witness.enabled) {
    const Eigen::Matrix2d W = witness_.floored(turned);
    witness_.observe({t_, e, W, filter_.innovation_cov(W)}, gnss_accepted());
    if (witness_.overrules(t_)) overrule_fixes(e, W);
    // A standing map that agrees with the filter is a witness of the position from this frame
    // on, before its poses are taken (scan_after_s): at a bias's onset every fix is refused at
    // once, and EMERGENCY must not race the first pose taken.
    if (witness_.standing(t_) && witness_.agrees()) manager_.on_witness(t_);
  }
  if (gnss_accepted()) return false;
  if (p_.witness.enabled && !witness_.verified()) {
    ++scan_unverified_;
    return false;
  }
  const Eigen::Matrix2d S = filter_.innovation_cov(R);
  if (!(e.dot(S.ldlt().solve(e)) <= p_.scan_gate)) {
    ++scan_refused_;
    return false;
  }
  filter_.update_position(z, R);
  manager_.on_witness(t_);
  ++scan_updates_;
  return true;
}

void Localizer::overrule_fixes(const Eigen::Vector2d& offset, const Eigen::Matrix2d& map_cov) {
  const Eigen::Vector2d before = filter_.position();
  filter_.relocate(before + offset, map_cov);
  witness_.relocated(t_, filter_.position() - before);
  reacquisition_.reset();
  manager_.on_witness(t_);
}

void Localizer::relocate_on_catch() {
  const Eigen::Vector2d before = filter_.position();
  filter_.relocate(before + witness_.offset(), witness_.cov());
  witness_.shifted(filter_.position() - before);
}

std::vector<MotionVerdict> Localizer::judge_motion(const std::vector<Fix>& epoch) {
  std::vector<MotionVerdict> v(epoch.size());
  if (!p_.witness.enabled || !motion_.enabled()) return v;
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    const Eigen::Vector2d base = filter_.base_from_antenna(epoch[i].antenna, epoch[i].lever);
    const double align = filter_.state()(PoseFilter::YAW) - dr_.yaw;
    v[i] = motion_.observe(epoch[i].receiver, {t_, base, filter_.fix_variance(epoch[i].sigma), {dr_.x, dr_.y}, align, filter_.position()});
  }
  return v;
}

const MotionVerdict* Localizer::catch_moving(const std::vector<Fix>& epoch, const std::vector<MotionVerdict>& moved, std::vector<bool>& refused) {
  if (!witness_.standing(t_)) return nullptr;
  std::vector<bool> off(epoch.size(), false);
  const MotionVerdict* first = nullptr;
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    if (refused[i] || !moved[i].off) continue;
    off[i] = refused[i] = true;
    witness_.refuse_beside(t_, epoch[i].receiver);
    if (!first) first = &moved[i];
  }
  if (!first) return nullptr;
  refuse_beside(epoch, off, refused);
  ++motion_catches_;
  if (first_motion_catch_s_ < 0) first_motion_catch_s_ = t_;
  return first;
}

void Localizer::relocate_by_motion(const MotionVerdict& v) {
  const Eigen::Vector2d before = filter_.position();
  filter_.relocate(v.start_xy + v.travel, with_floor(v.travel_cov, p_.motion.fix_floor));
  witness_.shifted(filter_.position() - before);
}

void Localizer::learn_motion(const std::vector<MotionVerdict>& moved, const EpochResult& r) {
  const bool healthy = !witness_.any_caught() && std::all_of(r.accepted.begin(), r.accepted.end(), [](bool a) { return a; });
  if (!healthy) return motion_.forget_pending();
  for (const auto& v : moved) motion_.learn(t_, v);
}

void Localizer::scan_unlocated() {
  if (p_.witness.enabled && filter_.initialized()) witness_.unlocated(t_, gnss_accepted());
}

void Localizer::imu(double t, double gyro_z, double accel_y) {
  if (!std::isfinite(t) || !std::isfinite(gyro_z) || !std::isfinite(accel_y)) {
    ++malformed_;
    return;
  }
  advance(t);
  yaw_rate_ = gyro_z;
  have_imu_ = true;
  if (p_.roll_filter_s <= 0) return;
  // Roll from the lateral specific force of a car cornering in the plane of a banked road:
  // f_y = v * yaw rate + dvy/dt + g sin(roll). dvy/dt is not measured and swings by metres per
  // second squared through a turn's entry and exit, so the estimate is low-passed.
  const double s = std::clamp((accel_y - speed_ * yaw_rate_) / 9.81, -0.5, 0.5);
  sin_roll_ += (s - sin_roll_) * (roll_t_ < 0 ? 1.0 : std::min(1.0, (t - roll_t_) / p_.roll_filter_s));
  roll_t_ = t;
  filter_.set_roll(std::asin(sin_roll_));
}

void Localizer::fixes(double t, const std::vector<Fix>& epoch_in) {
  if (epoch_in.empty()) return;
  auto finite = [](const Fix& f) { return std::isfinite(f.antenna.x()) && std::isfinite(f.antenna.y()) && std::isfinite(f.sigma) && f.sigma >= 0; };
  std::vector<Fix> epoch;
  epoch.reserve(epoch_in.size());
  for (const auto& f : epoch_in)
    if (finite(f)) epoch.push_back(f);
    else ++malformed_;
  if (!std::isfinite(t)) malformed_ += epoch.size(), epoch.clear();
  if (epoch.empty()) return;
  advance(t);
  if (filter_.initialized()) {
    // Delivered after IMU samples stamped later (a sample resent by DDS, a loaded host; on the
    // real clock, a receiver's fix that waited for the other's, epoch_gather.hpp): the filter has
    // moved on since the stamp, so each antenna is carried by the car's motion since its own
    // stamp. Taken as now, a fix 0.15 s late at 35 m/s is 5 m behind: past δ, rejected.
    std::vector<Fix> kept;
    kept.reserve(epoch.size());
    for (auto& f : epoch) {
      const double s = std::isfinite(f.stamp) ? f.stamp : t;
      if (s < t_) {
        const auto m = motion_since(s);
        if (!m) {  // older than the history kept: nothing to carry it by
          ++too_late_;
          continue;
        }
        f.antenna = m->carry(f.antenna, filter_.position());
        ++late_;
        late_max_s_ = std::max(late_max_s_, t_ - s);
      }
      kept.push_back(f);
    }
    epoch.swap(kept);
    if (epoch.empty()) return;
  }
  if (!filter_.initialized()) {
    initialize(t, epoch);
    for (const auto& f : epoch) manager_.on_fix(f.receiver, t, true);
    last_accepted_t_ = t;
    return;
  }
  const bool caught_before = witness_.any_caught();
  std::vector<bool> refused = refused_by_map(epoch);
  const std::vector<MotionVerdict> moved = judge_motion(epoch);
  const MotionVerdict* moving = catch_moving(epoch, moved, refused);
  // Caught now: the filter took their fixes until this epoch, so the map's position is the better
  // (or, caught moving unlike the car, the car's own travel from before they pulled it).
  if (!caught_before && witness_.any_caught() && witness_.standing(t_)) {
    if (moving) relocate_by_motion(*moving);
    else relocate_on_catch();
  }
  EpochResult r = apply_judged(epoch, refused);
  learn_motion(moved, r);
  // A standing map says where the car is: fixes it refused are not taken back by reacquisition.
  if (p_.policy == Policy::resilient && witness_.holds_reacquisition(t_)) reacquisition_.reset();
  else if (p_.policy == Policy::resilient) reacquire(t, epoch, r);
  ++epochs_;
  ++cases_[static_cast<int>(r.which)];
  last_case_ = r.which;
  std::fill(last_delta_.begin(), last_delta_.end(), -1.0);
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    if (epoch[i].receiver >= 0 && epoch[i].receiver < static_cast<int>(last_delta_.size()))
      last_delta_[epoch[i].receiver] = r.delta[i];
    manager_.on_fix(epoch[i].receiver, t, r.accepted[i]);
    rejected_ += !r.accepted[i];
    if (r.accepted[i]) last_accepted_t_ = t;
  }
}

std::vector<bool> Localizer::refused_by_map(const std::vector<Fix>& epoch) {
  std::vector<bool> refused(epoch.size(), false), off(epoch.size(), false);
  if (!p_.witness.enabled) return refused;
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    const Eigen::Vector2d base = filter_.base_from_antenna(epoch[i].antenna, epoch[i].lever);
    const Eigen::Matrix2d R = filter_.fix_variance(epoch[i].sigma) * Eigen::Matrix2d::Identity();
    refused[i] = witness_.refuses(t_, base, R, filter_.position(), epoch[i].receiver, filter_.innovation_cov(Eigen::Matrix2d::Zero()));
    off[i] = refused[i] && witness_.refused_off();
  }
  refuse_beside(epoch, off, refused);
  return refused;
}

void Localizer::refuse_beside(const std::vector<Fix>& epoch, const std::vector<bool>& off, std::vector<bool>& refused) {
  const double floor = p_.witness.sigma_floor * p_.witness.sigma_floor;
  auto base = [&](const Fix& f) { return filter_.base_from_antenna(f.antenna, f.lever); };
  for (std::size_t i = 0; i < epoch.size(); ++i)
    for (std::size_t j = 0; j < epoch.size() && !refused[i]; ++j) {
      if (!off[j]) continue;
      const double var = filter_.fix_variance(epoch[i].sigma) + filter_.fix_variance(epoch[j].sigma) + floor;
      if ((base(epoch[i]) - base(epoch[j])).squaredNorm() > p_.witness.gate * var) continue;
      refused[i] = true;
      witness_.refuse_beside(t_, epoch[i].receiver);
    }
}

EpochResult Localizer::apply_judged(const std::vector<Fix>& epoch, const std::vector<bool>& refused) {
  std::vector<Fix> judged;
  for (std::size_t i = 0; i < epoch.size(); ++i)
    if (!refused[i]) judged.push_back(epoch[i]);
  if (judged.size() == epoch.size()) return apply_fixes(filter_, epoch, p_.policy, p_.selection);
  const EpochResult kept = judged.empty() ? EpochResult{UpdateCase::rejected, {}, {}} : apply_fixes(filter_, judged, p_.policy, p_.selection);
  EpochResult r{kept.which, {}, {}};
  for (std::size_t i = 0, k = 0; i < epoch.size(); ++i) {
    if (refused[i]) {
      r.delta.push_back((filter_.base_from_antenna(epoch[i].antenna, epoch[i].lever) - filter_.position()).norm());
      r.accepted.push_back(false);
    } else {
      r.delta.push_back(kept.delta[k]);
      r.accepted.push_back(kept.accepted[k++]);
    }
  }
  return r;
}

// Every fix rejected: the rule of reacquisition.hpp may say the receivers are right and the
// prediction wrong; then the filter takes their position and the fixes count as accepted.
void Localizer::reacquire(double t, const std::vector<Fix>& epoch, EpochResult& r) {
  if (r.which != UpdateCase::rejected) {
    reacquisition_.reset();
    return;
  }
  std::vector<Eigen::Vector2d> z;
  for (const auto& f : epoch) z.push_back(filter_.base_from_antenna(f.antenna, f.lever));
  const auto at = reacquisition_.observe(t, z, filter_.position());
  if (!at) return;
  double sigma = 0;
  for (const auto& f : epoch) sigma = std::max(sigma, f.sigma);
  filter_.reset_pose(at->position, at->turn, std::max(sigma, p_.reacquire.agree_m));
  ++reacquisitions_;
  r.accepted.assign(epoch.size(), true);
}

// Position from the fixes; heading from the direction of travel once the car has moved.
void Localizer::initialize(double t, const std::vector<Fix>& epoch) {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  Eigen::Vector3d lever = Eigen::Vector3d::Zero();
  for (const auto& f : epoch) {
    p += f.antenna;
    lever += f.lever;
  }
  p /= static_cast<double>(epoch.size());
  lever /= static_cast<double>(epoch.size());
  if (!first_) {
    first_ = p;
    return;
  }
  const Eigen::Vector2d d = p - *first_;
  if (d.norm() < p_.init_distance) return;
  const double yaw = std::atan2(d.y(), d.x());
  filter_.init(p.x(), p.y(), yaw, 0.1, 0.05);
  const Eigen::Vector2d base = filter_.base_from_antenna(p, lever);
  filter_.init(base.x(), base.y(), yaw, 0.1, 0.05);
  // The pose is the one at the epoch's stamp; the filter's time may be later (a late epoch).
  if (t < t_) filter_.predict(t_ - t, speed_, yaw_rate_);
}

Localizer::Pose Localizer::pose_at(double t, double max_s) const {
  const auto& x = filter_.state();
  Pose p{x(PoseFilter::X), x(PoseFilter::Y), x(PoseFilter::YAW), 0, 0};
  const double ahead = t - t_;
  if (!(ahead > 0)) return p;
  const double dt = std::min(ahead, max_s);
  const double v = x(PoseFilter::SPEED), w = x(PoseFilter::YAW_RATE);
  const double mid = p.yaw + 0.5 * w * dt;
  return {p.x + v * std::cos(mid) * dt, p.y + v * std::sin(mid) * dt, p.yaw + w * dt, dt, ahead - dt};
}

Status Localizer::status(double t) { return filter_.initialized() ? manager_.update(t) : Status::warning; }

std::pair<UpdateCase, std::vector<double>> Localizer::take_epoch_summary() {
  auto out = std::make_pair(last_case_, last_delta_);
  last_case_ = UpdateCase::predict_only;
  std::fill(last_delta_.begin(), last_delta_.end(), -1.0);
  return out;
}

}  // namespace brickyard::estimation
