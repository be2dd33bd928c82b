#include "gnss_receiver.hpp"

#include <cmath>

namespace brickyard::sim {

BodyState carried(const BodyState& s, double dt) {
  BodyState at = s;
  const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
  at.x = s.x + (c * s.vx - sn * s.vy) * dt;
  at.y = s.y + (sn * s.vx + c * s.vy) * dt;
  at.yaw = s.yaw + s.yaw_rate * dt;
  return at;
}

Eigen::Isometry3d world_from_body(const BodyState& s) {
  return Eigen::Translation3d(s.x, s.y, s.z) * Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(s.pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(s.roll, Eigen::Vector3d::UnitX());
}

GnssReceiver::GnssReceiver(const Eigen::Vector3d& antenna, GnssNoise noise, FaultSchedule faults, Rng rng)
    : antenna_(antenna),
      sigma_(noise.sigma_m),
      sigma_z_(noise.sigma_z_m),
      reported_(noise.reported_sigma_m < 0 ? noise.sigma_m : noise.reported_sigma_m),
      fix_type_(noise.fix_type),
      faults_(std::move(faults)),
      rng_(rng) {}

GnssReceiver::Epoch GnssReceiver::epoch(std::int64_t stamp_ns, const BodyState& truth, std::int64_t truth_stamp_ns,
                                        std::int64_t run_start_ns) {
  // The position at the fix's stamp. On the sim clock the newest truth is of this instant; on
  // the real clock it is a millisecond or two old (the car's step ran before), and the car moves
  // 8 cm in 2 ms at 40 m/s: the truth is carried to the stamp by the car's motion.
  BodyState at = truth;
  if (const double dt = static_cast<double>(stamp_ns - truth_stamp_ns) * 1e-9; dt != 0) at = carried(truth, dt);
  const double t = static_cast<double>(stamp_ns - run_start_ns) * 1e-9;
  // Noise is drawn every epoch, faulty or not, so a fault window leaves the rest of the run's
  // noise sequence as it would have been.
  const double n[3] = {rng_.normal(), rng_.normal(), rng_.normal()};
  const FaultEffect e = faults_.at(t, rng_);
  if (e.drop) return Epoch::dropped;
  if (e.freeze && fixes_ > 0) return Epoch::frozen;
  fix_ = measure(at, n, e);
  for (double v : {fix_.x, fix_.y, fix_.z, fix_.sigma_x}) digest_.add(v);
  ++fixes_;
  return Epoch::fresh;
}

GnssFixValues GnssReceiver::measure(const BodyState& truth, const double (&n)[3], const FaultEffect& e) const {
  const Eigen::Vector3d p = world_from_body(truth) * antenna_;
  GnssFixValues f;
  f.x = p.x() + e.offset[0] + sigma_ * e.noise_factor * n[0];
  f.y = p.y() + e.offset[1] + sigma_ * e.noise_factor * n[1];
  f.z = p.z() + e.offset[2] + sigma_z_ * e.noise_factor * n[2];
  f.sigma_x = reported_ * e.sigma_factor;
  f.sigma_y = reported_ * e.sigma_factor;
  f.sigma_z = reported_ * e.sigma_factor * (sigma_ > 0 ? sigma_z_ / sigma_ : 1.0);
  f.fix_type = e.fix_type.value_or(fix_type_);
  f.valid = f.fix_type > 0;
  return f;
}

}  // namespace brickyard::sim
