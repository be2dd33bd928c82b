#include "track.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace brickyard::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> parse_row(const std::string& row, std::size_t want, const std::string& where) {
  std::vector<double> v;
  std::size_t start = 0;
  for (;;) {
    std::size_t comma = row.find(',', start);
    std::string cell = row.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    cell.erase(0, cell.find_first_not_of(" \t\r"));
    cell.erase(cell.find_last_not_of(" \t\r") + 1);
    char* end = nullptr;
    double x = std::strtod(cell.c_str(), &end);
    if (cell.empty() || *end != '\0')
      throw TrackFileError(where + ": field " + std::to_string(v.size() + 1) + " is not a number: '" + cell + "'");
    if (!std::isfinite(x)) throw TrackFileError(where + ": field " + std::to_string(v.size() + 1) + " is not finite");
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != want)
    throw TrackFileError(where + ": " + std::to_string(v.size()) + " fields, expected " + std::to_string(want));
  return v;
}

CenterLine parse(std::istream& in, const std::string& name, std::size_t fields) {
  CenterLine c;
  c.source = name;
  std::string row;
  int line = 0;
  std::vector<int> lines;
  while (std::getline(in, row)) {
    ++line;
    auto first = row.find_first_not_of(" \t\r");
    if (first == std::string::npos || row[first] == '#') continue;
    const std::string where = name + ":" + std::to_string(line);
    auto v = parse_row(row, fields, where);
    if (fields == 4 && (v[2] <= 0 || v[3] <= 0))
      throw TrackFileError(where + ": track widths must be positive");
    if (!c.x.empty() && std::hypot(v[0] - c.x.back(), v[1] - c.y.back()) < 1e-6)
      throw TrackFileError(where + ": repeats the point of line " + std::to_string(lines.back()));
    c.x.push_back(v[0]);
    c.y.push_back(v[1]);
    c.width_right.push_back(fields == 4 ? v[2] : 0.0);
    c.width_left.push_back(fields == 4 ? v[3] : 0.0);
    lines.push_back(line);
  }
  // A file may close the loop by repeating its first point.
  if (c.x.size() > 1 && std::hypot(c.x.back() - c.x[0], c.y.back() - c.y[0]) < 1e-6) {
    c.x.pop_back(); c.y.pop_back(); c.width_right.pop_back(); c.width_left.pop_back();
  }
  if (c.x.size() < 4) throw TrackFileError(name + ": needs at least 4 points, has " + std::to_string(c.x.size()));
  return c;
}

CenterLine load(const std::string& path, std::size_t fields) {
  std::ifstream f(path);
  if (!f) throw TrackFileError(path + ": cannot open");
  return parse(f, path, fields);
}

}  // namespace

CenterLine parse_centerline_csv(std::istream& in, const std::string& name) { return parse(in, name, 4); }
CenterLine load_centerline_csv(const std::string& path) { return load(path, 4); }
CenterLine load_xy_csv(const std::string& path) { return load(path, 2); }

Track::Track(WorldSpec spec) : spec_(std::move(spec)) {
  const auto& c = spec_.line;
  const int n = static_cast<int>(c.x.size());
  if (n < 4 || c.y.size() != c.x.size() || c.width_left.size() != c.x.size() || c.width_right.size() != c.x.size())
    throw std::invalid_argument("track needs at least 4 points with x, y and both widths");
  if (spec_.bank.empty()) spec_.bank.assign(n, 0.0);
  if (static_cast<int>(spec_.bank.size()) != n) throw std::invalid_argument("bank profile has the wrong length");
  seg_.resize(n);
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    Segment& s = seg_[i];
    s.p = {c.x[i], c.y[i]};
    Eigen::Vector2d e(c.x[j] - c.x[i], c.y[j] - c.y[i]);
    s.length = e.norm();
    if (s.length <= 0) throw std::invalid_argument("track has a zero-length segment at point " + std::to_string(i));
    s.t = e / s.length;
    s.n = {-s.t.y(), s.t.x()};
    s.s0 = length_;
    length_ += s.length;
  }
  ccw_ = sim::counter_clockwise(c);
  for (auto& p : spec_.pylons) {
    Frenet f = at(p.s, p.d);
    Eigen::Vector2d q = position(f);
    p.x = q.x();
    p.y = q.y();
    p.z = road_z(f);
  }
}

double Track::wrap_s(double s) const {
  s = std::fmod(s, length_);
  return s < 0 ? s + length_ : s;
}

double Track::lerp(const std::vector<double>& v, int seg, double u) const {
  u = std::clamp(u, 0.0, 1.0);
  return v[seg] + (v[wrap(seg + 1)] - v[seg]) * u;
}

double Track::bank(int seg, double u) const { return lerp(spec_.bank, seg, u); }
double Track::width_left(int seg, double u) const { return lerp(spec_.line.width_left, seg, u); }
double Track::width_right(int seg, double u) const { return lerp(spec_.line.width_right, seg, u); }

double Track::wall_left_d(int seg, double u) const {
  return spec_.walls.left ? width_left(seg, u) + spec_.walls.left_offset : kInf;
}
double Track::wall_right_d(int seg, double u) const {
  return spec_.walls.right ? -(width_right(seg, u) + spec_.walls.right_offset) : -kInf;
}

double Track::road_z(const Frenet& f) const {
  double d = std::clamp(f.d, -width_right(f.seg, f.u), width_left(f.seg, f.u));
  return d * std::tan(bank(f.seg, f.u));
}

Eigen::Vector2d Track::road_gradient(const Frenet& f) const {
  if (f.d > width_left(f.seg, f.u) || f.d < -width_right(f.seg, f.u)) return Eigen::Vector2d::Zero();
  return std::tan(bank(f.seg, f.u)) * seg_[f.seg].n;
}

Frenet Track::project_on(int i, double x, double y) const {
  const Segment& s = seg_[i];
  Eigen::Vector2d q(x - s.p.x(), y - s.p.y());
  Frenet f;
  f.seg = i;
  f.u = q.dot(s.t) / s.length;
  f.d = q.dot(s.n);
  f.s = wrap_s(s.s0 + f.u * s.length);
  return f;
}

Frenet Track::project(double x, double y, int hint) const {
  // The nearest segment: distance to the segment with u clamped to [0, 1].
  auto dist2 = [&](const Frenet& f) {
    const Segment& s = seg_[f.seg];
    double u = std::clamp(f.u, 0.0, 1.0);
    Eigen::Vector2d c = s.p + s.t * (u * s.length);
    return (Eigen::Vector2d(x, y) - c).squaredNorm();
  };
  auto search = [&](int from, int count) {
    Frenet best;
    double bd = kInf;
    for (int k = 0; k < count; ++k) {
      Frenet f = project_on(wrap(from + k), x, y);
      double dd = dist2(f);
      if (dd < bd) { bd = dd; best = f; }
    }
    return std::pair(best, bd);
  };
  if (hint >= 0) {
    auto [f, dd] = search(hint - 4, 9);
    // Trust the local answer when it lies inside its segment's slab, away from the window's ends.
    if (f.u >= -1e-9 && f.u <= 1 + 1e-9 && f.seg != wrap(hint - 4) && f.seg != wrap(hint + 4)) return f;
  }
  return search(0, size()).first;
}

Frenet Track::at(double s, double d) const {
  s = wrap_s(s);
  auto it = std::upper_bound(seg_.begin(), seg_.end(), s, [](double v, const Segment& g) { return v < g.s0; });
  int i = static_cast<int>(it - seg_.begin()) - 1;
  i = std::clamp(i, 0, size() - 1);
  Frenet f;
  f.seg = i;
  f.u = (s - seg_[i].s0) / seg_[i].length;
  f.s = s;
  f.d = d;
  return f;
}

Eigen::Vector2d Track::position(const Frenet& f) const {
  const Segment& s = seg_[f.seg];
  return s.p + s.t * (f.u * s.length) + s.n * f.d;
}

double Track::heading(const Frenet& f) const { return std::atan2(seg_[f.seg].t.y(), seg_[f.seg].t.x()); }

bool counter_clockwise(const CenterLine& c) {
  const std::size_t n = c.x.size();
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) area += c.x[i] * c.y[(i + 1) % n] - c.x[(i + 1) % n] * c.y[i];
  return area > 0;
}

std::vector<double> signed_curvature(const CenterLine& c, double smooth_m) {
  const int n = static_cast<int>(c.x.size());
  std::vector<double> k(n);
  for (int i = 0; i < n; ++i) {
    int a = (i + n - 1) % n, b = (i + 1) % n;
    Eigen::Vector2d p0(c.x[a], c.y[a]), p1(c.x[i], c.y[i]), p2(c.x[b], c.y[b]);
    Eigen::Vector2d e1 = p1 - p0, e2 = p2 - p1;
    double cross = e1.x() * e2.y() - e1.y() * e2.x();
    // Menger curvature of three points: 2 sin(angle) / chord.
    k[i] = 2 * cross / (e1.norm() * e2.norm() * (p2 - p0).norm());
  }
  if (smooth_m <= 0) return k;
  return cyclic_average(k, curvature_window(c, smooth_m));
}

int curvature_window(const CenterLine& c, double smooth_m) {
  if (smooth_m <= 0) return 0;
  const int n = static_cast<int>(c.x.size());
  double mean_len = 0;
  for (int i = 0; i < n; ++i) {
    const int b = (i + 1) % n;
    mean_len += Eigen::Vector2d(c.x[b] - c.x[i], c.y[b] - c.y[i]).norm() / n;
  }
  return std::max(0, static_cast<int>(std::round(smooth_m / mean_len / 2)));
}

std::vector<double> cyclic_average(const std::vector<double>& v, int half) {
  const int n = static_cast<int>(v.size());
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int j = -half; j <= half; ++j) sum += v[((i + j) % n + n) % n];
    out[i] = sum / (2 * half + 1);
  }
  return out;
}

std::vector<double> bank_profile(const CenterLine& c, const BankSpec& spec) {
  const int n = static_cast<int>(c.x.size());
  std::vector<double> target(n, 0.0);
  const double rad = spec.degrees * M_PI / 180.0;
  // The outside of a counter-clockwise loop is on the right: raising it lowers the left edge.
  const double loop_sign = counter_clockwise(c) ? -1.0 : 1.0;
  std::vector<double> s(n, 0.0);
  for (int i = 1; i < n; ++i) s[i] = s[i - 1] + std::hypot(c.x[i] - c.x[i - 1], c.y[i] - c.y[i - 1]);
  if (spec.mode == "none") return target;
  if (spec.mode == "constant") {
    target.assign(n, loop_sign * rad);
    return target;
  }
  if (spec.mode == "curvature") {
    auto k = signed_curvature(c, 50.0);
    for (int i = 0; i < n; ++i)
      if (std::abs(k[i]) > spec.curvature_threshold) target[i] = (k[i] > 0 ? -1.0 : 1.0) * rad;
  } else if (spec.mode == "segments") {
    for (const auto& r : spec.segments)
      for (int i = 0; i < n; ++i)
        if (s[i] >= r.s0 && s[i] < r.s1) target[i] = loop_sign * r.degrees * M_PI / 180.0;
  } else {
    throw std::invalid_argument("unknown bank mode '" + spec.mode + "'");
  }
  // Ramp in and out: a moving average over the transition length.
  double total = s[n - 1] + std::hypot(c.x[0] - c.x[n - 1], c.y[0] - c.y[n - 1]);
  int half = std::max(0, static_cast<int>(std::round(spec.transition_m / (total / n) / 2)));
  if (half == 0) return target;
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int j = -half; j <= half; ++j) sum += target[(i + j + n) % n];
    out[i] = sum / (2 * half + 1);
  }
  return out;
}

}  // namespace brickyard::sim
