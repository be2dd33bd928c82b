// brickyard-plan: the offline half of planning.
//   brickyard-plan line  --track FILE [--margin M] --out FILE [--profile FILE] [--vehicle FILE] [limits] [--min-time on|off] [--curvature-slack S]
//   brickyard-plan graph --track FILE --raceline FILE [--edge-margin M] [--vehicle FILE] [graph options] --out FILE
//   brickyard-plan track --track FILE --out-dir DIR [--vehicle FILE] [--margin M] [--edge-margin M]
// `line` optimises the minimum-curvature racing line, refines it for minimum time under the
// vehicle limits given (the vehicle file's, AV-21 by default, each overridable; --min-time off:
// not), and writes it as x_m,y_m (TUM's format, which
// planning.racing_line and planning.road_graph read); --profile also writes
// s_m,x_m,y_m,kappa_radpm,vx_mps with the ggv + drag speed profile (curvature averaged over 30 m,
// as the driving stack sees the line: lap_profile) and prints the lap time.
// `graph` builds the road graph planning.road_graph would build at start and saves it
// (graph_file=...). `track` is both in one step for any track file and the car: DIR/<track>_line.csv,
// DIR/<track>_profile.csv and DIR/<track>.byrg. Bad input: a message naming the file or option,
// exit 2.
#include "planning/common/line_setup.hpp"
#include "planning/common/min_curvature.hpp"
#include "planning/common/min_time.hpp"
#include "planning/common/road_graph.hpp"
#include "io/whole_file.hpp"
#include "motion/racing_line.hpp"
#include "motion/speed_profile.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/centre_line.hpp"
#include "track/track.hpp"
#include "vehicle/vehicle.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace brickyard;
using namespace brickyard::planning;

namespace {

struct Usage : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* kUsage =
    "usage: brickyard-plan line  --track FILE [--margin M] --out FILE [--profile FILE] [--vehicle FILE]\n"
    "                            [--v-max V --a-lat A --a-accel A --a-decel A --drag K --power P]\n"
    "                            [--min-time on|off] [--curvature-slack S]\n"
    "       brickyard-plan graph --track FILE --raceline FILE --out FILE [--edge-margin M] [--vehicle FILE]\n"
    "                            [--layer-spacing M --layer-spacing-turn M --lateral-step M --half-width M\n"
    "                             --graph-edge-margin M --max-curvature K --max-edge-length M]\n"
    "       brickyard-plan track --track FILE --out-dir DIR [--vehicle FILE] [--margin M] [--edge-margin M]\n";

std::map<std::string, std::string> parse(int argc, char** argv) {
  std::map<std::string, std::string> o;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) != 0 || i + 1 >= argc) throw Usage(a + ": expected --option VALUE");
    o[a.substr(2)] = argv[++i];
  }
  return o;
}

double number(std::map<std::string, std::string>& o, const std::string& k, double def) {
  auto it = o.find(k);
  if (it == o.end()) return def;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || !std::isfinite(v)) throw Usage("--" + k + " " + it->second + ": not a number");
  o.erase(it);
  return v;
}

// A number within what physics or the tool allows (an --a-lat of 0 planned a lap of 40,000 s):
// outside [lo, hi] is refused with the range and its unit.
double number_in(std::map<std::string, std::string>& o, const std::string& k, double def, double lo, double hi, const char* unit) {
  const std::string given = o.count(k) ? o[k] : "";
  const double v = number(o, k, def);
  if (!given.empty() && !(v >= lo && v <= hi)) {
    char range[96];
    std::snprintf(range, sizeof range, "expected %g to %g %s", lo, hi, unit);
    throw Usage("--" + k + " " + given + ": " + range);
  }
  return v;
}

std::string text(std::map<std::string, std::string>& o, const std::string& k) {
  auto it = o.find(k);
  if (it == o.end()) throw Usage("--" + k + " is required");
  std::string v = it->second;
  o.erase(it);
  return v;
}

void no_leftovers(const std::map<std::string, std::string>& o) {
  if (!o.empty()) throw Usage("--" + o.begin()->first + ": unknown option");
}

// The vehicle file: --vehicle, else the AV-21's from the data folder beside the executable
// (<prefix>/share/brickyard/data, in the build tree and once installed).
vehicle::Vehicle car(std::map<std::string, std::string>& o) {
  std::string path;
  if (o.count("vehicle")) {
    path = text(o, "vehicle");
  } else {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    path = (exe.parent_path() / ".." / "share" / "brickyard" / "data" / "vehicles" / "av21.json").string();
  }
  return vehicle::load_vehicle(path);
}

double since_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int line_cmd(std::map<std::string, std::string> o) {
  const std::string track = text(o, "track"), out = text(o, "out");
  const std::string profile = o.count("profile") ? text(o, "profile") : "";
  MinCurvatureParams p;
  p.margin = number(o, "margin", p.margin);
  VehicleLimits l = motion::vehicle_limits(car(o));  // the AV-21 unless told otherwise
  // Bounds far past any race car's, and none that leaves a lap without a speed.
  l.v_max = number_in(o, "v-max", l.v_max, 1, 200, "m/s");
  l.a_lat = number_in(o, "a-lat", l.a_lat, 0.5, 100, "m/s^2");
  l.a_accel = number_in(o, "a-accel", l.a_accel, 0.1, 100, "m/s^2");
  l.a_decel = number_in(o, "a-decel", l.a_decel, 0.1, 100, "m/s^2");
  l.drag = number_in(o, "drag", l.drag, 0, 0.1, "1/m");
  l.power = number_in(o, "power", l.power, 0, 1e5, "W/kg");
  const std::string refine = o.count("min-time") ? text(o, "min-time") : "on";
  if (refine != "on" && refine != "off") throw Usage("--min-time " + refine + ": expected on or off");
  MinTimeParams mp;
  mp.margin = p.margin;
  const std::string slack_text = o.count("curvature-slack") ? o["curvature-slack"] : "";
  mp.curvature_slack = number(o, "curvature-slack", mp.curvature_slack);
  if (!(mp.curvature_slack >= 0)) throw Usage("--curvature-slack " + slack_text + ": must be >= 0");
  no_leftovers(o);
  const track::CenterLine c = track::load_centerline_csv(track);
  for (const auto& note : c.notes) std::fprintf(stderr, "note: %s\n", note.c_str());  // a bridge
  const ClosedLine line{c.x, c.y, c.width_left, c.width_right};
  const auto t0 = std::chrono::steady_clock::now();
  MinCurvatureResult r = min_curvature_line(line, p);
  const double ms = since_ms(t0);
  std::string what = "minimum-curvature racing line";
  char refined[300] = "";
  if (refine == "on") {
    const auto t1 = std::chrono::steady_clock::now();
    MinTimeResult m = min_time_refine(line, r.offset, l, mp);
    std::snprintf(refined, sizeof refined,
                  "min-time refinement: lap time %.3f -> %.3f s (three-point curvature), %.3f -> %.3f s (averaged over %g m), "
                  "sum k^2 ds %.5f -> %.5f 1/m, %d steps, %.0f ms\n",
                  m.start_time, m.time, m.start_averaged_time, m.averaged_time, mp.averaged_over, m.start_energy, m.energy,
                  m.iterations, since_ms(t1));
    r.x = std::move(m.x), r.y = std::move(m.y), r.offset = std::move(m.offset);
    char slack[32];
    std::snprintf(slack, sizeof slack, "%g", mp.curvature_slack);
    what += ", refined for minimum time (curvature slack " + std::string(slack) + ")";
  }
  std::ostringstream f;
  f << "# " << what << " by brickyard-plan from " << track << ", margin " << p.margin << " m\n# x_m,y_m\n";
  char row[128];
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    std::snprintf(row, sizeof row, "%.4f,%.4f\n", r.x[i], r.y[i]);
    f << row;
  }
  io::write_whole_file(out, f.str());
  std::printf("%s: %zu points, sum k^2 ds %.5f 1/m, %d linearisations, %.0f ms\n", out.c_str(), r.x.size(),
              summed_squared_curvature(r.x, r.y), r.iterations, ms);
  std::fputs(refined, stdout);
  if (!profile.empty()) {
    // The curvature averaged as the driving stack does (motion::make_racing_line's 30 m), the window
    // of the refinement's second measure.
    const LapProfile lp = lap_profile(r.x, r.y, l, mp.averaged_over);
    const std::size_t n = r.x.size();
    const std::vector<double>& ds = lp.ds;
    std::ostringstream g;
    g << "# s_m,x_m,y_m,kappa_radpm,vx_mps\n";
    double s = 0;
    for (std::size_t i = 0; i < n; ++i) {
      std::snprintf(row, sizeof row, "%.3f,%.4f,%.4f,%.6f,%.3f\n", s, r.x[i], r.y[i], lp.kappa[i], lp.v[i]);
      g << row;
      s += ds[i];
    }
    io::write_whole_file(profile, g.str());
    std::printf("%s: lap time %.2f s\n", profile.c_str(), lp.time);
  }
  return 0;
}

int graph_cmd(std::map<std::string, std::string> o) {
  const std::string track = text(o, "track"), raceline = text(o, "raceline"), out = text(o, "out");
  const double edge_margin = number(o, "edge-margin", 2.5);  // planning.road_graph's default
  RoadGraphParams p;
  const double half_width = car(o).half_width;  // the vehicle file's, as planning.road_graph's
  p.layer_spacing = number(o, "layer-spacing", p.layer_spacing);
  p.layer_spacing_turn = number(o, "layer-spacing-turn", p.layer_spacing_turn);
  p.lateral_step = number(o, "lateral-step", p.lateral_step);
  p.half_width = number(o, "half-width", half_width);
  p.edge_margin = number(o, "graph-edge-margin", p.edge_margin);
  p.max_curvature = number(o, "max-curvature", p.max_curvature);
  p.max_edge_length = number(o, "max-edge-length", p.max_edge_length);
  no_leftovers(o);
  track::TrackGeometry w;
  w.line = track::load_centerline_csv(track);
  const track::Track t(w);
  const track::CenterLine raw = track::load_xy_csv(raceline);
  if (const std::string where = motion::leaves_track(raw, t); !where.empty())
    throw std::runtime_error(raceline + ": the line leaves the track (" + track + "): " + where);
  const VehicleLimits d;  // the line's speeds play no part in the graph: the planners' defaults
  const Reference ref = make_reference(raw, &t, edge_margin, motion::independent_limits(d.v_max, d.a_lat, d.a_accel, d.a_decel));
  const auto t0 = std::chrono::steady_clock::now();
  const RoadGraph g = RoadGraph::build(ref.line, track_room(t, ref.line), p, reference_digest(raw, edge_margin, p));
  const double ms = since_ms(t0);
  g.save(out);
  std::printf("%s: %zu layers, %zu nodes, %zu edges, built in %.0f ms\n", out.c_str(), g.layers().size(), g.node_count(),
              g.edge_count(), ms);
  return 0;
}

// Line, profile and road graph of one track in one folder, for the car of --vehicle.
int track_cmd(std::map<std::string, std::string> o) {
  const std::string track = text(o, "track"), dir = text(o, "out-dir");
  const std::string base = (std::filesystem::path(dir) / std::filesystem::path(track).stem()).string();
  std::map<std::string, std::string> line{{"track", track}, {"out", base + "_line.csv"}, {"profile", base + "_profile.csv"}};
  std::map<std::string, std::string> graph{{"track", track}, {"raceline", base + "_line.csv"}, {"out", base + ".byrg"}};
  if (o.count("vehicle")) line["vehicle"] = graph["vehicle"] = text(o, "vehicle");
  if (o.count("margin")) line["margin"] = text(o, "margin");
  if (o.count("edge-margin")) graph["edge-margin"] = text(o, "edge-margin");
  no_leftovers(o);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the folder: " + ec.message());
  const int rc = line_cmd(line);
  return rc != 0 ? rc : graph_cmd(graph);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  try {
    if (cmd == "line") return line_cmd(parse(argc, argv));
    if (cmd == "graph") return graph_cmd(parse(argc, argv));
    if (cmd == "track") return track_cmd(parse(argc, argv));
    if (cmd == "--help" || cmd == "-h") { std::fputs(kUsage, stdout); return 0; }
    throw Usage(cmd.empty() ? "no command" : cmd + ": unknown command (line, graph, track)");
  } catch (const Usage& e) {
    std::fprintf(stderr, "brickyard-plan: %s\n%s", e.what(), kUsage);
  } catch (const io::WriteError& e) {
    std::fprintf(stderr, "brickyard-plan: %s\n", e.what());
    return 1;  // not bad input: the output could not be written (a full disk)
  } catch (const std::exception& e) {
    std::fprintf(stderr, "brickyard-plan: %s\n", e.what());
  }
  return 2;
}
