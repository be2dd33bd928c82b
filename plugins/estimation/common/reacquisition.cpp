#include "reacquisition.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace brickyard::estimation {

std::optional<Reacquired> Reacquisition::fit() const {
  const int n = static_cast<int>(window_.size());
  Eigen::Matrix2Xd from(2, n), to(2, n);
  for (int i = 0; i < n; ++i) {
    from.col(i) = window_[i].filter;
    to.col(i) = window_[i].fix;
  }
  double span = 0;
  for (int i = 1; i < n; ++i) span = std::max(span, (from.col(i) - from.col(0)).norm());
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  Eigen::Vector2d shift = to.rowwise().mean() - from.rowwise().mean();
  if (span >= p_.min_span_m) {
    const Eigen::Matrix3d T = Eigen::umeyama(from, to, false);  // rotation and translation, no scale
    R = T.topLeftCorner<2, 2>();
    shift = T.topRightCorner<2, 1>();
  }
  const double turn = std::atan2(R(1, 0), R(0, 0));
  if (!(std::abs(turn) <= p_.max_turn)) return std::nullopt;
  for (int i = 0; i < n; ++i)
    if (!((R * from.col(i) + shift - to.col(i)).norm() <= p_.motion_m)) return std::nullopt;
  return Reacquired{window_.back().fix, turn};
}

std::optional<Reacquired> Reacquisition::observe(double t, const std::vector<Eigen::Vector2d>& fixes,
                                                 const Eigen::Vector2d& filter) {
  if (!p_.enabled || static_cast<int>(fixes.size()) < p_.min_receivers) {
    reset();
    return std::nullopt;
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& z : fixes) mean += z;
  mean /= static_cast<double>(fixes.size());
  for (std::size_t i = 0; i < fixes.size(); ++i)
    for (std::size_t j = i + 1; j < fixes.size(); ++j)
      if (!((fixes[i] - fixes[j]).norm() <= p_.agree_m)) {  // the receivers disagree (or are NaN)
        reset();
        return std::nullopt;
      }
  window_.push_back({t, mean, filter});
  // Only the last window_s counts; the rule is judged once the samples span all of it.
  while (window_.size() > 1 && t - window_[1].t >= p_.window_s) window_.pop_front();
  if (t - window_.front().t < p_.window_s) return std::nullopt;
  auto found = fit();
  if (!found) {
    window_.pop_front();  // slide on: the next epoch is judged with the oldest left out
    return std::nullopt;
  }
  reset();
  return found;
}

}  // namespace brickyard::estimation
