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
      L.surf = road ? (on_road ? M{} + static_cast<long>(Surface::road) : M{} + static_cast<long>(Surface::grass)) : L.surf;
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
[[gnu::always_inline]] inline void LidarCaster::march_columns(const Frame& f, int first, int stride, ColumnHits& h) const {
  const Eigen::Vector3d& o = f.o;
  const Eigen::Matrix3d& R = f.R;
  const int seg = f.seg;
  const std::vector<int>& near_pylons = f.near_pylons;
  // Rows go from the lowest up, resuming and ending columns as scan_one_by_one does (lidar.cpp).
  const int rows = static_cast<int>(row_c_.size());
  std::vector<Eigen::Vector3d> dw(rows);  // one column's rays, for rows_above_escape
  // A row of the W columns as vectors: the rays, shift and rest; the hits.
  // (plain doubles, copied in and out: std::vector does not align to the vectors' 32 bytes)
  std::vector<double> sx(W * rows), sy(W * rows), sz(W * rows), ssh(W * rows), srest(W * rows);
  auto load = [](const double* p) __attribute__((always_inline)) {
    typename V<W>::D v;
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  auto store = [](double* p, const typename V<W>::D& v) __attribute__((always_inline)) { std::memcpy(p, &v, sizeof v); };
  using D = typename V<W>::D;
  const D zero{};
  // A ray's direction is row_c (col_c, col_s, 0) + row_s (0, 0, 1) in the sensor frame: in the
  // world, row_c U + row_s Z with U per column and Z per frame (6 flops a ray, not a 3x3 product).
  const Eigen::Vector3d Z = R.col(2);
  for (int c0 = first * W; c0 < spec_.columns; c0 += stride * W) {
    const int nl = std::min(W, spec_.columns - c0);
    double* hrange = &h.range[static_cast<std::size_t>(c0) * rows];
    double* hcos = &h.cos[static_cast<std::size_t>(c0) * rows];
    long* hsurf = &h.surf[static_cast<std::size_t>(c0) * rows];
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
        const D apart = vsqrt(ax * ax + ay * ay);
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
    for (int l = 0; l < nl; ++l) h.cast[c0 + l] = static_cast<int>(ncast[l]);
  }
}

template <int W>
[[gnu::always_inline]] inline std::size_t LidarCaster::scan_lanes(const Eigen::Isometry3d& world_from_body,
                                                                   int seg_hint, Rng& rng, double noise_factor,
                                                                   PointBuffers& out) const {
  static_assert(W == 4, "the second thread marches with march_columns_avx2");
  const Frame f = begin_frame(world_from_body, seg_hint, noise_factor, out);
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
  // appended at once (one capacity check per buffer).
  Staging st(W * rows);
  for (int c0 = 0; c0 < spec_.columns; c0 += W) {
    const int nl = std::min(W, spec_.columns - c0);
    const std::size_t base = static_cast<std::size_t>(c0) * rows;
    for (int l = 0; l < nl; ++l) {
      const int c = c0 + l;
      for (int r = 0; r < h.cast[c]; ++r) {
        const std::size_t k = base + static_cast<std::size_t>(r) * W + l;
        const RayHit hit{h.range[k], static_cast<Surface>(h.surf[k]), h.cos[k]};
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

__attribute__((target("avx2"))) std::size_t LidarCaster::scan_avx2(const Eigen::Isometry3d& world_from_body,
                                                                    int seg_hint, Rng& rng, double noise_factor,
                                                                    PointBuffers& out) const {
  return scan_lanes<4>(world_from_body, seg_hint, rng, noise_factor, out);
}
#endif

}  // namespace brickyard::sim
