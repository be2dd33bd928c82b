#include "map_witness.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>

namespace brickyard::estimation {

namespace {

bool within(const Eigen::Vector2d& e, const Eigen::Matrix2d& S, double gate) { return e.dot(S.ldlt().solve(e)) <= gate; }

}  // namespace

Eigen::Matrix2d with_floor(const Eigen::Matrix2d& cov, double sigma) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (cov + cov.transpose()));
  const Eigen::Vector2d spread = es.eigenvalues().cwiseMax(sigma * sigma);
  return es.eigenvectors() * spread.asDiagonal() * es.eigenvectors().transpose();
}

void MapWitness::count_frame(double t, bool gnss_accepted) {
  if (gnss_accepted && !ever_verified_ && last_frame_t_ >= 0 && t - last_frame_t_ <= p_.fresh_s) unverified_s_ += t - last_frame_t_;
  last_frame_t_ = t;
  mismatch_ = mismatch_ || (!ever_verified_ && unverified_s_ >= p_.mismatch_s);
}

void MapWitness::unlocated(double t, bool gnss_accepted) {
  count_frame(t, gnss_accepted);
  agree_since_ = -1;
}

void MapWitness::observe(const MapPoseNow& m, bool gnss_accepted) {
  count_frame(m.t, gnss_accepted);
  const bool agrees = within(m.offset, m.innovation_cov, p_.gate);
  // Within fresh_s of the previous pose the offset must be continuous; after a gap (LiDAR lost,
  // the filter on dead reckoning meanwhile) the pose must agree with the filter's spread instead.
  const bool recent = last_t_ >= 0 && m.t - last_t_ <= p_.fresh_s;
  if (recent ? !within(m.offset - offset_, m.cov + cov_, p_.gate) : !agrees) {
    jumps_ += verified_;
    verified_ = false;
    agree_since_ = -1;
  }
  // The filter's own position spread: the innovation's less the map pose's.
  const double filter_var = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m.innovation_cov - m.cov).eigenvalues().maxCoeff();
  const bool witness_to_agree = gnss_accepted || filter_var <= p_.verify_sigma * p_.verify_sigma;
  if (mismatch_) {
    verified_ = false;
  } else if (witness_to_agree && agrees) {
    if (agree_since_ < 0) agree_since_ = m.t;
    if (m.t - agree_since_ >= p_.verify_s) verified_ = ever_verified_ = true;
  } else {
    agree_since_ = -1;
    disagreements_ += gnss_accepted;
  }
  if (!verified_ || agrees) disagree_since_ = -1;
  else if (disagree_since_ < 0) disagree_since_ = m.t;
  if (verified_) last_verified_t_ = m.t;
  agrees_ = agrees;
  last_t_ = m.t;
  offset_ = m.offset;
  cov_ = m.cov;
}

void MapWitness::relocated(double t, const Eigen::Vector2d& shift) {
  for (auto& c : caught_) c = {p_.retrust_s > 0, -1};
  shifted(shift);
  agrees_ = true;
  disagree_since_ = -1;
  ++overrulings_;
  if (first_overrule_ < 0) first_overrule_ = t;
}

bool MapWitness::refuses(double t, const Eigen::Vector2d& base, const Eigen::Matrix2d& R, const Eigen::Vector2d& filter_xy, int receiver,
                         const Eigen::Matrix2d& filter_cov) {
  Caught& c = entry(receiver);
  if (c.caught && still_caught(t, c, base, R, filter_xy, filter_cov)) {
    count_refusal(t);
    refused_off_ = c.agree_since < 0;
    return true;
  }
  if (!standing(t) || !agrees_ || within(base - (filter_xy + offset_), cov_ + R, p_.gate)) return false;
  count_refusal(t);
  refused_off_ = true;
  c = {p_.retrust_s > 0, -1};
  return true;
}

MapWitness::Caught& MapWitness::entry(int receiver) {
  const std::size_t i = receiver < 0 ? 0 : static_cast<std::size_t>(receiver);
  if (i >= caught_.size()) caught_.resize(i + 1);
  return caught_[i];
}

bool MapWitness::still_caught(double t, Caught& c, const Eigen::Vector2d& base, const Eigen::Matrix2d& R, const Eigen::Vector2d& filter_xy,
                              const Eigen::Matrix2d& filter_cov) {
  if (!holds_reacquisition(t)) return (c = {}), false;  // no witness left
  const Eigen::Matrix2d floor = Eigen::Matrix2d::Identity() * p_.sigma_floor * p_.sigma_floor;
  if (!within(base - filter_xy, filter_cov + R + floor, p_.gate)) c.agree_since = -1;
  else if (c.agree_since < 0) c.agree_since = t;
  if (c.agree_since >= 0 && t - c.agree_since >= p_.retrust_s) c = {};
  return c.caught;
}

void MapWitness::refuse_beside(double t, int receiver) {
  count_refusal(t);
  Caught& c = entry(receiver);
  if (!c.caught) c = {p_.retrust_s > 0, -1};
}

void MapWitness::count_refusal(double t) {
  ++refusals_;
  if (first_refusal_ < 0) first_refusal_ = t;
  if (t - last_refusal_ > 1.0) ++stretches_;  // a new stretch: none refused for a second
  last_refusal_ = t;
}

}  // namespace brickyard::estimation
