#include "lidar.hpp"
#include "lidar_march.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace brickyard::sim {

std::vector<double> row_elevations(int rows, double lo_deg, double hi_deg, const std::string& spacing,
                                   double exponent) {
  std::vector<double> e(rows);
  const double lo = lo_deg * M_PI / 180, hi = hi_deg * M_PI / 180;
  for (int i = 0; i < rows; ++i) {
    double u = rows == 1 ? 0.5 : static_cast<double>(i) / (rows - 1);  // 0..1, bottom to top
    if (spacing == "horizon") {
      double w = 2 * u - 1;  // -1..1
      double m = std::pow(std::abs(w), exponent);
      e[i] = w < 0 ? lo * m : hi * m;
    } else {
      e[i] = lo + (hi - lo) * u;
    }
  }
  return e;
}

LidarCaster::LidarCaster(const Track& track, LidarSpec spec) : track_(track), spec_(std::move(spec)) {
  const auto& w = track.spec();
  const std::vector<int> pylon_seg = sort_pylons_by_segment();
  build_segments(pylon_seg);
  build_blocks(pylon_seg);
  find_tops_within_reach();
  wall_left_ = w.walls.left;
  wall_right_ = w.walls.right;
  wall_left_off_ = w.walls.left_offset;
  wall_right_off_ = w.walls.right_offset;
  wall_h_ = w.walls.height;
  body_from_sensor_ = Eigen::Translation3d(spec_.mount) * Eigen::AngleAxisd(spec_.yaw, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(spec_.pitch, Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(spec_.roll, Eigen::Vector3d::UnitX());
  build_ray_directions();
  bound_road_slope();
}

std::vector<int> LidarCaster::sort_pylons_by_segment() {
  const Track& track = track_;
  pylons_ = track.spec().pylons;
  std::vector<int> pseg(pylons_.size());
  for (std::size_t i = 0; i < pylons_.size(); ++i) pseg[i] = track.project(pylons_[i].x, pylons_[i].y).seg;
  std::vector<std::size_t> order(pylons_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return pseg[a] < pseg[b]; });
  std::vector<Pylon> sorted;
  std::vector<int> sorted_seg;
  for (auto i : order) { sorted.push_back(pylons_[i]); sorted_seg.push_back(pseg[i]); }
  pylons_ = sorted;
  return sorted_seg;
}

void LidarCaster::build_segments(const std::vector<int>& pylon_seg) {
  const Track& track = track_;
  const auto& w = track.spec();
  const int n = track.size();
  seg_.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto& s = track.segments()[i];
    int j = track.wrap(i + 1);
    Seg& g = seg_[i];
    g.px = s.p.x(); g.py = s.p.y(); g.tx = s.t.x(); g.ty = s.t.y(); g.len = s.length;
    g.wl0 = w.line.width_left[i]; g.dwl = (w.line.width_left[j] - g.wl0) / s.length;
    g.wr0 = w.line.width_right[i]; g.dwr = (w.line.width_right[j] - g.wr0) / s.length;
    g.tb0 = std::tan(w.bank[i]); g.dtb = (std::tan(w.bank[j]) - g.tb0) / s.length;
    g.inv_n0 = 1 / std::sqrt(1 + g.tb0 * g.tb0);
    g.wall_l = w.walls.left ? g.wl0 + w.walls.left_offset : kInf;
    g.wall_r = w.walls.right ? -(g.wr0 + w.walls.right_offset) : -kInf;
    g.pylon_begin = static_cast<int>(std::lower_bound(pylon_seg.begin(), pylon_seg.end(), i) - pylon_seg.begin());
    g.pylon_end = static_cast<int>(std::upper_bound(pylon_seg.begin(), pylon_seg.end(), i) - pylon_seg.begin());
  }
}

void LidarCaster::build_blocks(const std::vector<int>& pylon_seg) {
  const Track& track = track_;
  const auto& w = track.spec();
  const int n = track.size();
  const int nb = (n + kBlock - 1) / kBlock;
  blocks_.resize(nb);
  for (int b = 0; b < nb; ++b) {
    const int first = b * kBlock, last = std::min(n, first + kBlock) - 1;
    const auto& S = track.segments();
    Block& B = blocks_[b];
    const Eigen::Vector2d p0 = S[first].p, p1 = S[last].p + S[last].t * S[last].length;
    B.sx = p0.x(); B.sy = p0.y(); B.stx = S[first].t.x(); B.sty = S[first].t.y();
    B.ex = p1.x(); B.ey = p1.y(); B.etx = S[last].t.x(); B.ety = S[last].t.y();
    const Eigen::Vector2d chord = (p1 - p0).normalized();
    B.cx = p0.x(); B.cy = p0.y(); B.ctx = chord.x(); B.cty = chord.y();
    auto chord_d = [&](const Eigen::Vector2d& q) { return (q.y() - p0.y()) * chord.x() - (q.x() - p0.x()) * chord.y(); };
    B.z_max = -kInf;
    B.dl_safe = kInf;
    B.dr_safe = -kInf;
    for (int i = first; i <= last + 1; ++i) {
      const int ii = track.wrap(i);
      const int sg = std::min(i, last);  // the normal of the segment the point belongs to
      const Eigen::Vector2d P = S[ii].p, nrm = S[sg].n;
      const double wl = w.line.width_left[ii], wr = w.line.width_right[ii], tb = std::tan(w.bank[ii]);
      B.z_max = std::max({B.z_max, wl * tb, -wr * tb});
      if (w.walls.left) B.dl_safe = std::min(B.dl_safe, chord_d(P + nrm * (wl + w.walls.left_offset)));
      if (w.walls.right) B.dr_safe = std::max(B.dr_safe, chord_d(P - nrm * (wr + w.walls.right_offset)));
    }
    // Margins for what lies between the sampled points (wall lines are straight between them).
    B.dl_safe -= 0.25;
    B.dr_safe += 0.25;
    B.z_max += 0.01;
  }
  for (std::size_t i = 0; i < pylons_.size(); ++i) {
    Block& B = blocks_[pylon_seg[i] / kBlock];
    B.z_max = std::max(B.z_max, pylons_[i].z + pylons_[i].height + 0.01);
  }
}

// Highest point within reach of a block: of every block that may come within max range of it.
// Two points of blocks b and c are at least (distance of their nearest end points - length of
// b - length of c) apart, so that bound decides.
void LidarCaster::find_tops_within_reach() {
  const auto& w = track_.spec();
  const int n = static_cast<int>(seg_.size()), nb = static_cast<int>(blocks_.size());
  std::vector<double> top(nb), blen(nb, 0.0);
  for (int i = 0; i < n; ++i) blen[i / kBlock] += seg_[i].len;
  const double wall_h = (w.walls.left || w.walls.right) ? w.walls.height : 0.0;
  for (int b = 0; b < nb; ++b) top[b] = blocks_[b].z_max + wall_h;
  for (int b = 0; b < nb; ++b) {
    const Block& B = blocks_[b];
    double zt = top[b];
    for (int c = 0; c < nb; ++c) {
      const Block& C = blocks_[c];
      double gap = std::min({std::hypot(B.sx - C.sx, B.sy - C.sy), std::hypot(B.ex - C.ex, B.ey - C.ey),
                             std::hypot(B.sx - C.ex, B.sy - C.ey), std::hypot(B.ex - C.sx, B.ey - C.sy)});
      if (gap <= spec_.max_range + blen[b] + blen[c]) zt = std::max(zt, top[c]);
    }
    blocks_[b].z_top_near = zt;
    z_top_all_ = std::max(z_top_all_, zt);
  }
}

void LidarCaster::build_ray_directions() {
  for (int c = 0; c < spec_.columns; ++c) {
    double a = spec_.columns == 1 ? 0.0 : spec_.h_fov / 2 - spec_.h_fov * c / (spec_.columns - 1);
    col_c_.push_back(std::cos(a));
    col_s_.push_back(std::sin(a));
  }
  std::vector<double> rows = spec_.elevations;
  std::sort(rows.begin(), rows.end());
  for (double e : rows) {
    row_c_.push_back(std::cos(e));
    row_s_.push_back(std::sin(e));
  }
}

// Steepest the road can be, in the slab frame the march uses: tan(bank) across, d * d(tan
// bank)/da and the edges' slope along; along-track distances on a curve's outside are
// stretched by 1 / (1 - curvature * d) against a.
void LidarCaster::bound_road_slope() {
  const Track& track = track_;
  const auto& w = track.spec();
  const int n = static_cast<int>(seg_.size());
  for (int i = 0; i < n; ++i) {
    const Seg& g = seg_[i];
    const Seg& h = seg_[track.wrap(i + 1)];
    const double tb = std::max(std::abs(g.tb0), std::abs(g.tb0 + g.dtb * g.len));
    const double wide = std::max({g.wl0, g.wl0 + g.dwl * g.len, g.wr0, g.wr0 + g.dwr * g.len});
    const double turn = std::abs(g.tx * h.ty - g.ty * h.tx) / g.len;  // ~ curvature
    const double reach = wide + std::max(w.walls.left_offset, w.walls.right_offset) + 1.0;
    const double stretch = turn * reach < 0.9 ? 1.0 / (1.0 - turn * reach) : 10.0;
    const double along = reach * std::abs(g.dtb) + std::max(std::abs(g.dwl), std::abs(g.dwr)) * tb;
    slope_max_ = std::max(slope_max_, tb + along * stretch);
  }
}

RayHit LidarCaster::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int k, const Resume* from, double shift,
                         double shift_rest, Resume* checkpoint) const {
  return march(o, v, k, from, shift, shift_rest, checkpoint);
}


// Row r escaped: its path, horizontally the segment from o along h_r = (its direction's x, y) to
// t_e, kept above the road and more than `margin` from every wall line, and met no pylon slab.
// Row q above it: at t, it is over the point of row r's path at ρ t (ρ = h_q·h_r / |h_r|²), off it
// sideways by λ t (λ = |h_q × h_r| / |h_r|), and higher than row r there by t (v_qz − ρ v_rz).
// Until it rises over the highest point of the world (t ≤ L), it surely meets nothing when
//   ρ L ≤ t_e            (it stays over the part of the path row r cleared),
//   λ L < margin         (its sideways offset never reaches a wall line),
//   v_qz − ρ v_rz ≥ slope_max λ   (it is higher than the road can rise over the offset),
//   no pylon within its radius + λ L of row r's path;
// and past L it is above everything and rising. The rows are then not cast: their output (no
// points, no random draws) is the same. With the sensor level, λ = 0 and ρ < 1; a banked car rolls
// the sensor, and L keeps the sideways drift of the steep rows small.
bool LidarCaster::rows_above_escape(const Eigen::Vector3d* dw, int r, int rows, double oz, const Resume& esc,
                                    const std::vector<int>& near_pylons, const Eigen::Vector3d& o) const {
  const double hx = dw[r].x(), hy = dw[r].y(), hh = hx * hx + hy * hy;
  if (!(hh > 0)) return false;
  const double inv_hh = 1 / hh, inv_h = 1 / std::sqrt(hh), max_t = spec_.max_range;
  double reach = 0;  // the largest sideways offset of any row above
  for (int q = r + 1; q < rows; ++q) {
    const double qx = dw[q].x(), qy = dw[q].y(), qz = dw[q].z();
    const double rho = (qx * hx + qy * hy) * inv_hh, lam = std::abs(qx * hy - qy * hx) * inv_h;
    if (!(rho >= 0) || qz - rho * dw[r].z() < slope_max_ * lam) return false;
    const double L = qz > 0 ? std::min(max_t, std::max(0.0, (z_top_all_ - oz) / qz)) : max_t;
    if (rho * L > esc.escape_t || lam * L >= esc.escape_margin) return false;
    reach = std::max(reach, lam * L);
  }
  // Pylons: horizontal distance from each to row r's path.
  const double ex = hx * esc.escape_t, ey = hy * esc.escape_t, ee = ex * ex + ey * ey;
  for (int i : near_pylons) {
    const Pylon& c = pylons_[i];
    const double px = c.x - o.x(), py = c.y - o.y();
    const double u = std::clamp((px * ex + py * ey) / ee, 0.0, 1.0);
    if (std::hypot(px - u * ex, py - u * ey) <= c.radius + reach + 1e-6) return false;
  }
  return true;
}

LidarCaster::Frame LidarCaster::begin_frame(const Eigen::Isometry3d& world_from_body, int seg_hint, double noise_factor,
                                             PointBuffers& out, const std::vector<CarBody>& cars) const {
  Frame f;
  const Eigen::Isometry3d ws = world_from_body * body_from_sensor_;
  f.o = ws.translation();
  f.R = ws.linear();
  f.seg = track_.project(f.o.x(), f.o.y(), seg_hint).seg;
  f.sigma = spec_.range_noise * noise_factor;
  f.rays = static_cast<std::size_t>(spec_.columns) * row_c_.size();
  out.x.reserve(out.x.size() + f.rays);
  out.y.reserve(out.y.size() + f.rays);
  out.z.reserve(out.z.size() + f.rays);
  out.intensity.reserve(out.intensity.size() + f.rays);
  // Pylons a ray of this frame can reach, for rows_above_escape.
  for (std::size_t i = 0; i < pylons_.size(); ++i)
    if (std::hypot(pylons_[i].x - f.o.x(), pylons_[i].y - f.o.y()) <= spec_.max_range + pylons_[i].radius)
      f.near_pylons.push_back(static_cast<int>(i));
  if (!cars.empty()) f.cars = FrameCars(cars, f.o, f.R, spec_.h_fov, spec_.max_range, col_c_, col_s_, row_c_, row_s_);
  return f;
}

RayHit LidarCaster::with_cars(const Frame& f, const RayHit& world, int r, int c) const {
  const CarHit k = f.cars.first_hit(r, c, world.surface == Surface::none ? 0.0 : world.range);
  return k.t > 0 ? RayHit{k.t, Surface::car, k.cos_incidence} : world;
}

// Ray by ray (no AVX2, or spec.simd off).
std::size_t LidarCaster::scan_one_by_one(const Frame& f, Rng& rng, PointBuffers& out) const {
  const auto& [o, R, seg, sigma, rays, near_pylons, cars] = f;
  // Rows go from the lowest up. The next row's ray lies within `shift` * t of this one
  // horizontally and higher by more than the road can rise over that distance, so it passes
  // over all road this one passed over; if this one also kept more than shift * t from the walls
  // and met no pylon, the next starts where this one's last slab began (`checkpoint`), and when
  // this one escapes (to max range, or above everything), so do all above it.
  const int rows = static_cast<int>(row_c_.size());
  std::vector<Eigen::Vector3d> dw(rows);
  std::vector<double> shift(rows), rest(rows);
  Staging st(rows);
  // A ray's direction is row_c (col_c, col_s, 0) + row_s (0, 0, 1) in the sensor frame: in the
  // world, row_c U + row_s Z with U per column and Z per frame (6 flops a ray, not a 3x3 product).
  const Eigen::Vector3d Z = R.col(2);
  for (int c = 0; c < spec_.columns; ++c) {
    const Eigen::Vector3d U = R.col(0) * col_c_[c] + R.col(1) * col_s_[c];
    for (int r = 0; r < rows; ++r) dw[r] = row_c_[r] * U + row_s_[r] * Z;
    for (int r = rows - 1; r >= 0; --r) {
      shift[r] = rest[r] = -1;
      if (r + 1 == rows || !spec_.coherent_columns) continue;
      const double ax = dw[r + 1].x() - dw[r].x(), ay = dw[r + 1].y() - dw[r].y(), apart = std::sqrt(ax * ax + ay * ay);
      if (dw[r + 1].z() - dw[r].z() <= slope_max_ * apart) continue;
      shift[r] = apart;
      rest[r] = r + 2 == rows ? apart : rest[r + 1] >= 0 ? apart + rest[r + 1] : -1;
    }
    // A column a car may be in: every ray is also held against the cars, the rows above an
    // escape too (the world returns nothing there, a car may).
    const bool sees_car = cars.sees(c);
    Resume from, checkpoint;
    bool resume = false;
    for (int r = 0; r < rows; ++r) {
      RayHit h = march(o, dw[r], seg, resume ? &from : nullptr, shift[r], rest[r], shift[r] >= 0 ? &checkpoint : nullptr);
      resume = shift[r] >= 0 && checkpoint.seg >= 0;
      from = checkpoint;
      const bool rest_escape =
          h.surface == Surface::none && shift[r] >= 0 &&
          (checkpoint.rest_escape || (spec_.skip_escaped_rows && checkpoint.escape_t > 0 &&
                                      rows_above_escape(dw.data(), r, rows, o.z(), checkpoint, near_pylons, o)));
      if (sees_car) h = with_cars(f, h, r, c);
      if (h.surface != Surface::none) add_point(h, r, c, sigma, rng, st);
      if (!rest_escape) continue;
      for (int q = r + 1; q < rows && sees_car; ++q)
        if (const RayHit k = with_cars(f, RayHit{}, q, c); k.surface != Surface::none) add_point(k, q, c, sigma, rng, st);
      break;
    }
    st.flush(out);
  }
  return rays;
}

std::size_t LidarCaster::scan(const Eigen::Isometry3d& world_from_body, int seg_hint, Rng& rng, double noise_factor,
                              PointBuffers& out, const std::vector<CarBody>& cars) const {
  const Frame f = begin_frame(world_from_body, seg_hint, noise_factor, out, cars);
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && spec_.simd) return scan_avx2(f, rng, out);
#endif
  return scan_one_by_one(f, rng, out);
}

}  // namespace brickyard::sim
