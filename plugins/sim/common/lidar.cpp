#include "lidar.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace brickyard::sim {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

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
  const int n = track.size();
  pylons_ = w.pylons;
  std::vector<int> pseg(pylons_.size());
  for (std::size_t i = 0; i < pylons_.size(); ++i) pseg[i] = track.project(pylons_[i].x, pylons_[i].y).seg;
  std::vector<std::size_t> order(pylons_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return pseg[a] < pseg[b]; });
  std::vector<Pylon> sorted;
  std::vector<int> sorted_seg;
  for (auto i : order) { sorted.push_back(pylons_[i]); sorted_seg.push_back(pseg[i]); }
  pylons_ = sorted;
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
    g.pylon_begin = static_cast<int>(std::lower_bound(sorted_seg.begin(), sorted_seg.end(), i) - sorted_seg.begin());
    g.pylon_end = static_cast<int>(std::upper_bound(sorted_seg.begin(), sorted_seg.end(), i) - sorted_seg.begin());
  }
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
    Block& B = blocks_[sorted_seg[i] / kBlock];
    B.z_max = std::max(B.z_max, pylons_[i].z + pylons_[i].height + 0.01);
  }
  // Highest point within reach of a block: of every block that may come within max range of it.
  // Two points of blocks b and c are at least (distance of their nearest end points - length of
  // b - length of c) apart, so that bound decides.
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
  wall_left_ = w.walls.left;
  wall_right_ = w.walls.right;
  wall_left_off_ = w.walls.left_offset;
  wall_right_off_ = w.walls.right_offset;
  wall_h_ = w.walls.height;
  body_from_sensor_ = Eigen::Translation3d(spec_.mount) * Eigen::AngleAxisd(spec_.yaw, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(spec_.pitch, Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(spec_.roll, Eigen::Vector3d::UnitX());
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
  // Steepest the road can be, in the slab frame the march uses: tan(bank) across, d * d(tan
  // bank)/da and the edges' slope along; along-track distances on a curve's outside are
  // stretched by 1 / (1 - curvature * d) against a.
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

namespace {
// The first t in [ta, tb] where a ray (a = a0 + va t, d = d0 + vd t, z = oz + vz t in the slab of
// g) meets the road, given it is above the road at ta and not at tb (f_tb = its height there).
// In closed form: the cross-section is straight between the edges and level beyond them, so the
// edges' crossings (linear in t) cut [ta, tb] into at most three pieces, and on each the road's
// height — the cross-section coordinate (d, or an edge's) times tan(bank), both linear in t — is a
// quadratic in t. (Regula falsi here took 4-8 evaluations per ray.)
template <class Seg>
double road_root(const Seg& g, double a0, double va, double d0, double vd, double oz, double vz, double ta, double tb,
                 double f_tb) {
  double cuts[2];
  int nc = 0;
  // An edge (num = den t) is crossed inside [ta, tb] only if num - den t changes sign there:
  // most rays cross none, and skip the division.
  auto cut = [&](double num, double den) {
    if ((num - den * ta) * (num - den * tb) < 0 && std::abs(den) > 1e-12) {
      const double t = num / den;
      if (t > ta && t < tb) cuts[nc++] = t;
    }
  };
  cut(g.wl0 + g.dwl * a0 - d0, vd - g.dwl * va);
  cut(-(g.wr0 + g.dwr * a0) - d0, vd + g.dwr * va);
  if (nc == 2 && cuts[0] > cuts[1]) std::swap(cuts[0], cuts[1]);
  const double b0 = g.tb0 + g.dtb * a0, b1 = g.dtb * va;
  double lo = ta;
  for (int k = 0; k <= nc; ++k) {
    const double hi = k < nc ? cuts[k] : tb;
    // Which piece: the middle of the interval says.
    const double tm = 0.5 * (lo + hi), am = a0 + va * tm, dm = d0 + vd * tm;
    double c0 = d0, c1 = vd;
    if (dm > g.wl0 + g.dwl * am) { c0 = g.wl0 + g.dwl * a0; c1 = g.dwl * va; }
    else if (dm < -(g.wr0 + g.dwr * am)) { c0 = -(g.wr0 + g.dwr * a0); c1 = -g.dwr * va; }
    // Height over the road: C + B t + A t².
    const double A = -c1 * b1, B = vz - c0 * b1 - c1 * b0, C = oz - c0 * b0;
    const double f_hi = k < nc ? C + hi * (B + A * hi) : f_tb;
    if (f_hi > 0) {
      lo = hi;
      continue;
    }
    double root = hi;
    if (std::abs(A) * (hi - lo) < 1e-12 * std::abs(B)) {
      if (B != 0) root = -C / B;
    } else {
      const double disc = B * B - 4 * A * C;
      if (disc >= 0) {
        const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
        const double r1 = q / A, r2 = q != 0 ? C / q : r1;
        const double eps = 1e-9 * (1 + std::abs(hi));
        root = hi;
        for (double r : {r1, r2})
          if (r >= lo - eps && r <= hi + eps) root = std::min(root, r);
      }
    }
    return std::clamp(root, lo, hi);
  }
  return tb;
}
}  // namespace

RayHit LidarCaster::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int k, const Resume* from, double shift,
                         double shift_rest, Resume* checkpoint) const {
  return march(o, v, k, from, shift, shift_rest, checkpoint);
}

// The march itself, inlined into scan's row loop (a call per ray cost ~ 5 % there).
[[gnu::always_inline]] inline RayHit LidarCaster::march(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int k,
                                                         const Resume* from, double shift, double shift_rest,
                                                         Resume* checkpoint) const {
  // March from slab to slab (the region of a segment between the planes normal to it at its
  // ends). Within a slab, the ray's along (a) and across (d) coordinates are linear in t, so the
  // wall lines are crossed at a t found in closed form and the road (a straight cross-section
  // whose bank varies linearly) by a few regula falsi steps.
  const double max_t = spec_.max_range;
  const int n = static_cast<int>(seg_.size());
  const double ox = o.x(), oy = o.y(), oz = o.z(), vx = v.x(), vy = v.y(), vz = v.z();
  RayHit best;
  double best_t = max_t;
  int dir = 0;
  double t0 = 0;
  // For the checkpoint: the least distance to a wall line along the path so far, and whether a
  // slab with pylons has been entered (past it, no checkpoint: pylons are not in the margin).
  double margin = kInf;
  bool checkpoints = checkpoint != nullptr;
  if (checkpoint) *checkpoint = Resume{0, -1, 0, false};
  // This ray escapes at t: so do the rays above it when the path up to t kept clear of the walls.
  auto escape = [&](double t) {
    if (!checkpoints) return;
    if (shift_rest >= 0 && margin - t * shift_rest > 0) checkpoint->rest_escape = true;
    if (margin > 0) {
      checkpoint->escape_t = t;
      checkpoint->escape_margin = margin;
    }
  };
  if (from && from->seg >= 0) {
    t0 = from->t;
    k = from->seg;
    margin = from->margin;
  }
  for (int steps = 0; steps < n; ++steps) {
    if (checkpoints) {
      // Not into a slab with pylons: the next ray enters it at another t, and the pylon's face
      // may lie between the two.
      if (seg_[k].pylon_begin < seg_[k].pylon_end) checkpoints = false;
      else if (margin - t0 * shift > 0) *checkpoint = Resume{t0, k, margin - t0 * shift};
    }
    if (vz >= 0 && oz + vz * t0 > blocks_[k / kBlock].z_top_near) {  // rising above all in reach
      escape(t0);
      break;
    }
    // Entering a block: cross it in one step when nothing in it can be reached.
    if (spec_.use_blocks && steps > 0 && (dir > 0 ? k % kBlock == 0 : (k % kBlock == kBlock - 1 || k == n - 1))) {
      const Block& B = blocks_[k / kBlock];
      const double px = dir > 0 ? B.ex : B.sx, py = dir > 0 ? B.ey : B.sy;
      const double nx = dir > 0 ? B.etx : B.stx, ny = dir > 0 ? B.ety : B.sty;
      const double vn = vx * nx + vy * ny;
      if (dir > 0 ? vn > 1e-12 : vn < -1e-12) {
        const double t_out = ((px - ox) * nx + (py - oy) * ny) / vn;
        if (t_out > t0 && std::min(oz + vz * t0, oz + vz * std::min(t_out, max_t)) > B.z_max) {
          auto cd = [&](double t) { return (oy + vy * t - B.cy) * B.ctx - (ox + vx * t - B.cx) * B.cty; };
          const double di = cd(t0), de = cd(t_out);
          if (std::max(di, de) < B.dl_safe && std::min(di, de) > B.dr_safe) {
            margin = std::min({margin, B.dl_safe - std::max(di, de), std::min(di, de) - B.dr_safe});
            if (t_out >= max_t) {
              escape(max_t);
              break;
            }
            t0 = t_out;
            k = dir > 0 ? std::min(n, (k / kBlock + 1) * kBlock) % n
                        : ((k / kBlock) * kBlock - 1 + n) % n;
            steps += kBlock - 1;
            continue;
          }
        }
      }
    }
    const Seg& g = seg_[k];
    const double rx = ox - g.px, ry = oy - g.py;
    const double a0 = rx * g.tx + ry * g.ty, va = vx * g.tx + vy * g.ty;
    const double d0 = ry * g.tx - rx * g.ty, vd = vy * g.tx - vx * g.ty;
    if (dir == 0) dir = va >= 0 ? 1 : -1;
    double t1 = kInf;
    if (dir > 0 ? va > 1e-12 : va < -1e-12) t1 = std::max((dir > 0 ? g.len - a0 : -a0) / va, t0);
    // Height of the ray above the road at t.
    auto above = [&](double t) {
      const double a = std::clamp(a0 + va * t, 0.0, g.len), d = d0 + vd * t;
      return oz + vz * t - std::clamp(d, -(g.wr0 + g.dwr * a), g.wl0 + g.dwl * a) * (g.tb0 + g.dtb * a);
    };
    double te = std::min(t1, best_t);
    // Pylons standing in this segment: vertical cylinders.
    for (int p = g.pylon_begin; p < g.pylon_end; ++p) {
      const Pylon& c = pylons_[p];
      const double cx = ox - c.x, cy = oy - c.y;
      const double A = vx * vx + vy * vy, B = cx * vx + cy * vy, C = cx * cx + cy * cy - c.radius * c.radius;
      const double disc = B * B - A * C;
      if (A < 1e-12 || disc < 0) continue;
      const double t = (-B - std::sqrt(disc)) / A;
      if (t < t0 || t >= te) continue;
      const double z = oz + vz * t;
      if (z < c.z || z > c.z + c.height) continue;
      te = best_t = t;
      best.surface = Surface::pylon;
      best.cos_incidence = std::abs((cx + vx * t) * vx + (cy + vy * t) * vy) / (c.radius * std::sqrt(A) + 1e-12);
    }
    // Walls: is the ray beyond a wall line at the end of its stretch in this slab?
    double t_wall = kInf;
    if (std::isfinite(te)) {
      const double ae = std::clamp(a0 + va * te, 0.0, g.len), de = d0 + vd * te;
      if (de >= g.wall_l + g.dwl * ae) {
        const double den = vd - g.dwl * va;  // d0 + vd t = wall_l + dwl (a0 + va t)
        if (den > 1e-12) t_wall = std::clamp((g.wall_l + g.dwl * a0 - d0) / den, t0, te);
      } else if (de <= g.wall_r - g.dwr * ae) {
        const double den = vd + g.dwr * va;  // d0 + vd t = wall_r - dwr (a0 + va t)
        if (den < -1e-12) t_wall = std::clamp((g.wall_r - g.dwr * a0 - d0) / den, t0, te);
      }
    } else {
      // The ray runs along this slab for ever (parallel to its end planes): it leaves by a wall.
      if (vd > 1e-12 && std::isfinite(g.wall_l)) t_wall = std::max((g.wall_l + g.dwl * a0 - d0) / (vd - g.dwl * va), t0);
      if (vd < -1e-12 && std::isfinite(g.wall_r)) t_wall = std::max((g.wall_r - g.dwr * a0 - d0) / (vd + g.dwr * va), t0);
      if (t_wall > max_t) t_wall = kInf;
    }
    const double tf = std::min({te, t_wall, max_t});
    const double f1 = above(tf);
    if (f1 <= 0) {
      double lo = t0, hi = tf, flo = above(t0), fhi = f1, t = hi;
      if (flo > 0) {
        t = road_root(g, a0, va, d0, vd, oz, vz, lo, hi, fhi);
      } else {
        t = t0;
      }
      best_t = t;
      best.surface = Surface::road;
      const double a = std::clamp(a0 + va * t, 0.0, g.len), d = d0 + vd * t;
      const bool on_road = d <= g.wl0 + g.dwl * a && d >= -(g.wr0 + g.dwr * a);
      // Surface normal (-grad z, 1): grad z = tan(bank) * (left normal) on the road, 0 beyond.
      const double tb = on_road ? g.tb0 + g.dtb * a : 0.0;
      const double gx = -tb * g.ty, gy = tb * g.tx;
      // |n . v| with n = (-grad z, 1) / |(-grad z, 1)|; the norm is the segment's own when its
      // bank is constant (most segments), so no square root and division per ray there.
      const double inv_n = !on_road ? 1.0 : g.dtb == 0 ? g.inv_n0 : 1 / std::sqrt(1 + tb * tb);
      best.cos_incidence = std::abs(-gx * vx - gy * vy + vz) * inv_n;
      break;
    }
    if (best.surface == Surface::pylon && best_t <= tf) break;
    if (t_wall <= tf) {
      // The wall stands on the road edge; over its top the world ends: nothing beyond returns.
      if (f1 <= wall_h_) {
        best_t = t_wall;
        best.surface = Surface::wall;
        best.cos_incidence = std::abs(vd);
      }
      break;
    }
    // The path's clearance from the walls: only a ray that goes on (or escapes here) needs it, so
    // it is not worked out for the slab where a ray hits something (most rays).
    if (checkpoints) {
      for (double t : {t0, tf}) {
        const double a = std::clamp(a0 + va * t, 0.0, g.len), d = d0 + vd * t;
        margin = std::min({margin, g.wall_l + g.dwl * a - d, d - (g.wall_r - g.dwr * a)});
      }
    }
    if (tf >= max_t) {
      if (best.surface == Surface::none) escape(max_t);
      break;
    }
    if (t1 >= best_t) break;
    t0 = t1;
    k = dir > 0 ? (k + 1 == n ? 0 : k + 1) : (k == 0 ? n - 1 : k - 1);
  }
  best.range = best.surface == Surface::none ? 0 : best_t;
  return best;
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

namespace {
// W doubles in SIMD lanes (GCC vector extensions) and their comparison masks. The helpers are
// std::min / std::max / std::clamp lane by lane, with libstdc++'s exact semantics.
template <int W> struct V {
  typedef double D __attribute__((vector_size(8 * W)));
  typedef long M __attribute__((vector_size(8 * W)));  // what comparisons of D give
};
template <class D> [[gnu::always_inline]] inline D vmin(D a, D b) { return b < a ? b : a; }
template <class D> [[gnu::always_inline]] inline D vmax(D a, D b) { return a < b ? b : a; }
template <class D> [[gnu::always_inline]] inline D vclamp(D v, D lo, D hi) { return vmin(vmax(v, lo), hi); }
template <class M> [[gnu::always_inline]] inline bool any(M m) {
  bool r = false;
  for (unsigned i = 0; i < sizeof(M) / 8; ++i) r |= m[i] != 0;
  return r;
}
template <class D> [[gnu::always_inline]] inline D vabs(D x) {  // std::abs: the sign bit cleared
  using M = decltype(x < x);
  return (D)((M)x & ~(M)(-D{}));
}
template <class D> [[gnu::always_inline]] inline D vsqrt(D x) {
  for (unsigned i = 0; i < sizeof(D) / 8; ++i) x[i] = std::sqrt(x[i]);
  return x;
}

// road_root for the lanes in `on`, lane by lane the same operations (the pieces' loop runs while
// some lane is still in it; a lane's result is taken at the piece where road_root returns).
template <class Seg, class D, class M>
[[gnu::always_inline]] inline D road_root_lanes(const Seg& g, M on, double a0, D va, double d0, D vd, double oz, D vz,
                                                 D ta, D tb, D f_tb) {
  const D zero{};
  M nc{};  // 0, -1 or -2: minus the number of cuts
  D cut0 = zero, cut1 = zero;
  auto cut = [&](double num, D den) __attribute__((always_inline)) {
    const M s = on & ((num - den * ta) * (num - den * tb) < 0) & (vabs(den) > 1e-12);
    if (!any(s)) return;  // (divisions only where needed: they are the dearest operations)
    const D t = num / den;
    const M c = s & (t > ta) & (t < tb);
    cut1 = (c & (nc != 0)) ? t : cut1;
    cut0 = (c & (nc == 0)) ? t : cut0;
    nc += c;
  };
  cut(g.wl0 + g.dwl * a0 - d0, vd - g.dwl * va);
  cut(-(g.wr0 + g.dwr * a0) - d0, vd + g.dwr * va);
  const M sw = (nc == -2) & (cut0 > cut1);
  const D c0s = sw ? cut1 : cut0, c1s = sw ? cut0 : cut1;
  const double b0 = g.tb0 + g.dtb * a0;
  const D b1 = g.dtb * va;
  D lo = ta, res = tb;
  M left = on;
  for (int k = 0; k <= 2 && any(left); ++k) {
    left &= (nc <= -k);  // lanes with a piece k (k <= their number of cuts)
    const M last = nc == -k;
    const D hi = last ? tb : k == 0 ? c0s : c1s;
    const D tm = 0.5 * (lo + hi), am = a0 + va * tm, dm = d0 + vd * tm;
    const M L = dm > g.wl0 + g.dwl * am, R = ~L & (dm < -(g.wr0 + g.dwr * am));
    const D c0 = L ? zero + (g.wl0 + g.dwl * a0) : R ? -(zero + (g.wr0 + g.dwr * a0)) : zero + d0;
    const D c1 = L ? g.dwl * va : R ? -g.dwr * va : vd;
    const D A = -c1 * b1, B = vz - c0 * b1 - c1 * b0, C = oz - c0 * b0;
    const D f_hi = last ? f_tb : C + hi * (B + A * hi);
    const M here = left & ~(f_hi > 0);
    if (any(here)) {
      const M lin = vabs(A) * (hi - lo) < 1e-12 * vabs(B);
      D root = hi;
      if (any(here & lin)) root = lin & (B != 0) ? -C / B : root;
      if (any(here & ~lin)) {
        const D disc = B * B - 4 * A * C;
        const M sign = (M)(-zero);
        const D q = -0.5 * (B + (D)(((M)vsqrt(disc) & ~sign) | ((M)B & sign)));
        const D r1 = q / A, r2 = q != 0 ? C / q : r1;
        const D eps = 1e-9 * (1 + vabs(hi));
        D rq = hi;
        rq = (r1 >= lo - eps) & (r1 <= hi + eps) ? vmin(rq, r1) : rq;
        rq = (r2 >= lo - eps) & (r2 <= hi + eps) ? vmin(rq, r2) : rq;
        root = lin ? root : disc >= 0 ? rq : hi;
      }
      res = here ? vclamp(root, lo, hi) : res;
      left &= ~here;
    }
    lo = hi;
  }
  return res;
}
}  // namespace

// A row of W columns, lane by lane (structure of arrays: loaded and stored as vectors). The
// checkpoint fields are march's Resume; a lane not keeping one (want_ck 0) leaves them as they were.
template <int W> struct LidarCaster::Lanes {
  using D = typename V<W>::D;
  using M = typename V<W>::M;
  D vx, vy, vz, shift, rest;                 // in: the rays, march's shift and shift_rest
  M on, use_from, want_ck;                    // in: lanes cast, resuming from from_*, keeping ck_*
  D from_t, from_m;                           // in: the Resume to start from
  M from_seg;
  D ck_t, ck_m, esc_t, esc_m;                 // out: the checkpoint
  M rest_esc;
  M ck_seg;
  D range, cos;                               // out: the hits
  M surf;                                     // out: the Surfaces
};

// march for the W rays of a row in neighbouring columns, in lockstep while all stay in the common
// case: one slab for all (its fields broadcast), no pylons, a block crossed by all or none. A lane
// that leaves it (a start slab more than two slabs off, another direction, a block only some lanes
// skip, a slab with pylons) is cast again by march from its start: march is a pure function of its
// arguments, so that is exact.
template <int W>
[[gnu::always_inline]] inline void LidarCaster::march_lanes(const Eigen::Vector3d& o, int seg, Lanes<W>& L) const {
  using D = typename V<W>::D;
  using M = typename V<W>::M;
  const int n = static_cast<int>(seg_.size());
  const double max_t = spec_.max_range, ox = o.x(), oy = o.y(), oz = o.z();
  const D inf = D{} + kInf, zero = D{}, vmax_t = D{} + max_t;
  const D vx = L.vx, vy = L.vy, vz = L.vz, shift = L.shift, rest = L.rest;
  const M fr = L.on & L.use_from;
  D t0 = fr ? L.from_t : zero, margin = fr ? L.from_m : inf;
  M act = L.on, to_scalar{}, waiting{};
  // Start slabs. The march starts at the first lane's, or up to two slabs behind it where another
  // lane starts there; the lanes starting ahead join when the march reaches their slab (each with
  // its own t0 and margin, as march would start it). Lanes further off go to march.
  const M kl = fr ? L.from_seg : M{} + seg;
  int f = 0;
  while (!act[f]) ++f;
  int k = static_cast<int>(kl[f]);
  int dir = vx[f] * seg_[k].tx + vy[f] * seg_[k].ty >= 0 ? 1 : -1;  // lane f's, as march sets it
  if (any(act & (kl != k))) {
    int back = 0, off[W];
    for (int l = 0; l < W; ++l) {
      off[l] = ((static_cast<int>(kl[l]) - k) * dir % n + n) % n;  // slabs ahead of k along dir
      if (off[l] > n / 2) off[l] -= n;
      if (act[l] && off[l] < 0 && off[l] >= -2) back = std::min(back, off[l]);
    }
    k = ((k + back * dir) % n + n) % n;
    for (int l = 0; l < W; ++l)
      if (act[l] && (off[l] < back || off[l] > back + 2)) to_scalar[l] = -1;
  }
  waiting = act & ~to_scalar;  // all join at their start slab (the first step for most)
  act = M{};
  if (!std::isfinite(max_t)) {  // (the lanes' march assumes a finite range)
    to_scalar |= waiting;
    waiting = M{};
  }
  const M ckm = waiting & L.want_ck;
  L.range = zero;
  L.cos = zero + 1.0;
  L.surf = M{};
  // Resume{0, -1, 0, false} for the lanes keeping a checkpoint.
  D ck_t = ckm ? zero : L.ck_t, ck_m = ckm ? zero : L.ck_m, esc_t = ckm ? zero : L.esc_t, esc_m = ckm ? zero : L.esc_m;
  M rest_esc = ckm ? M{} : L.rest_esc;
  M ck_seg = ckm ? M{} - 1 : L.ck_seg;
  auto escape = [&](M e, D t) __attribute__((always_inline)) {
    e &= ckm;
    rest_esc |= e & (rest >= 0) & (margin - t * rest > 0);
    const M em = e & (margin > 0);
    esc_t = em ? t : esc_t;
    esc_m = em ? margin : esc_m;
  };
  for (int steps = 0; any(act | waiting); ++steps) {
    const M fresh = waiting & (kl == k);  // lanes starting in this slab
    act |= fresh;
    waiting &= ~fresh;
    const Seg& g = seg_[k];
    if (steps >= n || g.pylon_begin < g.pylon_end) {
      to_scalar |= act | waiting;
      act = waiting = M{};
      break;
    }
    {
      const D m = margin - t0 * shift;
      const M c = ckm & act & (m > 0);
      ck_t = c ? t0 : ck_t;
      ck_m = c ? m : ck_m;
      ck_seg = c ? M{} + k : ck_seg;
    }
    {
      const M e = act & (vz >= 0) & (oz + vz * t0 > blocks_[k / kBlock].z_top_near);
      escape(e, t0);
      act &= ~e;
      if (!any(act | waiting)) break;
    }
    if (spec_.use_blocks && steps > 0 && (dir > 0 ? k % kBlock == 0 : (k % kBlock == kBlock - 1 || k == n - 1))) {
      const Block& B = blocks_[k / kBlock];
      const double px = dir > 0 ? B.ex : B.sx, py = dir > 0 ? B.ey : B.sy;
      const double nx = dir > 0 ? B.etx : B.stx, ny = dir > 0 ? B.ety : B.sty;
      const D vn = vx * nx + vy * ny;
      const M c1 = dir > 0 ? vn > 1e-12 : vn < -1e-12;
      const D t_out = ((px - ox) * nx + (py - oy) * ny) / vn;
      const M c2 = (t_out > t0) & (vmin(oz + vz * t0, oz + vz * vmin(t_out, vmax_t)) > B.z_max);
      auto cd = [&](D t) __attribute__((always_inline)) { return (oy + vy * t - B.cy) * B.ctx - (ox + vx * t - B.cx) * B.cty; };
      const D di = cd(t0), de = cd(t_out);
      const M skip = act & ~fresh & c1 & c2 & (vmax(di, de) < B.dl_safe) & (vmin(di, de) > B.dr_safe);
      if (any(act & ~skip)) {  // some lanes skip the block, some not: those that skip go to march
        to_scalar |= skip;
        act &= ~skip;
      } else if (any(skip)) {  // all skip it, in lockstep
        margin = act ? vmin(vmin(margin, B.dl_safe - vmax(di, de)), vmin(di, de) - B.dr_safe) : margin;
        const M out = act & (t_out >= max_t);
        escape(out, vmax_t);
        act &= ~out;
        t0 = act ? t_out : t0;
        k = dir > 0 ? std::min(n, (k / kBlock + 1) * kBlock) % n : ((k / kBlock) * kBlock - 1 + n) % n;
        steps += kBlock - 1;
        continue;
      }
      if (!any(act | waiting)) break;
    }
    const double rx = ox - g.px, ry = oy - g.py;
    const double a0 = rx * g.tx + ry * g.ty, d0 = ry * g.tx - rx * g.ty;
    const D va = vx * g.tx + vy * g.ty, vd = vy * g.tx - vx * g.ty;
    if (any(fresh)) {  // lanes going the other way along the line: march
      const M other = fresh & (dir > 0 ? ~(va >= 0) : (va >= 0));
      to_scalar |= other;
      act &= ~other;
    }
    const M c1 = dir > 0 ? va > 1e-12 : va < -1e-12;
    const D t1 = c1 ? vmax((dir > 0 ? g.len - a0 : -a0) / va, t0) : inf;
    const D te = vmin(t1, vmax_t);
    const D len = zero + g.len;
    const D ae = vclamp(a0 + va * te, zero, len), de = d0 + vd * te;
    const M wl = de >= g.wall_l + g.dwl * ae, wr = ~wl & (de <= g.wall_r - g.dwr * ae);
    const D denl = vd - g.dwl * va, denr = vd + g.dwr * va;
    const M wlc = act & wl & (denl > 1e-12), wrc = act & wr & (denr < -1e-12);
    D t_wall = inf;
    if (any(wlc)) t_wall = wlc ? vclamp((g.wall_l + g.dwl * a0 - d0) / denl, t0, te) : t_wall;
    if (any(wrc)) t_wall = wrc ? vclamp((g.wall_r - g.dwr * a0 - d0) / denr, t0, te) : t_wall;
    const D tf = vmin(vmin(te, t_wall), vmax_t);
    auto above = [&](D t) __attribute__((always_inline)) {
      const D a = vclamp(a0 + va * t, zero, len), d = d0 + vd * t;
      return oz + vz * t - vclamp(d, -(g.wr0 + g.dwr * a), g.wl0 + g.dwl * a) * (g.tb0 + g.dtb * a);
    };
    const D f1 = above(tf);
    const M road = act & (f1 <= 0);
    if (any(road)) {
      const D flo = above(t0);
      const M above_t0 = road & (flo > 0);
      const D t = any(above_t0) ? (above_t0 ? road_root_lanes(g, above_t0, a0, va, d0, vd, oz, vz, t0, tf, f1) : t0) : t0;
      const D a = vclamp(a0 + va * t, zero, len), d = d0 + vd * t;
      const M on_road = (d <= g.wl0 + g.dwl * a) & (d >= -(g.wr0 + g.dwr * a));
      const D tb = on_road ? g.tb0 + g.dtb * a : zero;
      const D gx = -tb * g.ty, gy = tb * g.tx;
      const D inv_n = on_road ? (g.dtb == 0 ? zero + g.inv_n0 : 1 / vsqrt(1 + tb * tb)) : zero + 1.0;
      L.range = road ? t : L.range;
      L.cos = road ? vabs(-gx * vx - gy * vy + vz) * inv_n : L.cos;
      L.surf = road ? M{} + static_cast<long>(Surface::road) : L.surf;
      act &= ~road;
    }
    const M wall = act & (t_wall <= tf);
    if (any(wall)) {
      for (int l = 0; l < W; ++l)
        if (wall[l] && f1[l] <= wall_h_) {
          L.range[l] = t_wall[l];
          L.surf[l] = static_cast<long>(Surface::wall);
          L.cos[l] = std::abs(vd[l]);
        }
      act &= ~wall;
    }
    for (D t : {t0, tf}) {
      const D a = vclamp(a0 + va * t, zero, len), d = d0 + vd * t;
      margin = act ? vmin(vmin(margin, g.wall_l + g.dwl * a - d), d - (g.wall_r - g.dwr * a)) : margin;
    }
    const M fin = act & (tf >= max_t);
    escape(fin, vmax_t);
    act &= ~fin & ~(t1 >= max_t);
    t0 = act ? t1 : t0;
    k = dir > 0 ? (k + 1 == n ? 0 : k + 1) : (k == 0 ? n - 1 : k - 1);
  }
  to_scalar |= waiting;  // (the march passed their slab in a block, or ended before it)
  L.ck_t = ck_t; L.ck_m = ck_m; L.esc_t = esc_t; L.esc_m = esc_m; L.rest_esc = rest_esc;
  L.ck_seg = ck_seg;
  if (!any(to_scalar)) return;
  for (int l = 0; l < W; ++l) {
    if (!to_scalar[l]) continue;
    Resume from{L.from_t[l], static_cast<int>(L.from_seg[l]), L.from_m[l]}, ck;
    const RayHit h = cast(o, Eigen::Vector3d(vx[l], vy[l], vz[l]), seg, L.use_from[l] ? &from : nullptr, shift[l], rest[l],
                          L.want_ck[l] ? &ck : nullptr);
    L.range[l] = h.range;
    L.surf[l] = static_cast<long>(h.surface);
    L.cos[l] = h.cos_incidence;
    if (L.want_ck[l]) {
      L.ck_t[l] = ck.t; L.ck_seg[l] = ck.seg; L.ck_m[l] = ck.margin; L.rest_esc[l] = ck.rest_escape ? -1 : 0;
      L.esc_t[l] = ck.escape_t; L.esc_m[l] = ck.escape_margin;
    }
  }
}

template <int W>
[[gnu::always_inline]] inline std::size_t LidarCaster::scan_lanes(const Eigen::Isometry3d& world_from_body,
                                                                   int seg_hint, Rng& rng, double noise_factor,
                                                                   PointBuffers& out) const {
  const Eigen::Isometry3d ws = world_from_body * body_from_sensor_;
  const Eigen::Vector3d o = ws.translation();
  const Eigen::Matrix3d R = ws.linear();
  const int seg = track_.project(o.x(), o.y(), seg_hint).seg;
  const double sigma = spec_.range_noise * noise_factor;
  const std::size_t rays = static_cast<std::size_t>(spec_.columns) * row_c_.size();
  out.x.reserve(out.x.size() + rays);
  out.y.reserve(out.y.size() + rays);
  out.z.reserve(out.z.size() + rays);
  out.intensity.reserve(out.intensity.size() + rays);
  // Rows go from the lowest up. The next row's ray lies within `shift` * t of this one
  // horizontally and higher by more than the road can rise over that distance, so it passes
  // over all road this one passed over; if this one also kept more than shift * t from the walls
  // and met no pylon, the next starts where this one's last slab began (`checkpoint`), and when
  // this one escapes (to max range, or above everything), so do all above it.
  const int rows = static_cast<int>(row_c_.size());
  std::vector<Eigen::Vector3d> dw(rows);  // one column's rays, for rows_above_escape
  // A row of the W columns as vectors: the rays, shift and rest; the hits.
  // (plain doubles, copied in and out: std::vector does not align to the vectors' 32 bytes)
  std::vector<double> sx(W * rows), sy(W * rows), sz(W * rows), ssh(W * rows), srest(W * rows), hrange(W * rows),
      hcos(W * rows);
  auto load = [](const double* p) __attribute__((always_inline)) {
    typename V<W>::D v;
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  auto store = [](double* p, const typename V<W>::D& v) __attribute__((always_inline)) { std::memcpy(p, &v, sizeof v); };
  using D = typename V<W>::D;
  const D zero{};
  std::vector<long> hsurf(W * rows);
  std::vector<float> px(W * rows), py(W * rows), pz(W * rows), pi(W * rows);
  std::vector<Surface> ps(W * rows);
  // Pylons a ray of this frame can reach, for rows_above_escape.
  std::vector<int> near_pylons;
  for (std::size_t i = 0; i < pylons_.size(); ++i)
    if (std::hypot(pylons_[i].x - o.x(), pylons_[i].y - o.y()) <= spec_.max_range + pylons_[i].radius)
      near_pylons.push_back(static_cast<int>(i));
  // A ray's direction is row_c (col_c, col_s, 0) + row_s (0, 0, 1) in the sensor frame: in the
  // world, row_c U + row_s Z with U per column and Z per frame (6 flops a ray, not a 3x3 product).
  const Eigen::Vector3d Z = R.col(2);
  for (int c0 = 0; c0 < spec_.columns; c0 += W) {
    const int nl = std::min(W, spec_.columns - c0);
    using M = typename V<W>::M;
    Lanes<W> L;
    // The column's rays and the row pairs' shift and rest (as in march's caller, lane by lane).
    M done{};
    M ncast{};  // rows cast
    D ux{}, uy{}, uz{};
    for (int l = 0; l < W; ++l) {
      if (l >= nl) {
        done[l] = -1;
        continue;
      }
      const Eigen::Vector3d U = R.col(0) * col_c_[c0 + l] + R.col(1) * col_s_[c0 + l];
      ux[l] = U.x(); uy[l] = U.y(); uz[l] = U.z();
    }
    for (int r = 0; r < rows; ++r) {
      store(&sx[r * W], row_c_[r] * ux + row_s_[r] * Z.x());
      store(&sy[r * W], row_c_[r] * uy + row_s_[r] * Z.y());
      store(&sz[r * W], row_c_[r] * uz + row_s_[r] * Z.z());
    }
    D re_up = zero - 1;  // rest of the row above
    for (int r = rows - 1; r >= 0; --r) {
      D sh = zero - 1, re = zero - 1;
      if (r + 1 < rows && spec_.coherent_columns) {
        const D ax = load(&sx[(r + 1) * W]) - load(&sx[r * W]), ay = load(&sy[(r + 1) * W]) - load(&sy[r * W]);
        D apart = ax * ax + ay * ay;
        for (int l = 0; l < W; ++l) apart[l] = std::sqrt(apart[l]);
        const M bad = load(&sz[(r + 1) * W]) - load(&sz[r * W]) <= slope_max_ * apart;
        sh = bad ? sh : apart;
        re = bad ? re : r + 2 == rows ? apart : re_up >= 0 ? apart + re_up : zero - 1;
      }
      store(&ssh[r * W], sh);
      store(&srest[r * W], re);
      re_up = re;
    }
    L.use_from = M{};
    for (int r = 0; r < rows; ++r) {
      L.on = ~done;
      if (!any(L.on)) break;
      L.vx = load(&sx[r * W]); L.vy = load(&sy[r * W]); L.vz = load(&sz[r * W]);
      L.shift = load(&ssh[r * W]); L.rest = load(&srest[r * W]);
      L.want_ck = L.shift >= 0;
      march_lanes<W>(o, seg, L);
      std::memcpy(&hrange[r * W], &L.range, sizeof L.range);
      std::memcpy(&hcos[r * W], &L.cos, sizeof L.cos);
      // As scan's scalar loop: resume from the checkpoint when one was kept; stop a column whose
      // rays above surely return nothing.
      L.from_t = L.ck_t;
      L.from_m = L.ck_m;
      L.from_seg = L.ck_seg;
      L.use_from = L.want_ck & (L.ck_seg >= 0);
      std::memcpy(&hsurf[r * W], &L.surf, sizeof L.surf);
      ncast = L.on ? M{} + (r + 1) : ncast;
      const M escaped = L.on & L.want_ck & (L.surf == static_cast<long>(Surface::none));
      if (any(escaped)) {
        done |= escaped & L.rest_esc;
        const M check = escaped & ~L.rest_esc & (L.esc_t > 0);
        for (int l = 0; l < W; ++l) {
          if (!check[l] || !spec_.skip_escaped_rows) continue;
          Resume e;
          e.escape_t = L.esc_t[l];
          e.escape_margin = L.esc_m[l];
          for (int q = r; q < rows; ++q) dw[q] = Eigen::Vector3d(sx[q * W + l], sy[q * W + l], sz[q * W + l]);
          if (rows_above_escape(dw.data(), r, rows, o.z(), e, near_pylons, o)) done[l] = -1;
        }
      }
    }
    // The points, column by column and rows lowest first (the order of the noise draws), the
    // group's appended at once (one capacity check per buffer).
    int m = 0;
    for (int l = 0; l < nl; ++l) {
      const int c = c0 + l;
      for (int r = 0; r < ncast[l]; ++r) {
        const RayHit h{hrange[r * W + l], static_cast<Surface>(hsurf[r * W + l]), hcos[r * W + l]};
        if (h.surface == Surface::none) continue;
        double range = h.range + (sigma > 0 ? rng.normal_fast(sigma) : 0.0);
        if (spec_.dropout > 0 && rng.uniform() < spec_.dropout) continue;
        if (range < spec_.min_range || range > spec_.max_range) continue;
        double refl = h.surface == Surface::road ? spec_.reflectivity_road
                      : h.surface == Surface::wall ? spec_.reflectivity_wall
                                                   : spec_.reflectivity_pylon;
        px[m] = static_cast<float>(range * (row_c_[r] * col_c_[c]));
        py[m] = static_cast<float>(range * (row_c_[r] * col_s_[c]));
        pz[m] = static_cast<float>(range * row_s_[r]);
        pi[m] = static_cast<float>(refl * h.cos_incidence);
        ps[m++] = h.surface;
      }
    }
    out.x.insert(out.x.end(), px.begin(), px.begin() + m);
    out.y.insert(out.y.end(), py.begin(), py.begin() + m);
    out.z.insert(out.z.end(), pz.begin(), pz.begin() + m);
    out.intensity.insert(out.intensity.end(), pi.begin(), pi.begin() + m);
    if (out.record_surface) out.surface.insert(out.surface.end(), ps.begin(), ps.begin() + m);
  }
  return rays;
}

// Ray by ray (no AVX2, or spec.simd off).
std::size_t LidarCaster::scan_one_by_one(const Eigen::Isometry3d& world_from_body, int seg_hint, Rng& rng,
                                         double noise_factor, PointBuffers& out) const {
  const Eigen::Isometry3d ws = world_from_body * body_from_sensor_;
  const Eigen::Vector3d o = ws.translation();
  const Eigen::Matrix3d R = ws.linear();
  const int seg = track_.project(o.x(), o.y(), seg_hint).seg;
  const double sigma = spec_.range_noise * noise_factor;
  const std::size_t rays = static_cast<std::size_t>(spec_.columns) * row_c_.size();
  out.x.reserve(out.x.size() + rays);
  out.y.reserve(out.y.size() + rays);
  out.z.reserve(out.z.size() + rays);
  out.intensity.reserve(out.intensity.size() + rays);
  // Rows go from the lowest up. The next row's ray lies within `shift` * t of this one
  // horizontally and higher by more than the road can rise over that distance, so it passes
  // over all road this one passed over; if this one also kept more than shift * t from the walls
  // and met no pylon, the next starts where this one's last slab began (`checkpoint`), and when
  // this one escapes (to max range, or above everything), so do all above it.
  const int rows = static_cast<int>(row_c_.size());
  std::vector<Eigen::Vector3d> dw(rows);
  std::vector<double> shift(rows), rest(rows);
  std::vector<float> px(rows), py(rows), pz(rows), pi(rows);
  std::vector<Surface> ps(rows);
  // Pylons a ray of this frame can reach, for rows_above_escape.
  std::vector<int> near_pylons;
  for (std::size_t i = 0; i < pylons_.size(); ++i)
    if (std::hypot(pylons_[i].x - o.x(), pylons_[i].y - o.y()) <= spec_.max_range + pylons_[i].radius)
      near_pylons.push_back(static_cast<int>(i));
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
    Resume from, checkpoint;
    bool resume = false;
    int m = 0;
    for (int r = 0; r < rows; ++r) {
      RayHit h = march(o, dw[r], seg, resume ? &from : nullptr, shift[r], rest[r], shift[r] >= 0 ? &checkpoint : nullptr);
      resume = shift[r] >= 0 && checkpoint.seg >= 0;
      from = checkpoint;
      if (h.surface == Surface::none) {
        if (shift[r] >= 0 && checkpoint.rest_escape) break;
        if (spec_.skip_escaped_rows && shift[r] >= 0 && checkpoint.escape_t > 0 && rows_above_escape(dw.data(), r, rows, o.z(), checkpoint, near_pylons, o))
          break;
        continue;
      }
      double range = h.range + (sigma > 0 ? rng.normal_fast(sigma) : 0.0);
      if (spec_.dropout > 0 && rng.uniform() < spec_.dropout) continue;
      if (range < spec_.min_range || range > spec_.max_range) continue;
      double refl = h.surface == Surface::road ? spec_.reflectivity_road
                    : h.surface == Surface::wall ? spec_.reflectivity_wall
                                                 : spec_.reflectivity_pylon;
      px[m] = static_cast<float>(range * (row_c_[r] * col_c_[c]));
      py[m] = static_cast<float>(range * (row_c_[r] * col_s_[c]));
      pz[m] = static_cast<float>(range * row_s_[r]);
      pi[m] = static_cast<float>(refl * h.cos_incidence);
      ps[m++] = h.surface;
    }
    // A column's points are appended at once (one capacity check per buffer, not per point).
    out.x.insert(out.x.end(), px.begin(), px.begin() + m);
    out.y.insert(out.y.end(), py.begin(), py.begin() + m);
    out.z.insert(out.z.end(), pz.begin(), pz.begin() + m);
    out.intensity.insert(out.intensity.end(), pi.begin(), pi.begin() + m);
    if (out.record_surface) out.surface.insert(out.surface.end(), ps.begin(), ps.begin() + m);
  }
  return rays;
}

std::size_t LidarCaster::scan(const Eigen::Isometry3d& world_from_body, int seg_hint, Rng& rng, double noise_factor,
                              PointBuffers& out) const {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && spec_.simd) return scan_avx2(world_from_body, seg_hint, rng, noise_factor, out);
#endif
  return scan_one_by_one(world_from_body, seg_hint, rng, noise_factor, out);
}

#if defined(__x86_64__)
// Four columns at a time in AVX2 (no FMA: no contraction, so every lane rounds as march does). In
// SSE2, two lanes were 15 % slower than ray by ray; the one-by-one scan serves there.
__attribute__((target("avx2"))) std::size_t LidarCaster::scan_avx2(const Eigen::Isometry3d& world_from_body,
                                                                    int seg_hint, Rng& rng, double noise_factor,
                                                                    PointBuffers& out) const {
  return scan_lanes<4>(world_from_body, seg_hint, rng, noise_factor, out);
}
#endif

}  // namespace brickyard::sim
