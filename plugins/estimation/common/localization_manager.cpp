#include "localization_manager.hpp"

#include <algorithm>
#include <cstdio>

namespace brickyard::estimation {

const char* status_name(Status s) {
  switch (s) {
    case Status::normal: return "NORMAL";
    case Status::warning: return "WARNING";
    case Status::emergency: return "EMERGENCY";
  }
  return "?";
}

LocalizationManager::LocalizationManager(ManagerParams p)
    : p_(p), last_fix_(std::max(p.receivers, 1), 0.0), last_ok_(std::max(p.receivers, 1), true) {}

void LocalizationManager::on_fix(int receiver, double t, bool accepted) {
  if (receiver < 0 || receiver >= static_cast<int>(last_fix_.size())) return;
  last_fix_[receiver] = t;
  last_ok_[receiver] = accepted;
}

Status LocalizationManager::update(double t) {
  if (!started_) {
    // A receiver that has not spoken yet is late only fix_timeout_s after the manager started.
    std::fill(last_fix_.begin(), last_fix_.end(), t);
    started_ = true;
  }
  int bad = 0;
  std::string why;
  for (std::size_t r = 0; r < last_fix_.size(); ++r) {
    char b[96];
    if (t - last_fix_[r] > p_.fix_timeout_s) {
      std::snprintf(b, sizeof b, "no fix from receiver %zu for %.2f s", r, t - last_fix_[r]);
    } else if (!last_ok_[r]) {
      std::snprintf(b, sizeof b, "receiver %zu rejected", r);
    } else {
      continue;
    }
    ++bad;
    why += why.empty() ? b : std::string("; ") + b;
  }
  const bool all_bad = bad == static_cast<int>(last_fix_.size());
  if (!all_bad) all_bad_since_ = -1;
  else if (all_bad_since_ < 0) all_bad_since_ = t;
  const bool witnessed = p_.witness_timeout_s > 0 && t - last_witness_ <= p_.witness_timeout_s;
  if (all_bad && witnessed) why += "; located on the map";
  Status raw = Status::normal;
  if (all_bad && t - all_bad_since_ >= p_.emergency_after_s && !witnessed) raw = Status::emergency;
  else if (bad > 0) raw = Status::warning;

  if (raw >= status_) {
    if (raw > status_ || !why.empty()) reason_ = why;
    status_ = raw;
    calm_since_ = -1;
  } else {
    if (calm_since_ < 0) calm_since_ = t;
    if (t - calm_since_ >= p_.recover_after_s) {
      status_ = static_cast<Status>(static_cast<int>(status_) - 1);
      calm_since_ = raw < status_ ? t : -1;
      reason_ = status_ == Status::normal ? "" : "recovering";
    }
  }
  return status_;
}

}  // namespace brickyard::estimation
