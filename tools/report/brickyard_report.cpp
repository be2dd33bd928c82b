// brickyard-report RUN_DIR: one HTML file, RUN_DIR/report.html, with the figures that tell a
// run's story, drawn by gnuplot from RUN_DIR/recording.db3 and summary.json (a tour of the
// figures: docs/report.md). `brickyard report RUN_DIR` runs it, and `brickyard run --out DIR`
// does at the end of a run. Exit 2 with a message naming the file when the run folder is not
// usable or gnuplot is missing.
#include "run_data.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

extern char** environ;

namespace fs = std::filesystem;
using brickyard::report::RunData;

namespace {

struct Figure {
  std::string name, title, caption, script;  // script: gnuplot commands drawing <name>.svg
};

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

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

// gnuplot on a script, its output into a log; no shell in between. Its exit code.
int run_gnuplot(const fs::path& script, const fs::path& log) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  std::string prog = "gnuplot", arg = script.string();
  std::vector<char*> argv = {prog.data(), arg.data(), nullptr};
  pid_t pid = 0;
  const int err = posix_spawnp(&pid, "gnuplot", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (err != 0) return 127;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

bool have_gnuplot() {
  const char* path = std::getenv("PATH");
  std::string p = path ? path : "/usr/bin:/bin";
  for (std::size_t at = 0; at <= p.size();) {
    const std::size_t colon = std::min(p.find(':', at), p.size());
    if (access((p.substr(at, colon - at) + "/gnuplot").c_str(), X_OK) == 0) return true;
    at = colon + 1;
  }
  return false;
}

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

class Writer {
 public:
  explicit Writer(fs::path dir) : dir_(std::move(dir)) {}
  fs::path file(const std::string& name) const { return dir_ / name; }
  std::ofstream open(const std::string& name) const {
    std::ofstream f(file(name));
    f.precision(10);
    return f;
  }

 private:
  fs::path dir_;
};

void figures(const RunData& d, const nlohmann::json& summary, const Writer& w, std::vector<Figure>& out) {
  const std::string term = "set terminal svg size 900,520 dynamic font 'sans,11'\nset grid lc rgb '#dddddd'\n";
  // 1. The track and the driven path, coloured by mode, with the raw GNSS fixes.
  if (!d.truth.empty()) {
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
    std::string s = "set terminal svg size 900,900 dynamic font 'sans,11'\nset grid lc rgb '#dddddd'\nset output " + gq(w.file("map.svg").string()) +
                    "\nset key top center horizontal\nset size ratio -1\nset xlabel 'x, m'\nset ylabel 'y, m'\n"
                    "set palette defined (0 '#1f77b4', 1 '#2ca02c', 2 '#ff7f0e', 3 '#d62728')\nset cbrange [0:3]\nunset colorbox\n"
                    "plot " + gq(w.file("edges.dat").string()) + " w l lc rgb '#888888' t 'track edges'";
    if (!d.fixes.empty()) s += ", " + gq(w.file("gnss.dat").string()) + " u 1:2 w p pt 7 ps 0.2 lc rgb '#c5b0d5' t 'GNSS fixes (raw)'";
    s += ", " + gq(w.file("driven.dat").string()) + " u 1:2:3 w l lw 2 lc palette t 'driven (green PATH, orange WALL\\_FOLLOW, red SAFE\\_STOP)'";
    if (!d.pylons.empty()) s += ", " + gq(w.file("pylons.dat").string()) + " u 1:2:3 w circles lc rgb 'black' fs solid t 'pylons'";
    out.push_back({"map", "Track map", "The driven path (ground truth) coloured by the system manager's mode, over the track's edges, with every raw GNSS fix.", s + "\n"});
  }
  // 2. Position error over time.
  if (!d.truth.empty() && !d.estimates.empty()) {
    auto f = w.open("error.dat");
    for (const auto& e : d.estimates) {
      auto it = std::lower_bound(d.truth.begin(), d.truth.end(), e.t, [](const auto& p, double t) { return p.t < t; });
      if (it == d.truth.end() || it == d.truth.begin()) continue;
      const auto& b = *it;
      const auto& a = *(it - 1);
      const double u = b.t > a.t ? (e.t - a.t) / (b.t - a.t) : 0;
      f << e.t << ' ' << std::hypot(e.x - (a.x + u * (b.x - a.x)), e.y - (a.y + u * (b.y - a.y))) << '\n';
    }
    out.push_back({"error", "Position error", "Distance between the estimate and the truth at the estimate's stamp.",
                   term + "set output " + gq(w.file("error.svg").string()) + "\nset xlabel 'time, s'\nset ylabel 'position error, m'\nplot " +
                       gq(w.file("error.dat").string()) + " w l lw 1.5 lc rgb '#1f77b4' t 'estimate - truth'\n"});
  }
  // 3. Δk per receiver with ε and δ.
  if (!d.estimates.empty()) {
    std::size_t receivers = 0;
    for (const auto& e : d.estimates) receivers = std::max(receivers, e.delta.size());
    if (receivers > 0) {
      auto f = w.open("delta.dat");
      for (const auto& e : d.estimates) {
        // Estimates between GNSS epochs carry no Δ (zeros): only the epochs are drawn.
        if (std::none_of(e.delta.begin(), e.delta.end(), [](double v) { return v > 0; })) continue;
        f << e.t;
        for (std::size_t k = 0; k < receivers; ++k) f << ' ' << (k < e.delta.size() && e.delta[k] > 0 ? e.delta[k] : NAN);
        f << '\n';
      }
      double eps = NAN, del = NAN;
      for (const auto& [name, n] : summary.value("nodes", nlohmann::json::object()).items())
        if (n.contains("metrics") && n["metrics"].contains("epsilon_m") && n["metrics"]["epsilon_m"].is_number()) {
          eps = n["metrics"]["epsilon_m"].get<double>();
          del = n["metrics"].value("delta_m", NAN);
        }
      std::string s = term + "set output " + gq(w.file("delta.svg").string()) +
                      "\nset logscale y\nset xlabel 'time, s'\nset ylabel 'Δk, m'\nplot ";
      for (std::size_t k = 0; k < receivers; ++k)
        s += (k ? ", " : "") + gq(w.file("delta.dat").string()) + " u 1:" + std::to_string(k + 2) + " w l t 'Δ receiver " + std::to_string(k) + "'";
      char buf[160];
      if (std::isfinite(eps)) {
        std::snprintf(buf, sizeof buf, ", %g w l dt 2 lc rgb '#2ca02c' t 'ε = %g m', %g w l dt 2 lc rgb '#d62728' t 'δ = %g m'", eps, eps, del, del);
        s += buf;
      }
      out.push_back({"delta", "Δk per receiver", "Each receiver's distance to the filter's prediction (log scale), with the selection's thresholds ε (below: every fix qualifies) and δ (above: rejected).", s + "\n"});
    }
  }
  // 4. Status timeline.
  if (!d.localization.empty() || !d.manager.empty()) {
    std::string s = term + "set output " + gq(w.file("status.svg").string()) +
                    "\nset xlabel 'time, s'\nset ytics ('NORMAL / PATH' 0, 'WARNING / WALL\\_FOLLOW' 1, 'EMERGENCY / SAFE\\_STOP' 2)\nset yrange [-0.3:2.3]\nplot ";
    bool first = true;
    for (auto [name, v] : {std::pair{"localization", &d.localization}, std::pair{"manager", &d.manager}}) {
      if (v->empty()) continue;
      auto f = w.open(std::string(name) + "_mode.dat");
      for (const auto& m : *v) {
        int level = m.mode;
        if (v == &d.manager) level = std::max(0, mode_colour(m.name) - 1);
        f << m.t << ' ' << level << '\n';
      }
      s += (first ? "" : ", ") + gq(w.file(std::string(name) + "_mode.dat").string()) + " w steps lw 2 t '" +
           (v == &d.manager ? "system manager" : "localization status") + "'";
      first = false;
    }
    out.push_back({"status", "Status timeline", "The localization manager's status and the system manager's mode over the run.", s + "\n"});
  }
  // 5. Steering of the controllers, around the fault when there is one.
  if (!d.commands.empty()) {
    double t0 = -1e18, t1 = 1e18;
    double first = NAN, last = NAN;
    for (const auto& m : d.manager)
      if (mode_colour(m.name) > 1) {
        if (std::isnan(first)) first = m.t;
        last = m.t;
      }
    if (std::isfinite(first)) { t0 = first - 5; t1 = last + 5; }
    std::string s = term + "set output " + gq(w.file("steering.svg").string()) + "\nset xlabel 'time, s'\nset ylabel 'road-wheel angle, deg'\nplot ";
    for (std::size_t k = 0; k < d.commands.size(); ++k) {
      const std::string name = "steer_" + std::to_string(k) + ".dat";
      auto f = w.open(name);
      for (const auto& c : d.commands[k].second)
        if (c.t >= t0 && c.t <= t1) f << c.t << ' ' << c.steer * 180 / M_PI << '\n';
      std::string label = d.commands[k].first;
      std::replace(label.begin(), label.end(), '_', '-');
      s += (k ? ", " : "") + gq(w.file(name).string()) + " w l lw 1.5 t " + gq(label);
    }
    out.push_back({"steering", "Steering", std::isfinite(first) ? "Every controller's steering command from 5 s before the manager left the path to 5 s after it came back." : "Every controller's steering command over the run (the manager never left the path).", s + "\n"});
  }
  // 6. The obstacle scene, along the track (s) and across it (d): pylons, the plans published on
  //    the way to them and the path driven. (Drawn in the track's frame: a straight seen from
  //    above is a thin strip.)
  if (!d.pylons.empty() && !d.truth.empty() && !d.centre_x.empty()) {
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
    // The road graph's nodes around the obstacles, as the planner reported them.
    std::string lattice;
    for (const auto& [name, n] : summary.value("nodes", nlohmann::json::object()).items()) {
      if (!n.is_object() || !n.contains("metrics") || !n["metrics"].is_object() || !n["metrics"].contains("lattice_near_obstacles_x")) continue;
      const auto& xs = n["metrics"]["lattice_near_obstacles_x"];
      const auto ys = n["metrics"].value("lattice_near_obstacles_y", nlohmann::json::array());
      if (!xs.is_array() || !ys.is_array()) continue;
      auto g = w.open("scene_lattice.dat");
      for (std::size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
        if (!xs[i].is_number() || !ys[i].is_number()) continue;
        const auto [ls, ld] = brickyard::report::to_track(d, xs[i].get<double>(), ys[i].get<double>());
        if (inside(unwrap(ls))) g << unwrap(ls) << ' ' << ld << '\n';
      }
      lattice = ", " + gq(w.file("scene_lattice.dat").string()) + " w p pt 7 ps 0.25 lc rgb '#999999' t 'road graph nodes'";
      break;
    }
    std::string paths;
    int shown = 0;
    for (double want : {150.0, 100.0, 50.0}) {
      const brickyard::report::PathSnapshot* pick = nullptr;
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
        const auto [s, dd] = brickyard::report::to_track(d, pick->x[i], pick->y[i]);
        if (inside(unwrap(s))) g << unwrap(s) << ' ' << dd << '\n';
      }
      char label[64];
      std::snprintf(label, sizeof label, "plan at t = %.1f s (%.0f m to go)", pick->t, want);
      paths += ", " + gq(w.file(name).string()) + " w l dt 2 lw 1.5 t " + gq(label);
      ++shown;
    }
    out.push_back({"scene", "Obstacle scene",
                   "Along the track (s) and across it (d, left positive): the road graph's nodes around the pylons (as the planner reported them), the pylons, the plans the planner published on the way to them and the path the car drove.",
                   term + "set output " + gq(w.file("scene.svg").string()) + "\nset xlabel 's along the centre line, m'\nset ylabel 'd, m (left positive)'\nset key outside bottom center horizontal\nplot " +
                       gq(w.file("scene_edges.dat").string()) + " w l lc rgb '#888888' t 'track edges'" + lattice + ", " + gq(w.file("scene_driven.dat").string()) +
                       " w l lw 2 lc rgb '#2ca02c' t 'driven (every pass)'" + paths + ", " + gq(w.file("scene_pylons.dat").string()) +
                       " u 1:2 w p pt 7 ps 1.2 lc rgb 'black' t 'pylons'\n"});
  }
  // 7. Speed over distance.
  if (!d.truth.empty()) {
    auto f = w.open("speed.dat");
    double dist = 0;
    for (std::size_t i = 0; i < d.truth.size(); ++i) {
      if (i > 0) dist += std::hypot(d.truth[i].x - d.truth[i - 1].x, d.truth[i].y - d.truth[i - 1].y);
      if (i % 10 == 0) f << dist << ' ' << d.truth[i].speed << '\n';
    }
    out.push_back({"speed", "Speed over distance", "The car's speed (ground truth) against the distance it has driven.",
                   term + "set output " + gq(w.file("speed.svg").string()) + "\nset xlabel 'distance driven, m'\nset ylabel 'speed, m/s'\nplot " +
                       gq(w.file("speed.dat").string()) + " w l lw 1.5 lc rgb '#1f77b4' t 'speed'\n"});
  }
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string metric_text(const nlohmann::json& v) {
  char b[48];
  if (v.is_number()) { std::snprintf(b, sizeof b, "%.4g", v.get<double>()); return b; }
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string o;
    for (const auto& x : v) o += (o.empty() ? "" : ", ") + metric_text(x);
    return o;
  }
  return v.dump();
}

int run(const fs::path& dir) {
  const fs::path summary_file = dir / "summary.json";
  std::ifstream sf(summary_file);
  if (!sf) throw std::invalid_argument(summary_file.string() + ": not found (is " + dir.string() + " a run folder of brickyard run --out?)");
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(sf);
  } catch (const std::exception& e) {
    throw std::invalid_argument(summary_file.string() + ": " + e.what());
  }
  if (!summary.is_object()) throw std::invalid_argument(summary_file.string() + ": not a run summary (not a JSON object)");
  // The run's own recording, as its summary names it: the folder's ("recording.db3", relative to
  // the folder) or a --record file (absolute). No summary entry: the run kept none.
  const auto rec = summary.value("recording", nlohmann::json::object());
  if (!rec.is_object() || !rec.contains("file") || !rec["file"].is_string())
    throw std::invalid_argument(summary_file.string() + ": the run kept no recording (run it with --out, or --record FILE)");
  fs::path recording = rec["file"].get<std::string>();
  if (recording.is_relative()) recording = dir / recording;
  if (!fs::exists(recording)) throw std::invalid_argument(recording.string() + ": the run's recording is gone");
  if (!have_gnuplot()) throw std::invalid_argument("gnuplot not found: the report's figures are drawn with it (apt-get install gnuplot-nox)");
  RunData data;
  try {
    data = brickyard::report::read_run(recording.string());
  } catch (const std::exception& e) {
    throw std::invalid_argument(e.what());
  }
  const fs::path work = dir / "report_files";
  fs::create_directories(work);
  Writer w(work);
  std::vector<Figure> figs;
  figures(data, summary, w, figs);
  std::ofstream gp(work / "figures.gp");
  for (const auto& f : figs) gp << f.script << "unset output\nreset\n";
  gp.close();
  if (run_gnuplot(work / "figures.gp", work / "gnuplot.log") != 0)
    throw std::runtime_error("gnuplot failed: see " + (work / "gnuplot.log").string());

  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Brickyard run: " << esc(summary.value("graph", "")) << "</title>\n"
    << "<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}figure{margin:2em 0}figcaption{color:#555}"
       ".ok{color:#2ca02c}.bad{color:#d62728}</style></head><body>\n";
  const std::string result = summary.value("result", "?");
  h << "<h1>Run of <code>" << esc(summary.value("graph", "")) << "</code></h1>\n<table>\n"
    << "<tr><th>result</th><td class=\"" << (result == "success" ? "ok" : "bad") << "\">" << esc(result) << ": " << esc(summary.value("reason", "")) << "</td></tr>\n"
    << "<tr><th>graph file</th><td>" << esc(summary.value("graph_file", "")) << "</td></tr>\n";
  char b[96];
  std::snprintf(b, sizeof b, "%.3f s of sim time in %.3f s", summary.value("sim_time_s", 0.0), summary.value("wall_time_s", 0.0));
  h << "<tr><th>time</th><td>" << b << "</td></tr>\n<tr><th>seed</th><td>" << summary.value("seed", 0) << "</td></tr>\n</table>\n";
  const auto nodes = summary.value("nodes", nlohmann::json::object());
  if (nodes.is_object() && nodes.contains("referee") && nodes["referee"].is_object() && nodes["referee"].contains("metrics") &&
      nodes["referee"]["metrics"].is_object()) {
    h << "<h2>Referee</h2>\n<table>\n";
    for (const auto& [k, v] : nodes["referee"]["metrics"].items()) h << "<tr><th>" << esc(k) << "</th><td>" << esc(metric_text(v)) << "</td></tr>\n";
    h << "</table>\n";
  }
  for (const auto& f : figs) {
    std::string svg = read_text(work / (f.name + ".svg"));
    const auto start = svg.find("<svg");
    if (start == std::string::npos) continue;
    h << "<figure id=\"" << f.name << "\"><h2>" << esc(f.title) << "</h2>\n" << svg.substr(start) << "\n<figcaption>" << esc(f.caption)
      << "</figcaption></figure>\n";
  }
  for (const auto& n : data.notes) h << "<p class=\"bad\">" << esc(n) << "</p>\n";
  h << "<p>Written by brickyard-report from " << esc(recording.string()) << " (docs/report.md).</p>\n</body></html>\n";
  std::ofstream out(dir / "report.html");
  out << h.str();
  if (!out) throw std::runtime_error((dir / "report.html").string() + ": cannot write");
  std::printf("%s: %zu figures\n", (dir / "report.html").string().c_str(), figs.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: brickyard-report RUN_DIR\n");
    return 2;
  }
  try {
    return run(argv[1]);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "brickyard-report: %s\n", e.what());
    return 2;
  } catch (const nlohmann::json::exception& e) {  // a summary.json of the wrong shape
    std::fprintf(stderr, "brickyard-report: %s/summary.json: %s\n", argv[1], e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "brickyard-report: %s\n", e.what());
    return 1;
  }
}
