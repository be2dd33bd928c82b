#include "road_surface.hpp"

#include <algorithm>
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
    if (!(range > 0.5 && range <= p_.max_range)) continue;
    const Eigen::Vector3d pv = vehicle_from_sensor * ps;
    const bool ground = std::abs(pv.z()) <= p_.ground_band, standing = pv.z() >= p_.standing_from && pv.z() <= p_.standing_to;
    if (!ground && !standing) continue;
    const double drop = sensor.z() - pv.z();
    const double cos = drop / range;  // against the road's normal under the car
    if (ground && (drop < p_.min_drop || cos < p_.min_cos || !std::isfinite(intensity[i]))) continue;
    const Eigen::Vector3d pm = map_from_sensor * ps;
    const double fx = std::floor(pm.x() * inv), fy = std::floor(pm.y() * inv);
    Cell* c = cell(static_cast<std::int64_t>(fx), static_cast<std::int64_t>(fy), true);
    if (c->n == 0 && c->standing == 0) ++cells_;
    if (ground) {
      c->refl_sum += static_cast<float>(intensity[i] / cos);
      c->z_sum += static_cast<float>(pm.z());
      ++c->n;
    } else {
      c->sx += static_cast<float>(pm.x() - fx * p_.cell);
      c->sy += static_cast<float>(pm.y() - fy * p_.cell);
      c->s_zmax = std::max(c->s_zmax, static_cast<float>(pm.z()));
      ++c->standing;
    }
  }
}

RoadSurface::Sample RoadSurface::at(double x, double y, double standing_value) const {
  Sample out;
  // Cell centres at (i + 0.5) · cell: the four round (x, y) and the weights of each.
  const double u = x / p_.cell - 0.5, v = y / p_.cell - 0.5;
  const std::int64_t i0 = static_cast<std::int64_t>(std::floor(u)), j0 = static_cast<std::int64_t>(std::floor(v));
  const double fu = u - static_cast<double>(i0), fv = v - static_cast<double>(j0);
  const Cell* cells[4];
  double w[4];
  double zw = 0, z = 0;
  for (int k = 0; k < 4; ++k) {
    const int di = k & 1, dj = k >> 1;
    cells[k] = cell(i0 + di, j0 + dj);
    w[k] = (di ? fu : 1 - fu) * (dj ? fv : 1 - fv) + 1e-9;
    if (cells[k] && cells[k]->n > 0) {
      z += w[k] * cells[k]->z_sum / cells[k]->n;
      zw += w[k];
    }
  }
  double w_sum = 0, r = 0, standing_n = 0;
  Eigen::Vector2d standing_at = Eigen::Vector2d::Zero();
  for (int k = 0; k < 4; ++k) {
    const Cell* c = cells[k];
    if (!c) continue;
    // Standing: rising standing_height above the ground here (its own cell's, else round it), and
    // not a few strays among the road's returns.
    const double ground = c->n > 0 ? c->z_sum / c->n : zw > 0 ? z / zw : -1e30;
    if (c->standing > 0 && c->standing >= p_.standing_share * c->n && c->s_zmax - ground >= p_.standing_height) {
      r += w[k] * standing_value;
      const Eigen::Vector2d corner(static_cast<double>(i0 + (k & 1)) * p_.cell, static_cast<double>(j0 + (k >> 1)) * p_.cell);
      standing_at += c->standing * (corner + Eigen::Vector2d(c->sx, c->sy) / c->standing);
      standing_n += c->standing;
      out.standing = true;
      w_sum += w[k];
    } else if (c->n > 0) {
      r += w[k] * c->refl_sum / c->n;
      w_sum += w[k];
    }
  }
  if (w_sum <= 0) return out;
  out.known = true;
  out.reflectivity = r / w_sum;
  if (standing_n > 0) out.standing_at = standing_at / standing_n;
  out.has_z = zw > 0;
  out.z = out.has_z ? z / zw : 0.0;
  return out;
}

}  // namespace brickyard::mapping
