#include "road_surface.hpp"

#include <cmath>

namespace brickyard::mapping {

namespace {
std::uint64_t tile_key(std::int64_t tx, std::int64_t ty) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(tx)) << 32) | static_cast<std::uint32_t>(ty);
}
std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace

RoadSurface::Cell* RoadSurface::cell(std::int64_t ix, std::int64_t iy, bool create) {
  const std::int64_t tx = floor_div(ix, kTile), ty = floor_div(iy, kTile);
  auto it = tiles_.find(tile_key(tx, ty));
  if (it == tiles_.end()) {
    if (!create) return nullptr;
    it = tiles_.emplace(tile_key(tx, ty), std::make_unique<Tile>()).first;
  }
  return &it->second->c[(iy - ty * kTile) * kTile + (ix - tx * kTile)];
}

const RoadSurface::Cell* RoadSurface::cell(std::int64_t ix, std::int64_t iy) const {
  return const_cast<RoadSurface*>(this)->cell(ix, iy, false);
}

void RoadSurface::add_scan(const float* x, const float* y, const float* z, const float* intensity, std::size_t n,
                           const Eigen::Isometry3d& vehicle_from_sensor, const Eigen::Isometry3d& map_from_vehicle) {
  const Eigen::Vector3d sensor = vehicle_from_sensor.translation();
  const Eigen::Isometry3d map_from_sensor = map_from_vehicle * vehicle_from_sensor;
  const double inv = 1.0 / p_.cell;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d ps(x[i], y[i], z[i]);
    const double range = ps.norm();
    if (!(range > 0.5 && range <= p_.max_range) || !std::isfinite(intensity[i])) continue;
    const Eigen::Vector3d pv = vehicle_from_sensor * ps;
    const double drop = sensor.z() - pv.z();
    if (drop < p_.min_drop) continue;  // level with the sensor or above: not the ground
    const double cos = drop / range;   // against the road's normal under the car
    if (cos < p_.min_cos) continue;
    const Eigen::Vector3d pm = map_from_sensor * ps;
    Cell* c = cell(static_cast<std::int64_t>(std::floor(pm.x() * inv)), static_cast<std::int64_t>(std::floor(pm.y() * inv)), true);
    if (c->n == 0 && c->standing == 0) ++cells_;
    c->refl_sum += static_cast<float>(intensity[i] / cos);
    c->z_sum += static_cast<float>(pm.z());
    ++c->n;
  }
}

void RoadSurface::add_standing(double x, double y) {
  if (!(std::isfinite(x) && std::isfinite(y))) return;
  const double inv = 1.0 / p_.cell;
  Cell* c = cell(static_cast<std::int64_t>(std::floor(x * inv)), static_cast<std::int64_t>(std::floor(y * inv)), true);
  if (c->n == 0 && c->standing == 0) ++cells_;
  ++c->standing;
}

RoadSurface::Sample RoadSurface::at(double x, double y, double standing_value) const {
  Sample out;
  // Cell centres at (i + 0.5) · cell: the four round (x, y) and the weights of each.
  const double u = x / p_.cell - 0.5, v = y / p_.cell - 0.5;
  const std::int64_t i0 = static_cast<std::int64_t>(std::floor(u)), j0 = static_cast<std::int64_t>(std::floor(v));
  const double fu = u - static_cast<double>(i0), fv = v - static_cast<double>(j0);
  double w_sum = 0, r = 0, zw = 0, z = 0;
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const Cell* c = cell(i0 + di, j0 + dj);
      if (!c || (c->n == 0 && c->standing == 0)) continue;
      const double w = (di ? fu : 1 - fu) * (dj ? fv : 1 - fv) + 1e-9;
      if (c->standing > 0) {
        r += w * standing_value;
        out.standing = true;
      } else {
        r += w * c->refl_sum / c->n;
        z += w * c->z_sum / c->n;
        zw += w;
      }
      w_sum += w;
    }
  if (w_sum <= 0) return out;
  out.known = true;
  out.reflectivity = r / w_sum;
  out.has_z = zw > 0;
  out.z = out.has_z ? z / zw : 0.0;
  return out;
}

}  // namespace brickyard::mapping
