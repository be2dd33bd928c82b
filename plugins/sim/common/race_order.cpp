#include "race_order.hpp"

#include <cmath>

namespace brickyard::sim {

void RaceOrder::advance(Progress& p, double x, double y, double near) const {
  const Frenet f = track_.project(x, y, p.hint);
  p.hint = f.seg;
  const double length = track_.length();
  const double from = p.seen ? p.s : near;
  p.s = from + std::remainder(f.s - from, length);  // the lap that keeps it within half a lap
  p.seen = true;
}

std::vector<RaceOrder::Pass> RaceOrder::update(double t, const CarBox& ours, const std::vector<std::optional<CarBox>>& others) {
  std::vector<Pass> out;
  advance(ours_, ours.x, ours.y, 0.0);
  if (others_.size() < others.size()) others_.resize(others.size());
  for (std::size_t k = 0; k < others.size(); ++k) {
    if (!others[k]) continue;
    Progress& p = others_[k];
    advance(p, others[k]->x, others[k]->y, ours_.s);
    const double ahead = p.s - ours_.s;
    const int side = ahead > margin_ ? 1 : ahead < -margin_ ? -1 : 0;
    if (side != 0 && p.side != 0 && side != p.side) {
      const bool ours_pass = side < 0;
      out.push_back({static_cast<int>(k), ours_pass, t, std::fmod(ours_.s, track_.length())});
      (ours_pass ? passes_ : passed_by_) += 1;
    }
    if (side != 0) p.side = side;
  }
  return out;
}

int RaceOrder::position() const {
  int ahead = 0;
  for (const Progress& p : others_)
    if (p.seen && p.s - ours_.s > margin_) ++ahead;
  return 1 + ahead;
}

}  // namespace brickyard::sim
