#include "localization_score.hpp"

#include "perception_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::sim {

void LocalizationScore::truth(double t, double x, double y) {
  truth_.push_back({t, {x, y}});
  while (truth_.size() > 4096) truth_.pop_front();
}

bool LocalizationScore::in_window(double t, double grace) const {
  for (const auto& [a, b] : p_.windows)
    if (t >= a && t < b + grace) return true;
  return false;
}

namespace {
constexpr double kNees999 = 13.8;  // chi-square, 2 degrees of freedom, 99.9 %
}  // namespace

bool LocalizationScore::estimate(double t, double x, double y, int status, const PlanarSpread* spread) {
  if (truth_.empty() || t < truth_.front().first || t > truth_.back().first) return false;
  // Truth at t, linear between the samples around it.
  std::size_t i = truth_.size() - 1;
  while (i > 0 && truth_[i - 1].first > t) --i;
  double tx = truth_[i].second.first, ty = truth_[i].second.second;
  if (i > 0 && truth_[i].first > t) {
    const auto& a = truth_[i - 1];
    const double u = (t - a.first) / (truth_[i].first - a.first);
    tx = a.second.first + u * (tx - a.second.first);
    ty = a.second.second + u * (ty - a.second.second);
  }
  last_truth_ = {tx, ty};
  if (t < p_.warmup_s) {
    last_status_ = status;
    return true;
  }
  const double e = std::hypot(x - tx, y - ty);
  ++n_;
  sq_ += e * e;
  max_ = std::max(max_, e);
  errors_.push_back(e);
  if (status == 0) max_normal_ = std::max(max_normal_, e);
  if (spread) judge(x - tx, y - ty, *spread);
  for (const auto& [a, b] : p_.windows) {
    if (t >= a && t <= b) max_window_ = std::max(max_window_, e);
    if (t < a || t >= b + p_.grace_s) continue;
    if (status >= 1 && flag_ < 0) flag_ = t - a;
    if (status >= 2 && emergency_ < 0) emergency_ = t - a;
  }
  if (last_status_ == 0 && status != 0 && !in_window(t, p_.grace_s)) ++false_alarms_;
  last_status_ = status;
  return true;
}

void LocalizationScore::judge(double ex, double ey, const PlanarSpread& c) {
  const double det = c.xx * c.yy - c.xy * c.xy;
  if (!(c.xx > 0 && det > 0)) return;
  nees_.push_back((c.yy * ex * ex - 2 * c.xy * ex * ey + c.xx * ey * ey) / det);
  // The larger eigenvalue of the 2x2 covariance: the estimate's least sure direction.
  const double largest = 0.5 * (c.xx + c.yy) + std::sqrt(0.25 * (c.xx - c.yy) * (c.xx - c.yy) + c.xy * c.xy);
  if (largest <= p_.sure_sigma_m * p_.sure_sigma_m) max_sure_ = std::max(max_sure_, std::hypot(ex, ey));
}

double LocalizationScore::nees_p99() const { return PerceptionScore::percentile(nees_, 0.99); }

double LocalizationScore::overconfident_share() const {
  if (nees_.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto over = std::count_if(nees_.begin(), nees_.end(), [](double d) { return d > kNees999; });
  return static_cast<double>(over) / static_cast<double>(nees_.size());
}

double LocalizationScore::p99_error() const { return PerceptionScore::percentile(errors_, 0.99); }

double LocalizationScore::rmse() const {
  return n_ ? std::sqrt(sq_ / static_cast<double>(n_)) : std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::pair<const char*, double>> score_metrics(const LocalizationScore& s) {
  return {{"samples", static_cast<double>(s.samples())},
          {"rmse_m", s.rmse()},
          {"max_error_m", s.max_error()},
          {"p99_error_m", s.p99_error()},
          {"max_error_normal_m", s.max_error_normal()},
          {"max_error_in_windows_m", s.max_error_in_windows()},
          {"time_to_flag_s", s.time_to_flag()},
          {"time_to_emergency_s", s.time_to_emergency()},
          {"false_alarms", static_cast<double>(s.false_alarms())},
          {"judged", static_cast<double>(s.judged())},
          {"nees_p99", s.nees_p99()},
          {"overconfident_share", s.overconfident_share()},
          {"max_error_sure_m", s.max_error_sure()}};
}

}  // namespace brickyard::sim
