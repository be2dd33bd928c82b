#include "reacquisition.hpp"

namespace brickyard::estimation {

std::optional<Eigen::Vector2d> Reacquisition::observe(double t, const std::vector<Eigen::Vector2d>& fixes,
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
      if ((fixes[i] - fixes[j]).norm() > p_.agree_m) {  // the receivers disagree
        reset();
        return std::nullopt;
      }
  const Eigen::Vector2d offset = mean - filter;
  if (!start_t_ || (offset - start_offset_).norm() > p_.motion_m) {  // (re)start the window here
    start_t_ = t;
    start_offset_ = offset;
    return std::nullopt;
  }
  if (t - *start_t_ < p_.window_s) return std::nullopt;
  reset();
  return mean;
}

}  // namespace brickyard::estimation
