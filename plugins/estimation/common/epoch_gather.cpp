#include "epoch_gather.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::estimation {

bool EpochGather::add(double stamp, Fix f) {
  if (!std::isfinite(stamp)) return false;
  f.stamp = stamp;
  // The nearest held epoch within pair_s that lacks this receiver (one that has it: f is another
  // epoch's).
  Held* best = nullptr;
  for (Held& h : held_) {
    if (!(std::abs(stamp - h.first) <= pair_s_)) continue;
    if (std::any_of(h.epoch.fixes.begin(), h.epoch.fixes.end(), [&](const Fix& g) { return g.receiver == f.receiver; })) continue;
    if (!best || std::abs(stamp - h.first) < std::abs(stamp - best->first)) best = &h;
  }
  if (best) {
    best->epoch.fixes.push_back(f);
    best->epoch.t = std::max(best->epoch.t, stamp);
    return true;
  }
  Held h;
  h.first = stamp;
  h.epoch.t = stamp;
  h.epoch.fixes.push_back(f);
  // Kept in the order of first stamps (a late fix may start an epoch older than those held).
  auto at = std::upper_bound(held_.begin(), held_.end(), stamp, [](double s, const Held& x) { return s < x.first; });
  held_.insert(at, std::move(h));
  return true;
}

std::vector<GatheredEpoch> EpochGather::release(double now) {
  std::vector<GatheredEpoch> out;
  std::size_t excess = held_.size() > kMaxHeld ? held_.size() - kMaxHeld : 0;
  for (auto it = held_.begin(); it != held_.end();) {
    const bool oldest_beyond_cap = excess > 0;
    if (oldest_beyond_cap || static_cast<int>(it->epoch.fixes.size()) >= receivers_ || now - it->first >= wait_s_) {
      if (oldest_beyond_cap) --excess;
      out.push_back(std::move(it->epoch));
      it = held_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

}  // namespace brickyard::estimation
