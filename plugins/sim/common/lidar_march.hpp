#pragma once
// Private to the caster (lidar.cpp, lidar_lanes.cpp): the scalar march of one ray and the road's
// root, inline in both files (each lane that leaves the lanes' common case is finished by march).
#include "lidar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace brickyard::sim {
namespace lidar_detail {
constexpr double kInf = std::numeric_limits<double>::infinity();
// The first t in [ta, tb] where a ray (a = a0 + va t, d = d0 + vd t, z = oz + vz t in the slab of
// g) meets the road, given it is above the road at ta and not at tb (f_tb = its height there).
// In closed form: the cross-section is straight between the edges and level beyond them, so the
// edges' crossings (linear in t) cut [ta, tb] into at most three pieces, and on each the road's
// height — the cross-section coordinate (d, or an edge's) times tan(bank), both linear in t — is a
// quadratic in t. (Regula falsi here took 4-8 evaluations per ray.)
template <class Seg>
inline double road_root(const Seg& g, double a0, double va, double d0, double vd, double oz, double vz, double ta, double tb,
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
}  // namespace lidar_detail

using lidar_detail::kInf;
using lidar_detail::road_root;

// One ray's march from slab to slab (the region of a segment between the planes normal to it at its
// ends), in the steps march takes. Within a slab, the ray's along (a) and across (d) coordinates
// are linear in t, so the wall lines are crossed at a t found in closed form and the road (a
// straight cross-section whose bank varies linearly) at the root road_root finds. The steps are
// inlined into march (the state stays in registers, as in one function).
struct LidarCaster::RayMarch {
  const LidarCaster& caster;
  const double max_t;
  const int n;
  const double ox, oy, oz, vx, vy, vz;
  const double shift, shift_rest;
  Resume* const checkpoint;
  RayHit best;
  double best_t;
  int k;  // the slab the ray is in, from t0 on
  int dir = 0;
  double t0 = 0;
  // For the checkpoint: the least distance to a wall line along the path so far, and whether a
  // slab with pylons has been entered (past it, no checkpoint: pylons are not in the margin).
  double margin = kInf;
  bool checkpoints;

  // The ray in slab k: its coordinates (a = a0 + va t, d = d0 + vd t) and where it leaves the slab
  // through the end plane ahead (t1; inf when it runs parallel to it).
  struct Slab {
    const Seg& g;
    double a0, va, d0, vd, t1;
  };
  enum class Crossing { none, crossed, escaped };

  [[gnu::always_inline]] RayMarch(const LidarCaster& caster, const Eigen::Vector3d& o, const Eigen::Vector3d& v, int k,
                                  double shift, double shift_rest, Resume* checkpoint)
      : caster(caster), max_t(caster.spec_.max_range), n(static_cast<int>(caster.seg_.size())), ox(o.x()), oy(o.y()),
        oz(o.z()), vx(v.x()), vy(v.y()), vz(v.z()), shift(shift), shift_rest(shift_rest), checkpoint(checkpoint),
        best_t(max_t), k(k), checkpoints(checkpoint != nullptr) {
    if (checkpoint) *checkpoint = Resume{0, -1, 0, false};
  }

  [[gnu::always_inline]] void resume(const Resume& from) {
    t0 = from.t;
    k = from.seg;
    margin = from.margin;
  }

  // This ray escapes at t: so do the rays above it when the path up to t kept clear of the walls.
  [[gnu::always_inline]] void escape(double t) {
    if (!checkpoints) return;
    if (shift_rest >= 0 && margin - t * shift_rest > 0) checkpoint->rest_escape = true;
    if (margin > 0) {
      checkpoint->escape_t = t;
      checkpoint->escape_margin = margin;
    }
  }

  [[gnu::always_inline]] void keep_checkpoint() {
    if (checkpoints) {
      // Not into a slab with pylons: the next ray enters it at another t, and the pylon's face
      // may lie between the two.
      if (caster.seg_[k].pylon_begin < caster.seg_[k].pylon_end) checkpoints = false;
      else if (margin - t0 * shift > 0) *checkpoint = Resume{t0, k, margin - t0 * shift};
    }
  }

  // Rising above all in reach: the ray escapes.
  [[gnu::always_inline]] bool rises_above_all() {
    if (vz >= 0 && oz + vz * t0 > caster.blocks_[k / kBlock].z_top_near) {
      escape(t0);
      return true;
    }
    return false;
  }

  [[gnu::always_inline]] bool at_block_start() const {
    return dir > 0 ? k % kBlock == 0 : (k % kBlock == kBlock - 1 || k == n - 1);
  }

  // Across the block k starts, in one step, when nothing in it can be reached.
  [[gnu::always_inline]] Crossing cross_block() {
    const Block& B = caster.blocks_[k / kBlock];
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
            return Crossing::escaped;
          }
          t0 = t_out;
          k = dir > 0 ? std::min(n, (k / kBlock + 1) * kBlock) % n
                      : ((k / kBlock) * kBlock - 1 + n) % n;
          return Crossing::crossed;
        }
      }
    }
    return Crossing::none;
  }

  [[gnu::always_inline]] Slab enter_slab() {
    const Seg& g = caster.seg_[k];
    const double rx = ox - g.px, ry = oy - g.py;
    const double a0 = rx * g.tx + ry * g.ty, va = vx * g.tx + vy * g.ty;
    const double d0 = ry * g.tx - rx * g.ty, vd = vy * g.tx - vx * g.ty;
    if (dir == 0) dir = va >= 0 ? 1 : -1;
    double t1 = kInf;
    if (dir > 0 ? va > 1e-12 : va < -1e-12) t1 = std::max((dir > 0 ? g.len - a0 : -a0) / va, t0);
    return Slab{g, a0, va, d0, vd, t1};
  }

  // Height of the ray above the road at t.
  [[gnu::always_inline]] double above(const Slab& s, double t) const {
    const Seg& g = s.g;
    const double a = std::clamp(s.a0 + s.va * t, 0.0, g.len), d = s.d0 + s.vd * t;
    return oz + vz * t - std::clamp(d, -(g.wr0 + g.dwr * a), g.wl0 + g.dwl * a) * (g.tb0 + g.dtb * a);
  }

  // Pylons standing in this segment (vertical cylinders) met before te: the nearest is the hit so
  // far. Returns where the ray's stretch in the slab ends now.
  [[gnu::always_inline]] double hit_pylons(const Slab& s, double te) {
    for (int p = s.g.pylon_begin; p < s.g.pylon_end; ++p) {
      const Pylon& c = caster.pylons_[p];
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
    return te;
  }

  // Walls: where the ray crosses a wall line in this slab before te (inf: it does not).
  [[gnu::always_inline]] double wall_crossing(const Slab& s, double te) const {
    const Seg& g = s.g;
    const double a0 = s.a0, va = s.va, d0 = s.d0, vd = s.vd;
    double t_wall = kInf;
    if (std::isfinite(te)) {
      // Is the ray beyond a wall line at the end of its stretch in this slab?
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
    return t_wall;
  }

  // The ray is under the road at tf (f1 = its height there): the hit is where it meets it.
  [[gnu::always_inline]] void hit_road(const Slab& s, double tf, double f1) {
    const Seg& g = s.g;
    const double a0 = s.a0, va = s.va, d0 = s.d0, vd = s.vd;
    double lo = t0, hi = tf, flo = above(s, t0), fhi = f1, t = hi;
    if (flo > 0) {
      t = road_root(g, a0, va, d0, vd, oz, vz, lo, hi, fhi);
    } else {
      t = t0;
    }
    best_t = t;
    const double a = std::clamp(a0 + va * t, 0.0, g.len), d = d0 + vd * t;
    const bool on_road = d <= g.wl0 + g.dwl * a && d >= -(g.wr0 + g.dwr * a);
    best.surface = on_road ? Surface::road : Surface::grass;
    // Surface normal (-grad z, 1): grad z = tan(bank) * (left normal) on the road, 0 beyond.
    const double tb = on_road ? g.tb0 + g.dtb * a : 0.0;
    const double gx = -tb * g.ty, gy = tb * g.tx;
    // |n . v| with n = (-grad z, 1) / |(-grad z, 1)|; the norm is the segment's own when its
    // bank is constant (most segments), so no square root and division per ray there.
    const double inv_n = !on_road ? 1.0 : g.dtb == 0 ? g.inv_n0 : 1 / std::sqrt(1 + tb * tb);
    best.cos_incidence = std::abs(-gx * vx - gy * vy + vz) * inv_n;
  }

  // The path's clearance from the walls, at both ends of its stretch [t0, tf] in this slab.
  [[gnu::always_inline]] void narrow_margin(const Slab& s, double tf) {
    const Seg& g = s.g;
    for (double t : {t0, tf}) {
      const double a = std::clamp(s.a0 + s.va * t, 0.0, g.len), d = s.d0 + s.vd * t;
      margin = std::min({margin, g.wall_l + g.dwl * a - d, d - (g.wall_r - g.dwr * a)});
    }
  }

  // The ray through slab k: whether it goes on into the next slab.
  [[gnu::always_inline]] bool through_slab() {
    const Slab s = enter_slab();
    const double te = hit_pylons(s, std::min(s.t1, best_t));
    const double t_wall = wall_crossing(s, te);
    const double tf = std::min({te, t_wall, max_t});
    const double f1 = above(s, tf);
    if (f1 <= 0) {
      hit_road(s, tf, f1);
      return false;
    }
    if (best.surface == Surface::pylon && best_t <= tf) return false;
    if (t_wall <= tf) {
      // The wall stands on the road edge; over its top the world ends: nothing beyond returns.
      if (f1 <= caster.wall_h_) {
        best_t = t_wall;
        best.surface = Surface::wall;
        best.cos_incidence = std::abs(s.vd);
      }
      return false;
    }
    // Only a ray that goes on (or escapes here) needs the clearance, so it is not worked out for
    // the slab where a ray hits something (most rays).
    if (checkpoints) narrow_margin(s, tf);
    if (tf >= max_t) {
      if (best.surface == Surface::none) escape(max_t);
      return false;
    }
    if (s.t1 >= best_t) return false;
    t0 = s.t1;
    k = dir > 0 ? (k + 1 == n ? 0 : k + 1) : (k == 0 ? n - 1 : k - 1);
    return true;
  }
};

// The march itself, inlined into scan's row loop (a call per ray cost ~ 5 % there).
[[gnu::always_inline]] inline RayHit LidarCaster::march(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int k,
                                                         const Resume* from, double shift, double shift_rest,
                                                         Resume* checkpoint) const {
  RayMarch m(*this, o, v, k, shift, shift_rest, checkpoint);
  if (from && from->seg >= 0) m.resume(*from);
  for (int steps = 0; steps < m.n; ++steps) {
    m.keep_checkpoint();
    if (m.rises_above_all()) break;
    // Entering a block: cross it in one step when nothing in it can be reached.
    if (spec_.use_blocks && steps > 0 && m.at_block_start()) {
      const RayMarch::Crossing crossing = m.cross_block();
      if (crossing == RayMarch::Crossing::escaped) break;
      if (crossing == RayMarch::Crossing::crossed) {
        steps += kBlock - 1;
        continue;
      }
    }
    if (!m.through_slab()) break;
  }
  m.best.range = m.best.surface == Surface::none ? 0 : m.best_t;
  return m.best;
}

struct LidarCaster::Staging {
  std::vector<float> x, y, z, i;
  // The surfaces as words, not as Surface (a char type): a char store may alias anything, and
  // after each one the compiler reloaded the random source's state, the buffers' pointers and the
  // spec from memory (the points' pass took a third of the time it takes now).
  std::vector<std::uint32_t> s;
  int m = 0;
  explicit Staging(std::size_t n) : x(n), y(n), z(n), i(n), s(n) {}
  // Appended at once: one capacity check per buffer, not per point.
  void flush(PointBuffers& out) {
    out.x.insert(out.x.end(), x.begin(), x.begin() + m);
    out.y.insert(out.y.end(), y.begin(), y.begin() + m);
    out.z.insert(out.z.end(), z.begin(), z.begin() + m);
    out.intensity.insert(out.intensity.end(), i.begin(), i.begin() + m);
    if (out.record_surface)
      for (int k = 0; k < m; ++k) out.surface.push_back(static_cast<Surface>(s[k]));
    m = 0;
  }
};

[[gnu::always_inline]] inline void LidarCaster::add_point(const RayHit& h, int r, int c, double sigma, Rng& rng,
                                                          Staging& st) const {
  const double range = h.range + (sigma > 0 ? rng.normal_fast(sigma) : 0.0);
  if (spec_.dropout > 0 && rng.uniform() < spec_.dropout) return;
  if (range < spec_.min_range || range > spec_.max_range) return;
  const double refl = h.surface == Surface::road    ? spec_.reflectivity_road
                      : h.surface == Surface::wall  ? spec_.reflectivity_wall
                      : h.surface == Surface::grass ? spec_.reflectivity_grass
                      : h.surface == Surface::car   ? spec_.reflectivity_car
                                                    : spec_.reflectivity_pylon;
  st.x[st.m] = static_cast<float>(range * (row_c_[r] * col_c_[c]));
  st.y[st.m] = static_cast<float>(range * (row_c_[r] * col_s_[c]));
  st.z[st.m] = static_cast<float>(range * row_s_[r]);
  st.i[st.m] = static_cast<float>(refl * h.cos_incidence);
  st.s[st.m++] = static_cast<std::uint32_t>(h.surface);
}

}  // namespace brickyard::sim
