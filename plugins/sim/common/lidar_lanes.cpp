// The caster's SIMD path: the rays of four neighbouring columns, same row, in AVX2 lanes
// (docs/simulator.md, "Lanes"). Chosen at run time by LidarCaster::scan (lidar.cpp).
#include "lidar_march.hpp"

#include <cstring>
#include <thread>

namespace brickyard::sim {

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

// march_lanes's state and its steps, all inlined into march_lanes. Lanes: `act` march in slab k from
// their t0 on, going dir along the line; `waiting` join when the march reaches their start slab
// (kl); `to_scalar` are left to march. The lanes in ckm keep a checkpoint (ck_*, esc_*, rest_esc:
// march's Resume). The steps read single lanes (v[l]) of their arguments and locals only, never of
// the members: GCC keeps a struct whose member is indexed lane by lane in memory, and the state in
// registers is what makes this as fast as one function.
template <int W> struct LidarCaster::LaneMarch {
  using D = typename V<W>::D;
  using M = typename V<W>::M;
  const LidarCaster& caster;
  Lanes<W>& L;
  const int n;
  const double max_t, ox, oy, oz;
  const D inf, zero, vmax_t;
  const D vx, vy, vz, shift, rest;
  D t0, margin;
  M act, to_scalar{}, waiting{};
  M kl;
  int k = 0, dir = 0;
  M ckm;
  D ck_t, ck_m, esc_t, esc_m;
  M rest_esc, ck_seg;

  // The rays in slab k: a = a0 + va t, d = d0 + vd t; they leave the slab ahead at t1 (inf: never)
  // and their stretch in it ends by te.
  struct Slab {
    const Seg& g;
    double a0, d0;
    D va, vd, t1, te, len;
  };

  [[gnu::always_inline]] LaneMarch(const LidarCaster& caster, const Eigen::Vector3d& o, int seg, Lanes<W>& L)
      : caster(caster), L(L), n(static_cast<int>(caster.seg_.size())), max_t(caster.spec_.max_range), ox(o.x()), oy(o.y()),
        oz(o.z()), inf(D{} + kInf), zero(D{}), vmax_t(D{} + max_t), vx(L.vx), vy(L.vy), vz(L.vz), shift(L.shift),
        rest(L.rest) {
    const M fr = L.on & L.use_from;
    t0 = fr ? L.from_t : zero;
    margin = fr ? L.from_m : inf;
    act = L.on;
    kl = fr ? L.from_seg : M{} + seg;
    to_scalar = start_slab(act, kl, vx, vy);
    waiting = act & ~to_scalar;  // all join at their start slab (the first step for most)
    act = M{};
    if (!std::isfinite(max_t)) {  // (the lanes' march assumes a finite range)
      to_scalar |= waiting;
      waiting = M{};
    }
    ckm = waiting & L.want_ck;
    clear_outputs();
  }

  // The slab the march starts in (k) and its direction (dir), for the lanes `act` starting in slabs
  // kl with directions (vx, vy). The march starts at the first lane's, or up to two slabs behind it
  // where another lane starts there; the lanes starting ahead join when the march reaches their
  // slab (each with its own t0 and margin, as march would start it). Returns the lanes further off:
  // they go to march.
  [[gnu::always_inline]] M start_slab(M act, M kl, D vx, D vy) {
    M to_scalar{};
    int f = 0;
    while (!act[f]) ++f;
    k = static_cast<int>(kl[f]);
    dir = vx[f] * caster.seg_[k].tx + vy[f] * caster.seg_[k].ty >= 0 ? 1 : -1;  // lane f's, as march sets it
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
    return to_scalar;
  }

  [[gnu::always_inline]] void clear_outputs() {
    L.range = zero;
    L.cos = zero + 1.0;
    L.surf = M{};
    // Resume{0, -1, 0, false} for the lanes keeping a checkpoint.
    ck_t = ckm ? zero : L.ck_t;
    ck_m = ckm ? zero : L.ck_m;
    esc_t = ckm ? zero : L.esc_t;
    esc_m = ckm ? zero : L.esc_m;
    rest_esc = ckm ? M{} : L.rest_esc;
    ck_seg = ckm ? M{} - 1 : L.ck_seg;
  }

  [[gnu::always_inline]] bool marching() const { return any(act | waiting); }

  // The lanes in e escape at t (march's escape, lane by lane).
  [[gnu::always_inline]] void escape(M e, D t) {
    e &= ckm;
    rest_esc |= e & (rest >= 0) & (margin - t * rest > 0);
    const M em = e & (margin > 0);
    esc_t = em ? t : esc_t;
    esc_m = em ? margin : esc_m;
  }

  // The lanes starting in slab k join the march.
  [[gnu::always_inline]] M join_lanes_starting_here() {
    const M fresh = waiting & (kl == k);
    act |= fresh;
    waiting &= ~fresh;
    return fresh;
  }

  [[gnu::always_inline]] void leave_all_to_march() {
    to_scalar |= act | waiting;
    act = waiting = M{};
  }

  // march's checkpoint at the entry of slab k, lane by lane.
  [[gnu::always_inline]] void keep_checkpoints() {
    const D m = margin - t0 * shift;
    const M c = ckm & act & (m > 0);
    ck_t = c ? t0 : ck_t;
    ck_m = c ? m : ck_m;
    ck_seg = c ? M{} + k : ck_seg;
  }

  // The lanes rising above all in reach escape.
  [[gnu::always_inline]] void escape_above_all() {
    const M e = act & (vz >= 0) & (oz + vz * t0 > caster.blocks_[k / kBlock].z_top_near);
    escape(e, t0);
    act &= ~e;
  }

  [[gnu::always_inline]] bool at_block_start() const {
    return dir > 0 ? k % kBlock == 0 : (k % kBlock == kBlock - 1 || k == n - 1);
  }

  // Across the block that starts at slab k in one step, when every lane marching can (returns
  // whether they crossed it).
  [[gnu::always_inline]] bool cross_block(M fresh) {
    const Block& B = caster.blocks_[k / kBlock];
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
      return true;
    }
    return false;
  }

  // The rays' coordinates in slab k.
  [[gnu::always_inline]] Slab enter_slab(const Seg& g, M fresh) {
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
    return Slab{g, a0, d0, va, vd, t1, te, len};
  }

  // Where the rays cross a wall line in the slab by te (inf: they do not).
  [[gnu::always_inline]] D wall_crossing(const Slab& s) const {
    const Seg& g = s.g;
    const double a0 = s.a0, d0 = s.d0;
    const D va = s.va, vd = s.vd, te = s.te;
    const D ae = vclamp(a0 + va * te, zero, s.len), de = d0 + vd * te;
    const M wl = de >= g.wall_l + g.dwl * ae, wr = ~wl & (de <= g.wall_r - g.dwr * ae);
    const D denl = vd - g.dwl * va, denr = vd + g.dwr * va;
    const M wlc = act & wl & (denl > 1e-12), wrc = act & wr & (denr < -1e-12);
    D t_wall = inf;
    if (any(wlc)) t_wall = wlc ? vclamp((g.wall_l + g.dwl * a0 - d0) / denl, t0, te) : t_wall;
    if (any(wrc)) t_wall = wrc ? vclamp((g.wall_r - g.dwr * a0 - d0) / denr, t0, te) : t_wall;
    return t_wall;
  }

  // Height of the rays above the road at t.
  [[gnu::always_inline]] D above(const Slab& s, D t) const {
    const Seg& g = s.g;
    const D a = vclamp(s.a0 + s.va * t, zero, s.len), d = s.d0 + s.vd * t;
    return oz + vz * t - vclamp(d, -(g.wr0 + g.dwr * a), g.wl0 + g.dwl * a) * (g.tb0 + g.dtb * a);
  }

  // The lanes under the road at tf (f1: their height there) hit it.
  [[gnu::always_inline]] void hit_road(const Slab& s, D tf, D f1) {
    const Seg& g = s.g;
    const double a0 = s.a0, d0 = s.d0;
    const D va = s.va, vd = s.vd;
    const M road = act & (f1 <= 0);
    if (!any(road)) return;
    const D flo = above(s, t0);
    const M above_t0 = road & (flo > 0);
    const D t = any(above_t0) ? (above_t0 ? road_root_lanes(g, above_t0, a0, va, d0, vd, oz, vz, t0, tf, f1) : t0) : t0;
    const D a = vclamp(a0 + va * t, zero, s.len), d = d0 + vd * t;
    const M on_road = (d <= g.wl0 + g.dwl * a) & (d >= -(g.wr0 + g.dwr * a));
    const D tb = on_road ? g.tb0 + g.dtb * a : zero;
    const D gx = -tb * g.ty, gy = tb * g.tx;
    const D inv_n = on_road ? (g.dtb == 0 ? zero + g.inv_n0 : 1 / vsqrt(1 + tb * tb)) : zero + 1.0;
    L.range = road ? t : L.range;
    L.cos = road ? vabs(-gx * vx - gy * vy + vz) * inv_n : L.cos;
    L.surf = road ? (on_road ? M{} + static_cast<long>(Surface::road) : M{} + static_cast<long>(Surface::grass)) : L.surf;
    act &= ~road;
  }

  // The lanes that reach a wall line by tf hit the wall, or pass over it and return nothing.
  [[gnu::always_inline]] void hit_walls(D vd, D t_wall, D tf, D f1) {
    const M wall = act & (t_wall <= tf);
    if (!any(wall)) return;
    for (int l = 0; l < W; ++l)
      if (wall[l] && f1[l] <= caster.wall_h_) {
        L.range[l] = t_wall[l];
        L.surf[l] = static_cast<long>(Surface::wall);
        L.cos[l] = std::abs(vd[l]);
      }
    act &= ~wall;
  }

  // The paths' clearance from the walls, at both ends of their stretch [t0, tf] in the slab.
  [[gnu::always_inline]] void narrow_margins(const Slab& s, D tf) {
    const Seg& g = s.g;
    for (D t : {t0, tf}) {
      const D a = vclamp(s.a0 + s.va * t, zero, s.len), d = s.d0 + s.vd * t;
      margin = act ? vmin(vmin(margin, g.wall_l + g.dwl * a - d), d - (g.wall_r - g.dwr * a)) : margin;
    }
  }

  // The lanes through slab k (g), on into the next slab.
  [[gnu::always_inline]] void through_slab(const Seg& g, M fresh) {
    const Slab s = enter_slab(g, fresh);
    const D t_wall = wall_crossing(s);
    const D tf = vmin(vmin(s.te, t_wall), vmax_t);
    const D f1 = above(s, tf);
    hit_road(s, tf, f1);
    hit_walls(s.vd, t_wall, tf, f1);
    narrow_margins(s, tf);
    const M fin = act & (tf >= max_t);
    escape(fin, vmax_t);
    act &= ~fin & ~(s.t1 >= max_t);
    t0 = act ? s.t1 : t0;
    k = dir > 0 ? (k + 1 == n ? 0 : k + 1) : (k == 0 ? n - 1 : k - 1);
  }

  // The checkpoints into L; the lanes that left the lockstep cast by march.
  [[gnu::always_inline]] void finish(const Eigen::Vector3d& o, int seg) {
    to_scalar |= waiting;  // (the march passed their slab in a block, or ended before it)
    L.ck_t = ck_t; L.ck_m = ck_m; L.esc_t = esc_t; L.esc_m = esc_m; L.rest_esc = rest_esc;
    L.ck_seg = ck_seg;
    if (!any(to_scalar)) return;
    cast_one_by_one(o, seg, to_scalar, vx, vy, vz, shift, rest);
  }

  // The lanes in to_scalar cast by march, from their start (march is a pure function of its
  // arguments, so that is exact).
  [[gnu::always_inline]] void cast_one_by_one(const Eigen::Vector3d& o, int seg, M to_scalar, D vx, D vy, D vz, D shift, D rest) {
    for (int l = 0; l < W; ++l) {
      if (!to_scalar[l]) continue;
      Resume from{L.from_t[l], static_cast<int>(L.from_seg[l]), L.from_m[l]}, ck;
      const RayHit h = caster.cast(o, Eigen::Vector3d(vx[l], vy[l], vz[l]), seg, L.use_from[l] ? &from : nullptr, shift[l],
                                   rest[l], L.want_ck[l] ? &ck : nullptr);
      L.range[l] = h.range;
      L.surf[l] = static_cast<long>(h.surface);
      L.cos[l] = h.cos_incidence;
      if (L.want_ck[l]) {
        L.ck_t[l] = ck.t; L.ck_seg[l] = ck.seg; L.ck_m[l] = ck.margin; L.rest_esc[l] = ck.rest_escape ? -1 : 0;
        L.esc_t[l] = ck.escape_t; L.esc_m[l] = ck.escape_margin;
      }
    }
  }
};

// march for the W rays of a row in neighbouring columns, in lockstep while all stay in the common
// case: one slab for all (its fields broadcast), no pylons, a block crossed by all or none. A lane
// that leaves it (a start slab more than two slabs off, another direction, a block only some lanes
// skip, a slab with pylons) is cast again by march from its start: march is a pure function of its
// arguments, so that is exact.
template <int W>
[[gnu::always_inline]] inline void LidarCaster::march_lanes(const Eigen::Vector3d& o, int seg, Lanes<W>& L) const {
  LaneMarch<W> m(*this, o, seg, L);
  for (int steps = 0; m.marching(); ++steps) {
    const typename V<W>::M fresh = m.join_lanes_starting_here();  // lanes starting in this slab
    const Seg& g = seg_[m.k];
    if (steps >= m.n || g.pylon_begin < g.pylon_end) {
      m.leave_all_to_march();
      break;
    }
    m.keep_checkpoints();
    m.escape_above_all();
    if (!m.marching()) break;
    if (spec_.use_blocks && steps > 0 && m.at_block_start()) {
      if (m.cross_block(fresh)) {
        steps += kBlock - 1;
        continue;
      }
      if (!m.marching()) break;
    }
    m.through_slab(g, fresh);
  }
  m.finish(o, seg);
}

// march_columns's scratch (allocated once per call) and its steps for a group of W columns, inlined
// into it. A row of the W columns as vectors: the rays, shift and rest (plain doubles, copied in and
// out: std::vector does not align to the vectors' 32 bytes).
template <int W> struct LidarCaster::GroupRays {
  using D = typename V<W>::D;
  using M = typename V<W>::M;
  const LidarCaster& caster;
  const int rows;
  std::vector<Eigen::Vector3d> dw;  // one column's rays, for rows_above_escape
  std::vector<double> sx, sy, sz, ssh, srest;

  [[gnu::always_inline]] GroupRays(const LidarCaster& caster, int rows)
      : caster(caster), rows(rows), dw(rows), sx(W * rows), sy(W * rows), sz(W * rows), ssh(W * rows), srest(W * rows) {}
  [[gnu::always_inline]] ~GroupRays() = default;

  [[gnu::always_inline]] static D load(const double* p) {
    D v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  [[gnu::always_inline]] static void store(double* p, const D& v) { std::memcpy(p, &v, sizeof v); }

  // The rays of columns [c0, c0 + nl), row by row. A ray's direction is row_c (col_c, col_s, 0) +
  // row_s (0, 0, 1) in the sensor frame: in the world, row_c U + row_s Z with U per column and Z
  // per frame (6 flops a ray, not a 3x3 product). Returns the lanes past the last column: done.
  [[gnu::always_inline]] M aim(const Eigen::Matrix3d& R, const Eigen::Vector3d& Z, int c0, int nl) {
    M done{};
    D ux{}, uy{}, uz{};
    for (int l = 0; l < W; ++l) {
      if (l >= nl) {
        done[l] = -1;
        continue;
      }
      const Eigen::Vector3d U = R.col(0) * caster.col_c_[c0 + l] + R.col(1) * caster.col_s_[c0 + l];
      ux[l] = U.x(); uy[l] = U.y(); uz[l] = U.z();
    }
    for (int r = 0; r < rows; ++r) {
      store(&sx[r * W], caster.row_c_[r] * ux + caster.row_s_[r] * Z.x());
      store(&sy[r * W], caster.row_c_[r] * uy + caster.row_s_[r] * Z.y());
      store(&sz[r * W], caster.row_c_[r] * uz + caster.row_s_[r] * Z.z());
    }
    return done;
  }

  // The row pairs' shift and rest (as in march's caller, lane by lane).
  [[gnu::always_inline]] void shift_rows() {
    const D zero{};
    D re_up = zero - 1;  // rest of the row above
    for (int r = rows - 1; r >= 0; --r) {
      D sh = zero - 1, re = zero - 1;
      if (r + 1 < rows && caster.spec_.coherent_columns) {
        const D ax = load(&sx[(r + 1) * W]) - load(&sx[r * W]), ay = load(&sy[(r + 1) * W]) - load(&sy[r * W]);
        const D apart = vsqrt(ax * ax + ay * ay);
        const M bad = load(&sz[(r + 1) * W]) - load(&sz[r * W]) <= caster.slope_max_ * apart;
        sh = bad ? sh : apart;
        re = bad ? re : r + 2 == rows ? apart : re_up >= 0 ? apart + re_up : zero - 1;
      }
      store(&ssh[r * W], sh);
      store(&srest[r * W], re);
      re_up = re;
    }
  }

  // The rows from the lowest up, as scan's scalar loop: each resumes from the checkpoint the row
  // below kept, and a column stops when its rays above surely return nothing. The hits go to the
  // group's rows in h. Returns the rows cast per lane.
  [[gnu::always_inline]] M march_rows(const Frame& f, M done, int c0, ColumnHits& h) {
    double* hrange = &h.range[static_cast<std::size_t>(c0) * rows];
    double* hcos = &h.cos[static_cast<std::size_t>(c0) * rows];
    long* hsurf = &h.surf[static_cast<std::size_t>(c0) * rows];
    Lanes<W> L;
    M ncast{};
    L.use_from = M{};
    for (int r = 0; r < rows; ++r) {
      L.on = ~done;
      if (!any(L.on)) break;
      L.vx = load(&sx[r * W]); L.vy = load(&sy[r * W]); L.vz = load(&sz[r * W]);
      L.shift = load(&ssh[r * W]); L.rest = load(&srest[r * W]);
      L.want_ck = L.shift >= 0;
      caster.march_lanes<W>(f.o, f.seg, L);
      std::memcpy(&hrange[r * W], &L.range, sizeof L.range);
      std::memcpy(&hcos[r * W], &L.cos, sizeof L.cos);
      L.from_t = L.ck_t;
      L.from_m = L.ck_m;
      L.from_seg = L.ck_seg;
      L.use_from = L.want_ck & (L.ck_seg >= 0);
      std::memcpy(&hsurf[r * W], &L.surf, sizeof L.surf);
      ncast = L.on ? M{} + (r + 1) : ncast;
      const M escaped = L.on & L.want_ck & (L.surf == static_cast<long>(Surface::none));
      if (any(escaped)) end_escaped_columns(f, L, escaped, r, done);
    }
    return ncast;
  }

  // The lanes whose row r escaped: done when every row above surely escapes too.
  [[gnu::always_inline]] void end_escaped_columns(const Frame& f, const Lanes<W>& L, M escaped, int r, M& done) {
    done |= escaped & L.rest_esc;
    const M check = escaped & ~L.rest_esc & (L.esc_t > 0);
    for (int l = 0; l < W; ++l) {
      if (!check[l] || !caster.spec_.skip_escaped_rows) continue;
      Resume e;
      e.escape_t = L.esc_t[l];
      e.escape_margin = L.esc_m[l];
      for (int q = r; q < rows; ++q) dw[q] = Eigen::Vector3d(sx[q * W + l], sy[q * W + l], sz[q * W + l]);
      if (caster.rows_above_escape(dw.data(), r, rows, f.o.z(), e, f.near_pylons, f.o)) done[l] = -1;
    }
  }
};

// Rows go from the lowest up, resuming and ending columns as scan_one_by_one does (lidar.cpp).
template <int W>
[[gnu::always_inline]] inline void LidarCaster::march_columns(const Frame& f, int first, int stride, ColumnHits& h) const {
  GroupRays<W> group(*this, static_cast<int>(row_c_.size()));
  const Eigen::Vector3d Z = f.R.col(2);
  for (int c0 = first * W; c0 < spec_.columns; c0 += stride * W) {
    const int nl = std::min(W, spec_.columns - c0);
    const typename V<W>::M done = group.aim(f.R, Z, c0, nl);
    group.shift_rows();
    const typename V<W>::M ncast = group.march_rows(f, done, c0, h);
    for (int l = 0; l < nl; ++l) h.cast[c0 + l] = static_cast<int>(ncast[l]);
  }
}

template <int W>
[[gnu::always_inline]] inline std::size_t LidarCaster::scan_lanes(const Frame& f, Rng& rng, PointBuffers& out) const {
  static_assert(W == 4, "the second thread marches with march_columns_avx2");
  const int rows = static_cast<int>(row_c_.size());
  const int groups = (spec_.columns + W - 1) / W;
  // The caster's scratch: sized once, every entry read is written first this frame (a column's
  // rows up to its `cast`).
  ColumnHits& h = hits_;
  h.rows = rows;
  h.range.resize(static_cast<std::size_t>(groups) * W * rows);
  h.cos.resize(h.range.size());
  h.surf.resize(h.range.size());
  h.cast.resize(static_cast<std::size_t>(groups) * W);
  // The march is pure and column by column; the noise is drawn in one order afterwards, so two
  // threads give the same bits as one.
  if (spec_.threads >= 2 && groups >= 8) {
    std::thread second([&] { march_columns_avx2(f, 1, 2, h); });
    march_columns<W>(f, 0, 2, h);
    second.join();
  } else {
    march_columns<W>(f, 0, 1, h);
  }
  // The points, column by column and rows lowest first (the order of the noise draws), a group's
  // appended at once (one capacity check per buffer). A column a car may be in: every row held
  // against the cars, those above its escape (not cast: the world returns nothing there) too.
  Staging st(W * rows);
  for (int c0 = 0; c0 < spec_.columns; c0 += W) {
    const int nl = std::min(W, spec_.columns - c0);
    const std::size_t base = static_cast<std::size_t>(c0) * rows;
    for (int l = 0; l < nl; ++l) {
      const int c = c0 + l;
      const bool sees_car = f.cars.sees(c);
      for (int r = 0, last = sees_car ? rows : h.cast[c]; r < last; ++r) {
        const std::size_t k = base + static_cast<std::size_t>(r) * W + l;
        RayHit hit = r < h.cast[c] ? RayHit{h.range[k], static_cast<Surface>(h.surf[k]), h.cos[k]} : RayHit{};
        if (sees_car) hit = with_cars(f, hit, r, c);
        if (hit.surface == Surface::none) continue;
        add_point(hit, r, c, f.sigma, rng, st);
      }
    }
    st.flush(out);
  }
  return f.rays;
}

#if defined(__x86_64__)
// Four columns at a time in AVX2 (no FMA: no contraction, so every lane rounds as march does). In
// SSE2, two lanes were 15 % slower than ray by ray; the one-by-one scan serves there.
__attribute__((target("avx2"))) void LidarCaster::march_columns_avx2(const Frame& f, int first, int stride, ColumnHits& h) const {
  march_columns<4>(f, first, stride, h);
}

__attribute__((target("avx2"))) std::size_t LidarCaster::scan_avx2(const Frame& f, Rng& rng, PointBuffers& out) const {
  return scan_lanes<4>(f, rng, out);
}
#endif

}  // namespace brickyard::sim
