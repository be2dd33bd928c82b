#include "figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace brickyard::report {
namespace {

// ---- gnuplot boilerplate shared by the figures ----

// gnuplot's strings are single-quoted: a quote inside is doubled, and a control character (a
// newline would end the command and start another — `!` runs a shell) becomes '?'. Names come
// from the recording, which anyone may have written.
std::string gq(const std::string& s) {
  std::string o = "'";
  for (char c : s) {
    if (c == '\'') o += "''";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) o += '?';
    else o += c;
  }
  return o + "'";
}

// A data file of the work folder, as a gnuplot string.
std::string data(const Writer& w, const std::string& name) { return gq(w.file(name).string()); }

// The start of every figure's script: an SVG terminal of this size, the grid, <name>.svg.
std::string begin_svg(const Writer& w, const std::string& name, int width = 900, int height = 520) {
  return "set terminal svg size " + std::to_string(width) + "," + std::to_string(height) +
         " dynamic font 'sans,11'\nset grid lc rgb '#dddddd'\nset output " + gq(w.file(name + ".svg").string()) + "\n";
}

std::string axes(const std::string& x, const std::string& y) { return "set xlabel '" + x + "'\nset ylabel '" + y + "'\n"; }

// The end of every figure's script: one plot command of these items.
std::string plot(const std::vector<std::string>& items) {
  std::string s = "plot ";
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", " : "") + items[i];
  return s + "\n";
}

// ---- what the figures read ----

int mode_colour(const std::string& name) {
  if (name == "PATH") return 1;
  if (name == "WALL_FOLLOW") return 2;
  if (name == "SAFE_STOP") return 3;
  return 0;
}

// The value of a step timeline at t (the last sample at or before t).
template <class T>
const T* at(const std::vector<T>& v, double t) {
  auto it = std::upper_bound(v.begin(), v.end(), t, [](double x, const T& m) { return x < m.t; });
  return it == v.begin() ? nullptr : &*(it - 1);
}

// ---- the figures ----

// 1. The track and the driven path, coloured by mode, with the raw GNSS fixes.
std::optional<Figure> track_map(const RunData& d, const Writer& w) {
  if (d.truth.empty()) return std::nullopt;
  auto e = w.open("edges.dat");
  for (std::size_t i = 0; i < d.left_x.size(); ++i) e << d.left_x[i] << ' ' << d.left_y[i] << '\n';
  e << "\n\n";
  for (std::size_t i = 0; i < d.right_x.size(); ++i) e << d.right_x[i] << ' ' << d.right_y[i] << '\n';
  auto p = w.open("driven.dat");
  int last = -1;
  for (std::size_t i = 0; i < d.truth.size(); ++i) {
    const auto& s = d.truth[i];
    const auto* m = at(d.manager, s.t);
    const int c = m ? mode_colour(m->name) : 0;
    if (c != last && last >= 0) p << s.x << ' ' << s.y << ' ' << last << "\n\n";  // a gap closes each colour run
    if (c != last || i % 10 == 0 || i + 1 == d.truth.size()) p << s.x << ' ' << s.y << ' ' << c << '\n';  // every 10th is enough
    last = c;
  }
  auto g = w.open("gnss.dat");
  for (const auto& f : d.fixes) g << f.x << ' ' << f.y << ' ' << f.receiver << '\n';
  auto py = w.open("pylons.dat");
  for (const auto& q : d.pylons) py << q.x << ' ' << q.y << ' ' << q.radius << '\n';
  std::vector<std::string> items = {data(w, "edges.dat") + " w l lc rgb '#888888' t 'track edges'"};
  if (!d.fixes.empty()) items.push_back(data(w, "gnss.dat") + " u 1:2 w p pt 7 ps 0.2 lc rgb '#c5b0d5' t 'GNSS fixes (raw)'");
  items.push_back(data(w, "driven.dat") + " u 1:2:3 w l lw 2 lc palette t 'driven (green PATH, orange WALL\\_FOLLOW, red SAFE\\_STOP)'");
  if (!d.pylons.empty()) items.push_back(data(w, "pylons.dat") + " u 1:2:3 w circles lc rgb 'black' fs solid t 'pylons'");
  return Figure{"map", "Track map", "The driven path (ground truth) coloured by the system manager's mode, over the track's edges, with every raw GNSS fix.",
                begin_svg(w, "map", 900, 900) + "set key top center horizontal\nset size ratio -1\n" + axes("x, m", "y, m") +
                    "set palette defined (0 '#1f77b4', 1 '#2ca02c', 2 '#ff7f0e', 3 '#d62728')\nset cbrange [0:3]\nunset colorbox\n" + plot(items)};
}

// 2. Position error over time.
std::optional<Figure> position_error(const RunData& d, const Writer& w) {
  if (d.truth.empty() || d.estimates.empty()) return std::nullopt;
  auto f = w.open("error.dat");
  for (const auto& e : d.estimates) {
    auto it = std::lower_bound(d.truth.begin(), d.truth.end(), e.t, [](const auto& p, double t) { return p.t < t; });
    if (it == d.truth.end() || it == d.truth.begin()) continue;
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double u = b.t > a.t ? (e.t - a.t) / (b.t - a.t) : 0;
    f << e.t << ' ' << std::hypot(e.x - (a.x + u * (b.x - a.x)), e.y - (a.y + u * (b.y - a.y))) << '\n';
  }
  return Figure{"error", "Position error", "Distance between the estimate and the truth at the estimate's stamp.",
                begin_svg(w, "error") + axes("time, s", "position error, m") +
                    plot({data(w, "error.dat") + " w l lw 1.5 lc rgb '#1f77b4' t 'estimate - truth'"})};
}

// 3. Δk per receiver with ε and δ (the fusion's metrics epsilon_m and delta_m).
std::optional<Figure> receiver_deltas(const RunData& d, const nlohmann::json& summary, const Writer& w) {
  if (d.estimates.empty()) return std::nullopt;
  std::size_t receivers = 0;
  for (const auto& e : d.estimates) receivers = std::max(receivers, e.delta.size());
  if (receivers == 0) return std::nullopt;
  auto f = w.open("delta.dat");
  for (const auto& e : d.estimates) {
    // Estimates between GNSS epochs carry no Δ (zeros): only the epochs are drawn.
    if (std::none_of(e.delta.begin(), e.delta.end(), [](double v) { return v > 0; })) continue;
    f << e.t;
    for (std::size_t k = 0; k < receivers; ++k) f << ' ' << (k < e.delta.size() && e.delta[k] > 0 ? e.delta[k] : NAN);
    f << '\n';
  }
  double eps = NAN, del = NAN;
  // Held: items() refers to it (a temporary would be gone by the loop).
  const auto nodes = summary.value("nodes", nlohmann::json::object());
  for (const auto& [name, n] : nodes.items())
    if (n.contains("metrics") && n["metrics"].contains("epsilon_m") && n["metrics"]["epsilon_m"].is_number()) {
      eps = n["metrics"]["epsilon_m"].get<double>();
      del = n["metrics"].value("delta_m", NAN);
    }
  std::vector<std::string> items;
  for (std::size_t k = 0; k < receivers; ++k)
    items.push_back(data(w, "delta.dat") + " u 1:" + std::to_string(k + 2) + " w l t 'Δ receiver " + std::to_string(k) + "'");
  if (std::isfinite(eps)) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "%g w l dt 2 lc rgb '#2ca02c' t 'ε = %g m'", eps, eps);
    items.push_back(buf);
    std::snprintf(buf, sizeof buf, "%g w l dt 2 lc rgb '#d62728' t 'δ = %g m'", del, del);
    items.push_back(buf);
  }
  return Figure{"delta", "Δk per receiver", "Each receiver's distance to the filter's prediction (log scale), with the selection's thresholds ε (below: every fix qualifies) and δ (above: rejected).",
                begin_svg(w, "delta") + "set logscale y\n" + axes("time, s", "Δk, m") + plot(items)};
}

// 4. Status timeline: the localization status and the system manager's mode.
std::optional<Figure> status_timeline(const RunData& d, const Writer& w) {
  if (d.localization.empty() && d.manager.empty()) return std::nullopt;
  std::vector<std::string> items;
  for (auto [name, v] : {std::pair{"localization", &d.localization}, std::pair{"manager", &d.manager}}) {
    if (v->empty()) continue;
    auto f = w.open(std::string(name) + "_mode.dat");
    for (const auto& m : *v) {
      int level = m.mode;
      if (v == &d.manager) level = std::max(0, mode_colour(m.name) - 1);
      f << m.t << ' ' << level << '\n';
    }
    items.push_back(data(w, std::string(name) + "_mode.dat") + " w steps lw 2 t '" + (v == &d.manager ? "system manager" : "localization status") + "'");
  }
  return Figure{"status", "Status timeline", "The localization manager's status and the system manager's mode over the run.",
                begin_svg(w, "status") + "set xlabel 'time, s'\nset ytics ('NORMAL / PATH' 0, 'WARNING / WALL\\_FOLLOW' 1, 'EMERGENCY / SAFE\\_STOP' 2)\nset yrange [-0.3:2.3]\n" + plot(items)};
}

// 5. Steering of the controllers, around the fault when there is one.
std::optional<Figure> steering(const RunData& d, const Writer& w) {
  if (d.commands.empty()) return std::nullopt;
  double t0 = -1e18, t1 = 1e18;
  double first = NAN, last = NAN;
  for (const auto& m : d.manager)
    if (mode_colour(m.name) > 1) {
      if (std::isnan(first)) first = m.t;
      last = m.t;
    }
  if (std::isfinite(first)) { t0 = first - 5; t1 = last + 5; }
  std::vector<std::string> items;
  for (std::size_t k = 0; k < d.commands.size(); ++k) {
    const std::string name = "steer_" + std::to_string(k) + ".dat";
    auto f = w.open(name);
    for (const auto& c : d.commands[k].second)
      if (c.t >= t0 && c.t <= t1) f << c.t << ' ' << c.steer * 180 / M_PI << '\n';
    std::string label = d.commands[k].first;
    std::replace(label.begin(), label.end(), '_', '-');
    items.push_back(data(w, name) + " w l lw 1.5 t " + gq(label));
  }
  return Figure{"steering", "Steering",
                std::isfinite(first) ? "Every controller's steering command from 5 s before the manager left the path to 5 s after it came back."
                                     : "Every controller's steering command over the run (the manager never left the path).",
                begin_svg(w, "steering") + axes("time, s", "road-wheel angle, deg") + plot(items)};
}

// 6. The obstacle scene, along the track (s) and across it (d): pylons, the plans published on
//    the way to them and the path driven. (Drawn in the track's frame: a straight seen from
//    above is a thin strip.)
std::optional<Figure> obstacle_scene(const RunData& d, const nlohmann::json& summary, const Writer& w) {
  if (d.pylons.empty() || d.truth.empty() || d.centre_x.empty()) return std::nullopt;
  double s0 = 1e18, s1 = -1e18;
  for (const auto& p : d.pylons) { s0 = std::min(s0, p.s); s1 = std::max(s1, p.s); }
  s0 -= 150;
  s1 += 100;
  // Along-track distance to a window that may cross the start line: unwrap near s0.
  double length = 0;
  for (std::size_t i = 0; i < d.centre_x.size(); ++i) {
    const std::size_t j = (i + 1) % d.centre_x.size();
    length += std::hypot(d.centre_x[j] - d.centre_x[i], d.centre_y[j] - d.centre_y[i]);
  }
  auto unwrap = [&](double s) {
    while (s < s0 - length / 2) s += length;
    while (s > s0 + length / 2) s -= length;
    return s;
  };
  auto inside = [&](double s) { return s >= s0 && s <= s1; };
  auto f = w.open("scene_driven.dat");
  double last_s = NAN;
  for (const auto& p : d.truth) {
    const double s = unwrap(p.s);
    if (!inside(s)) { if (!std::isnan(last_s)) f << "\n"; last_s = NAN; continue; }
    f << s << ' ' << p.d << '\n';
    last_s = s;
  }
  auto e = w.open("scene_edges.dat");
  for (int side = 0; side < 2; ++side) {
    double acc = 0;
    for (std::size_t i = 0; i <= d.centre_x.size(); ++i) {
      const std::size_t k = i % d.centre_x.size();
      if (i > 0) {
        const std::size_t a = i - 1;
        acc += std::hypot(d.centre_x[k] - d.centre_x[a], d.centre_y[k] - d.centre_y[a]);
      }
      const double s = unwrap(acc);
      if (inside(s)) e << s << ' ' << (side ? -d.width_right[k] : d.width_left[k]) << '\n';
      else e << '\n';
    }
    e << "\n\n";
  }
  auto py = w.open("scene_pylons.dat");
  for (const auto& p : d.pylons) py << unwrap(p.s) << ' ' << p.d << ' ' << p.radius << '\n';
  auto dist = [&](double x, double y) {
    double best = 1e18;
    for (const auto& p : d.pylons) best = std::min(best, std::hypot(p.x - x, p.y - y));
    return best;
  };
  std::vector<std::string> items = {data(w, "scene_edges.dat") + " w l lc rgb '#888888' t 'track edges'"};
  // The road graph's nodes around the obstacles, as the planner reported them (its metrics
  // lattice_near_obstacles_x and _y).
  // Held: items() refers to it (a temporary would be gone by the loop).
  const auto nodes = summary.value("nodes", nlohmann::json::object());
  for (const auto& [name, n] : nodes.items()) {
    if (!n.is_object() || !n.contains("metrics") || !n["metrics"].is_object() || !n["metrics"].contains("lattice_near_obstacles_x")) continue;
    const auto& xs = n["metrics"]["lattice_near_obstacles_x"];
    const auto ys = n["metrics"].value("lattice_near_obstacles_y", nlohmann::json::array());
    if (!xs.is_array() || !ys.is_array()) continue;
    auto g = w.open("scene_lattice.dat");
    for (std::size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
      if (!xs[i].is_number() || !ys[i].is_number()) continue;
      const auto [ls, ld] = to_track(d, xs[i].get<double>(), ys[i].get<double>());
      if (inside(unwrap(ls))) g << unwrap(ls) << ' ' << ld << '\n';
    }
    items.push_back(data(w, "scene_lattice.dat") + " w p pt 7 ps 0.25 lc rgb '#999999' t 'road graph nodes'");
    break;
  }
  items.push_back(data(w, "scene_driven.dat") + " w l lw 2 lc rgb '#2ca02c' t 'driven (every pass)'");
  // The plans published 150, 100 and 50 m before the pylons.
  int shown = 0;
  for (double want : {150.0, 100.0, 50.0}) {
    const PathSnapshot* pick = nullptr;
    double err = 1e18;
    for (const auto& p : d.paths) {
      const auto* car = at(d.truth, p.t);
      if (!car || !inside(unwrap(car->s))) continue;
      const double dd = dist(car->x, car->y);
      if (std::abs(dd - want) < err) { err = std::abs(dd - want); pick = &p; }
    }
    if (!pick || err > 20) continue;
    const std::string name = "scene_path_" + std::to_string(shown) + ".dat";
    auto g = w.open(name);
    for (std::size_t i = 0; i < pick->x.size(); ++i) {
      const auto [s, dd] = to_track(d, pick->x[i], pick->y[i]);
      if (inside(unwrap(s))) g << unwrap(s) << ' ' << dd << '\n';
    }
    char label[64];
    std::snprintf(label, sizeof label, "plan at t = %.1f s (%.0f m to go)", pick->t, want);
    items.push_back(data(w, name) + " w l dt 2 lw 1.5 t " + gq(label));
    ++shown;
  }
  items.push_back(data(w, "scene_pylons.dat") + " u 1:2 w p pt 7 ps 1.2 lc rgb 'black' t 'pylons'");
  return Figure{"scene", "Obstacle scene",
                "Along the track (s) and across it (d, left positive): the road graph's nodes around the pylons (as the planner reported them), the pylons, the plans the planner published on the way to them and the path the car drove.",
                begin_svg(w, "scene") + axes("s along the centre line, m", "d, m (left positive)") + "set key outside bottom center horizontal\n" + plot(items)};
}

// 7. Speed over distance.
std::optional<Figure> speed_over_distance(const RunData& d, const Writer& w) {
  if (d.truth.empty()) return std::nullopt;
  auto f = w.open("speed.dat");
  double dist = 0;
  for (std::size_t i = 0; i < d.truth.size(); ++i) {
    if (i > 0) dist += std::hypot(d.truth[i].x - d.truth[i - 1].x, d.truth[i].y - d.truth[i - 1].y);
    if (i % 10 == 0) f << dist << ' ' << d.truth[i].speed << '\n';
  }
  return Figure{"speed", "Speed over distance", "The car's speed (ground truth) against the distance it has driven.",
                begin_svg(w, "speed") + axes("distance driven, m", "speed, m/s") + plot({data(w, "speed.dat") + " w l lw 1.5 lc rgb '#1f77b4' t 'speed'"})};
}

}  // namespace

std::vector<Figure> figures(const RunData& d, const nlohmann::json& summary, const Writer& w) {
  std::vector<Figure> out;
  auto add = [&](std::optional<Figure> f) {
    if (f) out.push_back(std::move(*f));
  };
  add(track_map(d, w));
  add(position_error(d, w));
  add(receiver_deltas(d, summary, w));
  add(status_timeline(d, w));
  add(steering(d, w));
  add(obstacle_scene(d, summary, w));
  add(speed_over_distance(d, w));
  return out;
}

}  // namespace brickyard::report
