#include "track_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace brickyard::mapping {

namespace {

// The closed polyline `lap` resampled at m evenly spaced points.
std::vector<Eigen::Vector2d> resample_closed(const std::vector<Eigen::Vector2d>& lap, double length, int m) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(m);
  const std::size_t n = lap.size();
  std::size_t i = 0;
  double at = 0;  // arc length at lap[i]
  for (int k = 0; k < m; ++k) {
    const double s = length * k / m;
    for (;;) {
      const double seg = (lap[(i + 1) % n] - lap[i]).norm();
      if (at + seg >= s || i + 1 >= n) {
        const double f = seg > 1e-9 ? std::clamp((s - at) / seg, 0.0, 1.0) : 0.0;
        out.push_back(lap[i] + f * (lap[(i + 1) % n] - lap[i]));
        break;
      }
      at += seg;
      ++i;
    }
  }
  return out;
}

// Circular median of the finite values within ±half; NaN where none.
std::vector<double> median_filter(const std::vector<double>& v, int half) {
  const int m = static_cast<int>(v.size());
  std::vector<double> out(m, NAN), w;
  for (int k = 0; k < m; ++k) {
    w.clear();
    for (int j = -half; j <= half; ++j)
      if (const double x = v[((k + j) % m + m) % m]; std::isfinite(x)) w.push_back(x);
    if (w.empty()) continue;
    std::nth_element(w.begin(), w.begin() + w.size() / 2, w.end());
    out[k] = w[w.size() / 2];
  }
  return out;
}

// NaNs filled by linear interpolation between the nearest finite values either side (circular).
// Returns false when there is none at all.
bool fill_gaps(std::vector<double>& v) {
  const int m = static_cast<int>(v.size());
  int first = -1;
  for (int k = 0; k < m && first < 0; ++k)
    if (std::isfinite(v[k])) first = k;
  if (first < 0) return false;
  int last = first;
  for (int step = 1; step <= m; ++step) {
    const int k = (first + step) % m;
    if (!std::isfinite(v[k])) continue;
    const int gap = ((k - last) % m + m) % m;
    for (int j = 1; j < gap; ++j) v[(last + j) % m] = v[last] + (v[k] - v[last]) * j / gap;
    last = k;
  }
  return true;
}

// The edge near t (where the profile first rose past the threshold) at half height between the
// road's level just before it and the ground's just after: beyond a banked turn's lower edge the
// grass faces the car and returns up to 1.9 (against 0.45 level), and a fixed threshold of 0.3
// crossed 0.15 m short of the edge there.
template <class Sample>
double refine_edge(const Sample& sample, double t, const TrackExtractionParams& p) {
  double r0 = 0, r1 = 0;
  int n0 = 0, n1 = 0;
  for (double u = t - 1.0; u <= t - 0.3; u += p.probe_step)
    if (const auto s = sample(u); s.known && !s.standing && s.reflectivity < p.threshold) r0 += s.reflectivity, ++n0;
  for (double u = t + 0.3; u <= t + 1.0; u += p.probe_step)
    if (const auto s = sample(u); s.known && !s.standing) r1 += s.reflectivity, ++n1;
  if (n0 == 0 || n1 == 0) return t;
  const double mid = 0.5 * (r0 / n0 + r1 / n1);
  double prev_u = t - 0.5, prev_r = NAN;
  for (double u = t - 0.5; u <= t + 0.5; u += p.probe_step) {
    const auto s = sample(u);
    if (!s.known || s.standing) {
      prev_r = NAN;
      continue;
    }
    if (s.reflectivity >= mid) {
      if (std::isfinite(prev_r) && s.reflectivity > prev_r) return prev_u + (mid - prev_r) / (s.reflectivity - prev_r) * (u - prev_u);
      return u;
    }
    prev_u = u;
    prev_r = s.reflectivity;
  }
  return t;
}

// The widths of the kept stations narrowed so that a reader of the file, which joins two kept
// centre points straight and puts each edge at the widths interpolated along that segment's
// normal (track::Track), claims no road beyond any station's edge between them. Why: in a bend
// that chord runs beyond the edge on the bend's inside (Monza's first chicane written every 6 m:
// up to 0.5 m beyond the edge the drive saw, and the race's line 0.07 m from the wall against
// 1.03 m on the true file). Written closer instead (2 m there), the edges' jitter became
// curvature, and the car left that chicane into the wall.
void narrow_to_stations(track::CenterLine& kept, const std::vector<int>& at, const std::vector<Eigen::Vector2d>& left,
                        const std::vector<Eigen::Vector2d>& right, int m) {
  const std::size_t n = at.size();
  std::vector<double> less_left(n, 0.0), less_right(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1) % n;
    const Eigen::Vector2d a(kept.x[i], kept.y[i]), b(kept.x[k], kept.y[k]);
    const double len = (b - a).norm();
    if (len <= 0) continue;
    const Eigen::Vector2d t = (b - a) / len, nl(-t.y(), t.x());
    const int last = k == 0 ? at[0] + m : at[k];
    for (int j = at[i] + 1; j < last; ++j) {
      const Eigen::Vector2d L = left[j % m] - a, R = right[j % m] - a;
      const double ul = std::clamp(L.dot(t) / len, 0.0, 1.0), ur = std::clamp(R.dot(t) / len, 0.0, 1.0);
      const double over_left = kept.width_left[i] * (1 - ul) + kept.width_left[k] * ul - L.dot(nl);
      const double over_right = kept.width_right[i] * (1 - ur) + kept.width_right[k] * ur + R.dot(nl);
      less_left[i] = std::max(less_left[i], over_left), less_left[k] = std::max(less_left[k], over_left);
      less_right[i] = std::max(less_right[i], over_right), less_right[k] = std::max(less_right[k], over_right);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    kept.width_left[i] -= less_left[i];
    kept.width_right[i] -= less_right[i];
  }
}

// Whether the drive from driven[i0] comes back to pass near it after a lap: `end` the pose nearest
// i0 there, `length` the distance driven to it (to wherever the search stopped when it does not).
bool close_lap(const std::vector<Eigen::Vector2d>& driven, std::size_t i0, const TrackExtractionParams& p, std::size_t& end,
               double& length) {
  end = 0;
  length = 0;
  for (std::size_t i = i0 + 1; i < driven.size(); ++i) {
    length += (driven[i] - driven[i - 1]).norm();
    if (length > p.min_lap && (driven[i] - driven[i0]).norm() < p.close_within) {
      end = i;
      while (end + 1 < driven.size() && (driven[end + 1] - driven[i0]).norm() < (driven[end] - driven[i0]).norm()) {
        length += (driven[end + 1] - driven[end]).norm();
        ++end;
      }
      return true;
    }
  }
  return false;
}

// 1. One lap of the driven path, from `lap_from` metres into the drive (the start is off the
//    line the car then drives: a lap closed there joined two lines metres apart, and the
//    reference's kink put IMS's edges 2.8 m off at the line) round to where it passes nearest
//    that point again; from the first pose when the drive is too short for that.
std::vector<Eigen::Vector2d> one_lap(const std::vector<Eigen::Vector2d>& driven, const TrackExtractionParams& p) {
  std::size_t start = 0, end = 0;
  double length = 0;
  for (double along = 0; start + 1 < driven.size() && along < p.lap_from; ++start) along += (driven[start + 1] - driven[start]).norm();
  if (!close_lap(driven, start, p, end, length)) {
    start = 0;
    if (!close_lap(driven, 0, p, end, length))
      throw std::invalid_argument("the drive never came back to where it started (" + std::to_string(static_cast<long>(length)) +
                                  " m driven): a track needs a whole lap");
  }
  return std::vector<Eigen::Vector2d>(driven.begin() + static_cast<long>(start), driven.begin() + static_cast<long>(end));
}

// The length of the closed polyline `lap`.
double closed_length(const std::vector<Eigen::Vector2d>& lap) {
  double perimeter = 0;
  for (std::size_t i = 0; i < lap.size(); ++i) perimeter += (lap[(i + 1) % lap.size()] - lap[i]).norm();
  return perimeter;
}

// The circular moving average of `raw` over ±half points.
std::vector<Eigen::Vector2d> moving_average(const std::vector<Eigen::Vector2d>& raw, int half) {
  const int m = static_cast<int>(raw.size());
  std::vector<Eigen::Vector2d> ref(m);
  for (int k = 0; k < m; ++k) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int j = -half; j <= half; ++j) sum += raw[((k + j) % m + m) % m];
    ref[k] = sum / (2 * half + 1);
  }
  return ref;
}

// Per station: the reference, its left normal, and the edges' distances along it either side.
struct Stations {
  std::vector<Eigen::Vector2d> ref, normal;
  std::vector<double> wl, wr;
  std::size_t sides_found = 0;  // in the last pass, before the gaps were filled
};

// The centre found, barely smoothed (one station either side): smoothed over ±10 m as the
// driven path is, a hairpin's centre moves inward by L²/6R, 0.8 m on Spielberg's, and the
// file's normals then differ from the ones the edges were measured along.
void recentre(Stations& s) {
  const int m = static_cast<int>(s.ref.size());
  std::vector<Eigen::Vector2d> centre(m);
  for (int k = 0; k < m; ++k) centre[k] = s.ref[k] + 0.5 * (s.wl[k] - s.wr[k]) * s.normal[k];
  for (int k = 0; k < m; ++k) s.ref[k] = (centre[(k + m - 1) % m] + centre[k] + centre[(k + 1) % m]) / 3.0;
}

// The left normal at each point of the closed line `ref`, across its neighbours' chord.
std::vector<Eigen::Vector2d> left_normals(const std::vector<Eigen::Vector2d>& ref) {
  const int m = static_cast<int>(ref.size());
  std::vector<Eigen::Vector2d> normal(m);
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector2d t = (ref[(k + 1) % m] - ref[(k + m - 1) % m]).normalized();
    normal[k] = {-t.y(), t.x()};  // left
  }
  return normal;
}

// The ground at t across the track, averaged over a strip along it (±strip): the ground's
// returns lie on the LiDAR's rings, which a drive samples every frame's distance along the
// track, so one cell in several along a line across holds none.
RoadSurface::Sample strip_sample(const RoadSurface& surface, const Eigen::Vector2d& ref, const Eigen::Vector2d& normal,
                                 const Eigen::Vector2d& along, int side, double t, const TrackExtractionParams& p) {
  RoadSurface::Sample out;
  double rs = 0, zs = 0;
  int n = 0, nz = 0, ns = 0;
  for (int j = 0; j < p.strip_samples; ++j) {
    const double a = p.strip_samples > 1 ? p.strip * (2.0 * j / (p.strip_samples - 1) - 1) : 0.0;
    const Eigen::Vector2d q = ref + side * t * normal + a * along;
    const RoadSurface::Sample s = surface.at(q.x(), q.y(), p.standing_value);
    if (!s.known) continue;
    if (s.standing) {
      out.standing_at += s.standing_at;
      ++ns;
    }
    rs += s.reflectivity;
    ++n;
    if (s.has_z) zs += s.z, ++nz;
  }
  if (n == 0) return out;
  out.known = true;
  out.reflectivity = rs / n;
  out.standing = ns > 0;
  if (ns > 0) out.standing_at /= ns;
  out.has_z = nz > 0;
  out.z = nz > 0 ? zs / nz : 0.0;
  return out;
}

// 2. The edge on one side (+1 left, -1 right) of a station, out along its normal; none when the
//    road runs on past max_half_width, or the first sample is already off it.
std::optional<double> edge_on_side(const RoadSurface& surface, const Eigen::Vector2d& ref, const Eigen::Vector2d& normal, int side,
                                   const TrackExtractionParams& p) {
  const Eigen::Vector2d along(normal.y(), -normal.x());
  auto sample = [&](double t) { return strip_sample(surface, ref, normal, along, side, t, p); };
  double prev_t = 0, last_road = -1;
  bool prev_known = false;
  for (double t = 0; t <= p.max_half_width; t += p.probe_step) {
    const RoadSurface::Sample s = sample(t);
    if (!s.known) {
      prev_known = false;
      continue;
    }
    if (s.standing) {
      // A wall: where its returns are (a cell's worth nearer, interpolated, would be 0.1 m
      // inside it), not short of the road's last sample.
      const double at = side * (s.standing_at - ref).dot(normal);
      if (t > 0) return std::clamp(at, prev_known ? prev_t : t - p.probe_step, t + 0.5);
      return std::nullopt;
    }
    if (s.reflectivity >= p.threshold) {
      // After a stretch with no returns (far from the car the ground's are sparse), the edge
      // is somewhere in it: its middle, not its far end (0.4 to 0.8 m out on IMS's main
      // straight, seen from across the track).
      const double edge = prev_known ? refine_edge(sample, t, p) : last_road >= 0 && t - last_road < 1.0 ? 0.5 * (last_road + t) : t;
      if (t > 0) return edge;
      return std::nullopt;
    }
    prev_t = t;
    last_road = t;
    prev_known = true;
  }
  return std::nullopt;
}

// 2. The edges either side of every station (NaN where none was found).
void find_edges(const RoadSurface& surface, const TrackExtractionParams& p, Stations& s) {
  const int m = static_cast<int>(s.ref.size());
  s.wl.assign(m, NAN);
  s.wr.assign(m, NAN);
  s.sides_found = 0;
  for (int k = 0; k < m; ++k) {
    for (int side : {+1, -1})
      if (const std::optional<double> edge = edge_on_side(surface, s.ref[k], s.normal[k], side, p)) (side > 0 ? s.wl : s.wr)[k] = *edge;
    s.sides_found += std::isfinite(s.wl[k]) + std::isfinite(s.wr[k]);
  }
}

// 3. The edges filtered along the track, gaps filled.
void filter_edges(const TrackExtractionParams& p, Stations& s) {
  const int mh = std::max(0, p.median_window / 2);
  s.wl = median_filter(s.wl, mh);
  s.wr = median_filter(s.wr, mh);
  if (!fill_gaps(s.wl) || !fill_gaps(s.wr))
    throw std::invalid_argument("no edge found on one side anywhere round the lap (no ground returns beside the road?)");
}

// Steps 2 and 3 `passes` times: each after the first across the centre line the one before found.
// The driven line's normals in a chicane or a hairpin cross the edges slantwise, and the edges
// measured along them stood up to 2.8 m off (Monza's Roggia, Spielberg's hairpin).
Stations measure_stations(const RoadSurface& surface, std::vector<Eigen::Vector2d> ref, const TrackExtractionParams& p) {
  Stations s;
  s.ref = std::move(ref);
  for (int pass = 0; pass < std::max(1, p.passes); ++pass) {
    if (pass > 0) recentre(s);
    s.normal = left_normals(s.ref);
    find_edges(surface, p, s);
    filter_edges(p, s);
  }
  return s;
}

// 4. The ground's slope across the road at station k, left positive, in degrees (NaN where too
//    few heights to fit).
double ground_bank(const RoadSurface& surface, const Stations& s, int k, const TrackExtractionParams& p) {
  double su = 0, sz = 0, suu = 0, suz = 0;
  int n = 0;
  for (double u = -s.wr[k] + p.bank_margin; u <= s.wl[k] - p.bank_margin; u += 0.25) {
    const Eigen::Vector2d q = s.ref[k] + u * s.normal[k];
    const RoadSurface::Sample g = surface.at(q.x(), q.y(), p.standing_value);
    if (!g.has_z || g.standing || g.reflectivity >= p.threshold) continue;
    su += u; sz += g.z; suu += u * u; suz += u * g.z;
    ++n;
  }
  const double den = n * suu - su * su;
  if (n >= 5 && den > 1e-9) return std::atan((n * suz - su * sz) / den) * 180.0 / M_PI;
  return NAN;
}

// The centre line between the edges, the widths half their sum, and the ground's bank at each station.
void centre_between_edges(const RoadSurface& surface, const Stations& s, const TrackExtractionParams& p, track::CenterLine& c,
                          std::vector<double>& bank) {
  const int m = static_cast<int>(s.ref.size());
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector2d centre = s.ref[k] + 0.5 * (s.wl[k] - s.wr[k]) * s.normal[k];
    c.x.push_back(centre.x());
    c.y.push_back(centre.y());
    c.width_left.push_back(0.5 * (s.wl[k] + s.wr[k]));
    c.width_right.push_back(0.5 * (s.wl[k] + s.wr[k]));
    bank[k] = ground_bank(surface, s, k, p);
  }
}

// The car's roll (degrees) at each driven pose near enough to the reference, gathered at its
// nearest station (the poses in order, so a short search from the last one's).
std::vector<std::vector<double>> rolls_near_stations(const std::vector<Eigen::Vector2d>& driven, const std::vector<double>& roll,
                                                     const std::vector<Eigen::Vector2d>& ref, const TrackExtractionParams& p) {
  const int m = static_cast<int>(ref.size());
  std::vector<std::vector<double>> near(m);
  std::vector<std::size_t> last_seen(m, 0);
  std::size_t at = 0;
  for (std::size_t i = 0; i < driven.size(); ++i) {
    if (!std::isfinite(roll[i])) continue;
    std::size_t best = at;
    double best_d = (driven[i] - ref[at]).squaredNorm();
    int best_j = 0;
    for (int j = -20; j <= 20; ++j) {
      const std::size_t k = static_cast<std::size_t>(((static_cast<long>(at) + j) % m + m) % m);
      const double d = (driven[i] - ref[k]).squaredNorm();
      if (d < best_d) best_d = d, best = k, best_j = j;
    }
    // Lost (the window's edge, or far from the line: the drive before the lap, a jump): all.
    const double reach = p.max_half_width * p.max_half_width;
    if (std::abs(best_j) == 20 || best_d > reach) {
      for (int k = 0; k < m; ++k)
        if (const double d = (driven[i] - ref[k]).squaredNorm(); d < best_d) best_d = d, best = static_cast<std::size_t>(k);
    }
    at = best;
    // (The racing line runs metres from the centre line: any pose on the road counts.)
    // Each station's first pass only: where the loop closes, a lap on, the map's two ends
    // disagree by a lap's drift of height and pitch, and the frames there tilt to reconcile
    // them (IMS: the roll 0.4 deg off for 250 m of the second lap's straight, 1.2 deg where
    // the bank begins); on the first pass the roll has drifted by one lap at most.
    if (best_d > reach) continue;
    if (!near[best].empty() && i - last_seen[best] > p.pass_gap) continue;
    near[best].push_back(roll[i] * 180.0 / M_PI);
    last_seen[best] = i;
  }
  return near;
}

// 4. The bank from the car's roll: per station, the median of the rolls near it (NaN where none).
std::vector<double> roll_bank(const std::vector<Eigen::Vector2d>& driven, const std::vector<double>& roll,
                              const std::vector<Eigen::Vector2d>& ref, const TrackExtractionParams& p) {
  std::vector<std::vector<double>> near = rolls_near_stations(driven, roll, ref, p);
  const int m = static_cast<int>(ref.size());
  std::vector<double> bank(m, NAN);
  for (int k = 0; k < m; ++k) {
    auto& v = near[k];
    if (v.empty()) {
      bank[k] = NAN;
      continue;
    }
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    bank[k] = v[v.size() / 2];
  }
  return bank;
}

// 5. Every `every`th station of `c` kept, the widths narrowed to the stations' edges between them.
track::CenterLine thin_out(const track::CenterLine& c, const std::vector<Eigen::Vector2d>& normal, int every) {
  const int m = static_cast<int>(normal.size());
  std::vector<Eigen::Vector2d> left(m), right(m);
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector2d centre(c.x[k], c.y[k]);
    left[k] = centre + c.width_left[k] * normal[k];
    right[k] = centre - c.width_right[k] * normal[k];
  }
  track::CenterLine kept;
  kept.source = c.source;
  std::vector<int> at;
  for (int k = 0; k < m; k += every) {
    at.push_back(k);
    kept.x.push_back(c.x[k]);
    kept.y.push_back(c.y[k]);
    kept.width_left.push_back(c.width_left[k]);
    kept.width_right.push_back(c.width_right[k]);
    kept.bank_deg.push_back(c.bank_deg[k]);
  }
  narrow_to_stations(kept, at, left, right, m);
  return kept;
}

}  // namespace

ExtractedTrack extract_track(const RoadSurface& surface, const std::vector<Eigen::Vector2d>& driven,
                             const TrackExtractionParams& p, const std::vector<double>* roll) {
  const std::vector<Eigen::Vector2d> lap = one_lap(driven, p);
  const double perimeter = closed_length(lap);
  const int m = std::max(8, static_cast<int>(std::lround(perimeter / p.station_step)));
  const int half = std::max(0, static_cast<int>(std::lround(p.smooth / (perimeter / m))));
  const Stations s = measure_stations(surface, moving_average(resample_closed(lap, perimeter, m), half), p);
  ExtractedTrack out;
  out.stations = static_cast<std::size_t>(m);
  out.sides_found = s.sides_found;
  out.reference = s.ref;
  out.normal = s.normal;
  track::CenterLine& c = out.line;
  c.source = "mapped";
  std::vector<double> bank(m, NAN);
  centre_between_edges(surface, s, p, c, bank);
  if (roll && roll->size() == driven.size()) bank = roll_bank(driven, *roll, s.ref, p);
  bank = median_filter(bank, std::max(0, p.bank_window / 2));
  if (!fill_gaps(bank)) bank.assign(m, 0.0);
  c.bank_deg = std::move(bank);
  // Written every output_step, not every station: the edges' centimetres of jitter from station to
  // station are curvature to a line planner, and on Spielberg's file at 2 m the race's line came
  // within 0.20 m of the wall (1.10 m on the true file; 1.24 m at 6 m, the edges unchanged); the
  // widths narrowed where a chord between two written points would cut beyond a station's edge.
  const int every = std::max(1, static_cast<int>(std::lround(p.output_step / (perimeter / m))));
  if (every > 1) c = thin_out(c, s.normal, every);
  return out;
}

}  // namespace brickyard::mapping
