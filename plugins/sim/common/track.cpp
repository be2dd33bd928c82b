#include "track.hpp"

#include <limits>
#include <utility>

namespace brickyard::sim {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

Track::Track(WorldSpec spec) : track::Track(static_cast<const track::TrackGeometry&>(spec)), spec_(std::move(spec)) {
  spec_.bank = geometry().bank;  // the geometry fills in a flat bank when none was given
  for (auto& p : spec_.pylons) {
    Frenet f = at(p.s, p.d);
    Eigen::Vector2d q = position(f);
    p.x = q.x();
    p.y = q.y();
    p.z = road_z(f);
  }
}

double Track::wall_left_d(int seg, double u) const {
  return spec_.walls.left ? width_left(seg, u) + spec_.walls.left_offset : kInf;
}
double Track::wall_right_d(int seg, double u) const {
  return spec_.walls.right ? -(width_right(seg, u) + spec_.walls.right_offset) : -kInf;
}

}  // namespace brickyard::sim
