// brickyard — the host executive.
#include "cli/bag_play.hpp"
#include "cli/commands.hpp"
#include "cli/supervisor.hpp"
#include "cli/topic_command.hpp"
#include "exec/crash_guard.hpp"
#include "exec/executive.hpp"
#include "exec/node_checks.hpp"
#include "graph/diagnostics.hpp"
#include "io/whole_file.hpp"
#include "record/recording_info.hpp"
#include "security/security_files.hpp"

#include "map_build_graph.hpp"

#include <brickyard/version.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>

extern char** environ;

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <fstream>
#include <set>
#include <iostream>

using namespace brickyard::fw;
namespace fs = std::filesystem;

namespace {
// The recording `--out DIR` writes (everything but point clouds), which the report reads.
constexpr const char* kOutRecording = "recording.mcap";

const char* kUsage = R"(brickyard — plugin-based autonomy framework

usage:
  brickyard run GRAPH.json [options]       run a graph
  brickyard validate GRAPH.json [options]  check everything, start nothing
  brickyard plugins [NAME] [--json]        list the plugins found and their manifests (NAME: that one only)
  brickyard graph GRAPH.json --dot         print the graph for Graphviz
  brickyard report RUN_DIR                 write RUN_DIR/report.html from a run's recording
  brickyard bag info RECORDING [--json]    a recording's clock, span and topics (types, counts, rates,
                                           bytes)
  brickyard bag play RECORDING             republish its topics over DDS at the recorded times
                                           (--rate X, --only NODE.PORT,..., --domain N)
  brickyard map build RECORDING --out DIR  a track file and a point map from a recorded drive:
                                           DIR/track.csv, DIR/map.pcd, DIR/summary.json
                                           (configs/map_build.json; docs/mapping.md)
  brickyard topic list [--domain N]        the wires of graphs running on domain N, over DDS (listens
                                           --duration S, 2 s by default)
  brickyard topic echo NODE.PORT           its samples as JSON lines (--count N, --duration S)
  brickyard topic hz NODE.PORT             its rate, a line a second (--count N, --duration S)
  brickyard security init GRAPH --out DIR  DDS security for the graph: a CA, an identity per process
                                           and one to observe, signed governance and permissions from
                                           its wires (--protect sign|encrypt, --days N; docs/security.md)
                                           topic and bag play take --security DIR (bag play --identity P)
  brickyard new-plugin NAME --dir DIR      scaffold a plugin project from the SDK template
  brickyard --version

options:
  --duration S         stop after S seconds (sim or real clock); overrides clock.duration_s
  --set NODE.PARAM=V   override a parameter (V is JSON, or else a string); repeatable
  --arg NAME=V         give one of the graph's named arguments ("args", used as ${NAME}) a value;
                       repeatable
  --seed N             seed of every random source (default 0)
  --process NAME       run only the nodes of process NAME; other processes meet over DDS.
                       Without it, a real-clock graph whose nodes name several processes is
                       supervised: each process a child, watched, restarted by the graph's
                       "processes" policies (docs/reliability.md)
  --one-process        run every node of such a graph in this one process instead
  --domain N           DDS domain id; overrides transport.domain
  --plugin-path DIR    search DIR for plugin libraries first (its plugins override those of
                       the same name found later); repeatable
  --quiet              only warnings and errors
  --progress S         a progress line every S seconds (default: 0.25 on a terminal, one
                       updating line; 5 otherwise, plain lines); 0: none
  --out DIR            write DIR/summary.json, and (unless --no-report) record the run's wires
                       but its point clouds into DIR/recording.mcap and write DIR/report.html
  --no-report          with --out: the summary alone (also the case with --process)
  --record FILE        record every wire's samples into FILE: MCAP, or SQLite when FILE ends in
                       .db3 (docs/recording.md)
  --record-compression zstd|lz4|none   the MCAP chunks' (default zstd)
  --record-only P,...  record only the topics NODE.PORT matching these patterns ('*' any)
  --record-cloud-precision M   record point clouds compact, each coordinate to M metres
                       (0 < M <= 0.1; about 4x smaller; docs/recording.md)
  --live PORT          serve the run to Foxglove (WebSocket, foxglove.websocket.v1) on
                       127.0.0.1:PORT: every wire as a channel (docs/live.md)
  --live-address A     bind the live server to address A instead (opt-in: 0.0.0.0 is every
                       interface)
  --live-cloud-hz X    send each point-cloud channel at most X clouds a second of wall time
                       (default 20, a display's rate; 0: every cloud)
  --pace X             sim clock: run at most X times real time, so a person can watch
  --threads N          sim clock: step nodes that cannot see each other on N threads (default:
                       the machine's cores, at most 4); the run is the same on any number
  --profile            time each node's steps on the wall clock: a table at the end, sorted by
                       time, and "step_wall_s" per node in the summary (docs/performance.md)

exit codes: 0 success, 1 the run failed, 2 invalid input
)";

struct Args {
  std::string command, target, dir, out, process, record, record_compression = "zstd";
  std::vector<std::string> more;  // positional arguments after the target (map build RECORDING)
  std::vector<std::string> record_only;
  std::vector<std::string> sets, args, plugin_paths;
  std::optional<double> duration;
  std::optional<int> domain;
  double progress = -1, pace = 0;
  std::optional<int> live_port;
  std::optional<long> count;
  double rate = 1.0;
  std::vector<std::string> only;
  std::string live_address = "127.0.0.1";
  bool live_address_set = false;
  std::optional<double> live_cloud_hz;  // --live-cloud-hz
  double record_cloud_precision = 0;    // --record-cloud-precision (0: clouds exact)
  int threads = 0;
  std::uint64_t seed = 0;
  bool json = false, dot = false, quiet = false, no_report = false, profile = false, one_process = false;
  std::vector<std::string> child_flags;  // what a supervised run's children are given as they are
  std::string security, identity, protect = "sign";  // security init; topic and bag play against a secured graph
  int days = 365;
};

[[noreturn]] void usage_error(const std::string& where, const std::string& msg) {
  throw InvalidInput(where, msg);
}

double parse_number(const std::string& flag, const std::string& v) {
  try {
    std::size_t n = 0;
    double d = std::stod(v, &n);
    if (n == v.size()) return d;
  } catch (...) {
  }
  usage_error(flag + " " + v, "expected a number");
}

// NODE.PORT patterns, comma-separated (--record-only, --only).
std::vector<std::string> patterns(const std::string& flag, const std::string& list) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at <= list.size();) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    if (comma > at) out.push_back(list.substr(at, comma - at));
    at = comma + 1;
  }
  if (out.empty()) usage_error(flag, "expected NODE.PORT patterns, comma-separated");
  return out;
}

Args parse_args(int argc, char** argv) {
  Args a;
  std::vector<std::string> v(argv + 1, argv + argc);
  if (v.empty()) usage_error("brickyard", "no command given (try --help)");
  a.command = v[0];
  for (std::size_t i = 1; i < v.size(); ++i) {
    const std::string& f = v[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= v.size()) usage_error(f, "needs a value");
      return v[++i];
    };
    // Flags every process of a supervised run is given as they are.
    static const std::set<std::string> kForwarded = {"--set", "--arg", "--seed", "--plugin-path", "--threads", "--progress", "--pace"};
    if (kForwarded.count(f) && i + 1 < v.size()) a.child_flags.insert(a.child_flags.end(), {f, v[i + 1]});
    if (f == "--quiet" || f == "-q" || f == "--profile" || f == "--no-report") a.child_flags.push_back(f);
    if (f == "--duration") {
      double d = parse_number(f, value());
      if (!(d > 0 && d <= kMaxDuration_s)) usage_error("--duration", "expected a positive number of seconds, at most 1e7");
      a.duration = d;
    } else if (f == "--set") a.sets.push_back(value());
    else if (f == "--arg") a.args.push_back(value());
    else if (f == "--seed") {
      std::string s = value();
      // Up to 19 digits: every such number fits the 64-bit seed (stoull would throw on more).
      if (s.empty() || s.size() > 19 || s.find_first_not_of("0123456789") != std::string::npos)
        usage_error("--seed " + (s.size() > 40 ? s.substr(0, 40) + "…" : s), "expected a non-negative integer of at most 19 digits");
      a.seed = std::stoull(s);
    } else if (f == "--out") a.out = value();
    else if (f == "--process") a.process = value();
    else if (f == "--domain") {
      double d = parse_number(f, value());
      if (d < 0 || d > 232 || d != static_cast<int>(d)) usage_error("--domain", "expected an integer from 0 to 232");
      a.domain = static_cast<int>(d);
    } else if (f == "--plugin-path") a.plugin_paths.push_back(value());
    else if (f == "--dir") a.dir = value();
    else if (f == "--record") a.record = value();
    else if (f == "--record-compression") {
      a.record_compression = value();
      if (a.record_compression != "zstd" && a.record_compression != "lz4" && a.record_compression != "none")
        usage_error("--record-compression " + a.record_compression, "expected zstd, lz4 or none");
    }
    else if (f == "--live") {
      const std::string v = value();
      if (v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos || std::stoi(v) > 65535)
        usage_error("--live " + v, "expected a port from 0 to 65535 (0: any free one)");
      a.live_port = std::stoi(v);
    } else if (f == "--live-address") a.live_address = value(), a.live_address_set = true;
    else if (f == "--record-cloud-precision") {
      a.record_cloud_precision = parse_number(f, value());
      if (!(a.record_cloud_precision > 0 && a.record_cloud_precision <= 0.1))
        usage_error("--record-cloud-precision", "expected metres, more than 0 and at most 0.1");
    }
    else if (f == "--live-cloud-hz") {
      a.live_cloud_hz = parse_number(f, value());
      if (!(*a.live_cloud_hz >= 0) || *a.live_cloud_hz > 1000)
        usage_error("--live-cloud-hz", "expected clouds a second from 0 (every one) to 1000");
    }
    else if (f == "--pace") {
      a.pace = parse_number(f, value());
      if (!(a.pace > 0)) usage_error("--pace", "expected a factor of real time, more than 0");
    }
    else if (f == "--no-report") a.no_report = true;
    else if (f == "--one-process") a.one_process = true;
    else if (f == "--profile") a.profile = true;
    else if (f == "--threads") {
      const std::string s = value();
      if (s.empty() || s.size() > 3 || s.find_first_not_of("0123456789") != std::string::npos || std::stoi(s) < 1 || std::stoi(s) > 64)
        usage_error("--threads " + s, "expected an integer from 1 to 64");
      a.threads = std::stoi(s);
    }
    else if (f == "--progress") {
      a.progress = parse_number(f, value());
      if (!(a.progress >= 0)) usage_error("--progress", "expected seconds, 0 or more");
    }
    else if (f == "--record-only") a.record_only = patterns(f, value());
    else if (f == "--rate") {
      a.rate = parse_number(f, value());
      if (!(a.rate > 0)) usage_error("--rate", "expected a factor of the recorded speed, more than 0");
    } else if (f == "--only") a.only = patterns(f, value());
    else if (f == "--count") {
      const std::string v = value();
      if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos || std::stol(v) < 1)
        usage_error("--count " + v, "expected a whole number of samples, 1 or more");
      a.count = std::stol(v);
    }
    else if (f == "--security") a.security = value();
    else if (f == "--identity") a.identity = value();
    else if (f == "--protect") {
      a.protect = value();
      if (a.protect != "sign" && a.protect != "encrypt") usage_error("--protect " + a.protect, "expected sign or encrypt");
    } else if (f == "--days") {
      const std::string v = value();
      if (v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos || std::stoi(v) < 1 || std::stoi(v) > 3650)
        usage_error("--days " + v, "expected a whole number of days from 1 to 3650");
      a.days = std::stoi(v);
    }
    else if (f == "--json") a.json = true;
    else if (f == "--dot") a.dot = true;
    else if (f == "--quiet" || f == "-q") a.quiet = true;
    else if (f.rfind("--", 0) == 0) usage_error(f, "unknown option (see brickyard --help)");
    else if (a.target.empty()) a.target = f;
    else if (a.command == "map" || a.command == "bag" || a.command == "topic" || a.command == "security") a.more.push_back(f);
    else usage_error(f, "unexpected argument");
  }
  return a;
}

// The plugins of every folder in search order (--plugin-path first); an earlier folder's plugin
// overrides a later one of the same name, and says so on stderr (not with --quiet).
Registry load_registry(const Args& a, const GraphDecl* g) {
  Registry reg;
  for (const auto& d : plugin_search_dirs(a.plugin_paths, g ? g->plugin_path : std::vector<std::string>{})) reg.add_directory(d);
  if (!a.quiet)
    for (const auto& n : reg.notices()) std::fprintf(stderr, "notice: %s\n", n.c_str());
  return reg;
}

void on_signal(int) {
  g_interrupt = true;
  crash_guard::interrupted();  // the run has 2 s from here; a second signal ends it at once
}

// brickyard-report, installed beside this executable, on a run folder; its exit code. Started
// with an argument vector, no shell: a folder's name is never parsed.
int run_report(const std::string& dir, bool quiet) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const std::string tool = (self.parent_path() / "brickyard-report").string();
  if (ec || !fs::exists(tool)) {
    std::fprintf(stderr, "[brickyard] brickyard-report not found beside %s\n", self.string().c_str());
    return 2;
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (quiet) posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  std::vector<char*> argv = {const_cast<char*>(tool.c_str()), const_cast<char*>(dir.c_str()), nullptr};
  pid_t pid = 0;
  const int err = posix_spawn(&pid, tool.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (err != 0) return 2;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

// The end of a run at a glance: one row per node with its metrics (arrays cut at four values).
std::string summary_table(const nlohmann::json& j) {
  if (!j.contains("nodes") || j["nodes"].empty()) return "";
  std::size_t wn = 4, wp = 6;
  for (const auto& [name, n] : j["nodes"].items()) {
    wn = std::max(wn, name.size());
    wp = std::max(wp, n.value("plugin", std::string()).size());
  }
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return std::string(b);
  };
  auto value = [&](const nlohmann::json& v) -> std::string {
    if (v.is_number()) return num(v.get<double>());
    if (v.is_string()) return v.get<std::string>();
    if (v.is_array()) {
      std::string out = "[";
      for (std::size_t i = 0; i < v.size() && i < 4; ++i) out += (i ? " " : "") + (v[i].is_number() ? num(v[i].get<double>()) : v[i].dump());
      return out + (v.size() > 4 ? " … (" + std::to_string(v.size()) + ")]" : "]");
    }
    return v.dump();
  };
  std::string out;
  char row[256];
  std::snprintf(row, sizeof row, "%-*s  %-*s  %8s  %s\n", static_cast<int>(wn), "node", static_cast<int>(wp), "plugin", "steps", "metrics");
  out += row;
  for (const auto& [name, n] : j["nodes"].items()) {
    std::string m;
    if (n.contains("metrics"))
      for (const auto& [k, v] : n["metrics"].items()) m += (m.empty() ? "" : " · ") + k + " " + value(v);
    std::snprintf(row, sizeof row, "%-*s  %-*s  %8llu  ", static_cast<int>(wn), name.c_str(), static_cast<int>(wp),
                  n.value("plugin", std::string()).c_str(), static_cast<unsigned long long>(n.value("steps", 0ull)));
    out += row + (m.empty() ? "—" : m) + "\n";
  }
  return out;
}

// --profile: where the run's wall time went, node by node, most first.
std::string profile_table(const nlohmann::json& j) {
  std::vector<std::pair<double, std::string>> rows;
  std::size_t wn = 4;
  double total = 0;
  for (const auto& [name, n] : j["nodes"].items()) {
    const double s = n.value("step_wall_s", 0.0);
    rows.emplace_back(s, name);
    wn = std::max(wn, name.size());
    total += s;
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  const double wall = j.value("wall_time_s", 0.0);
  std::string out;
  char row[256];
  std::snprintf(row, sizeof row, "%-*s  %10s  %10s  %8s\n", static_cast<int>(wn), "node", "step ms", "us/step", "of wall");
  out += row;
  for (const auto& [s, name] : rows) {
    const auto steps = j["nodes"][name].value("steps", 0ull);
    std::snprintf(row, sizeof row, "%-*s  %10.1f  %10.1f  %7.1f%%\n", static_cast<int>(wn), name.c_str(), s * 1e3,
                  steps ? s * 1e6 / static_cast<double>(steps) : 0.0, wall > 0 ? 100 * s / wall : 0.0);
    out += row;
  }
  std::snprintf(row, sizeof row, "%-*s  %10.1f  %10s  %7.1f%%  (the rest: the host, the transport, start and end)\n", static_cast<int>(wn),
                "all nodes", total * 1e3, "", wall > 0 ? 100 * total / wall : 0.0);
  return out + row;
}

int run_graph(const Args& a, GraphDecl g, bool validate_only);

// A run replaces what an earlier run wrote into its --out folder, and nothing else: a
// summary.json that is not a run's (it names its result, and its graph or its writer) or a
// report.html that is not brickyard-report's is the user's, and the run refuses.
void refuse_foreign_files(const std::string& out) {
  const fs::path dir(out);
  std::error_code ec;
  if (fs::exists(dir / "summary.json", ec)) {
    bool ours = false;
    std::ifstream old(dir / "summary.json");
    try {
      const auto j = nlohmann::json::parse(old);
      ours = j.is_object() && j.contains("result") && (j.contains("graph") || j.contains("summary"));
    } catch (...) {
    }
    if (!ours) usage_error("--out " + out, (dir / "summary.json").string() + " was not written by brickyard: move it or use another folder");
  }
  if (fs::exists(dir / "report.html", ec)) {
    std::ifstream old(dir / "report.html");
    std::string head(300, '\0');
    old.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (head.find("<title>Brickyard run: ") == std::string::npos)
      usage_error("--out " + out, (dir / "report.html").string() + " was not written by brickyard-report: move it or use another folder");
  }
}

int cmd_run(const Args& a, bool validate_only) {
  if (a.target.empty()) usage_error(a.command, "needs a graph file");
  return run_graph(a, load_graph_file(a.target, a.sets, a.args), validate_only);
}

// `brickyard map build RECORDING --out DIR`: configs/map_build.json (built in) on the recording.
// What is wrong with the file is said before anything runs (exit 2); a drive from which no
// track could be made is bad input too (the recording is the input), and leaves no track file.
int cmd_map(const Args& a) {
  if (a.target != "build")
    usage_error(a.target.empty() ? "map" : "map " + a.target, a.target.empty() ? "needs a command (brickyard map build RECORDING --out DIR)"
                                                                             : "unknown map command (brickyard map build RECORDING --out DIR)");
  if (a.more.size() != 1) usage_error("map build", "needs one recording (brickyard run GRAPH --record FILE)");
  if (a.out.empty()) usage_error("map build", "needs --out DIR (for DIR/track.csv, DIR/map.pcd, DIR/summary.json)");
  const std::string rec = a.more[0];
  RecordingInfo info;
  try {
    info = read_recording_info(rec);
  } catch (const std::exception& e) {
    usage_error(rec, e.what());
  }
  if (!info.damage.empty()) usage_error(rec, info.damage);
  if (info.messages == 0) usage_error(rec, "the recording holds no samples");
  if (info.clock != "sim" && info.clock != "real")
    usage_error(rec, "recorded on the " + (info.clock.empty() ? std::string("unknown") : info.clock) + " clock: neither sim nor real");
  // A real drive's recording (Unix times) is re-timed onto the sim clock from its first sample.
  std::int64_t first_ns = 0;
  if (info.clock == "real") {
    bool any = false;
    for (const auto& t : read_topic_stats(rec))
      if (t.count) first_ns = any ? std::min(first_ns, t.first_ns) : t.first_ns, any = true;
  }
  for (const auto& arg : a.args)
    for (const char* ours : {"recording=", "map_file=", "track_file=", "duration=", "retime_from_ns="})
      if (arg.rfind(ours, 0) == 0) usage_error("--arg " + arg, "map build sets this one itself");
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec) usage_error("--out " + a.out, "cannot create the folder: " + ec.message());
  const fs::path dir = fs::absolute(a.out), track = dir / "track.csv", map = dir / "map.pcd";
  for (const char* own : {"recording.mcap", "recording.db3"})
    if (fs::equivalent(rec, dir / own, ec))
      usage_error("--out " + a.out, std::string("holds the recording as ") + own + ", which a run into the folder replaces: use another folder");
  // An earlier build's files must not stand for this one's.
  fs::remove(track, ec);
  fs::remove(map, ec);
  std::vector<std::string> args = a.args;
  args.push_back("recording=" + fs::absolute(rec).string());
  args.push_back("map_file=" + map.string());
  args.push_back("track_file=" + track.string());
  char duration[64];
  std::snprintf(duration, sizeof duration, "duration=%.3f", static_cast<double>(info.last_ns - first_ns) * 1e-9 + 0.1);
  args.push_back(duration);
  if (info.clock == "real") args.push_back("retime_from_ns=" + std::to_string(first_ns));
  Args run = a;
  run.no_report = true;  // DIR gets the summary; the recording is the input, not recorded again
  const int rc = run_graph(run, parse_graph_text(kMapBuildGraph, "configs/map_build.json (built into brickyard)", a.sets, args), false);
  if (rc != 1) {
    if (rc == 0) std::printf("map build: %s and %s from %s\n", track.c_str(), map.c_str(), rec.c_str());
    return rc;
  }
  // The mapper could make no track (no lap in the drive, no edge found; its metric track_error
  // says why): the recording's fault.
  std::ifstream f(dir / "summary.json");
  std::string why;
  try {
    why = nlohmann::json::parse(f).at("nodes").at("mapper").at("metrics").value("track_error", "");
  } catch (...) {
  }
  if (!why.empty()) {
    std::fprintf(stderr, "error: %s: no track from this drive: %s\n", rec.c_str(), why.c_str());
    return 2;
  }
  return rc;
}

// `brickyard security init GRAPH --out DIR`: a CA, an identity per process and one to observe,
// the signed governance and each identity's signed permissions from the graph's wires.
int cmd_security(const Args& a) {
  if (a.target != "init")
    usage_error(a.target.empty() ? "security" : "security " + a.target, "expected: brickyard security init GRAPH --out DIR [--protect sign|encrypt] [--days N]");
  if (a.more.size() != 1) usage_error("security init", "needs one graph file");
  if (a.out.empty()) usage_error("security init", "needs --out DIR (the folder the graph's transport.security names)");
  const GraphDecl g = load_graph_file(a.more[0], a.sets, a.args);
  Registry reg = load_registry(a, &g);
  const ResolvedGraph rg = resolve_graph(g, reg);
  security::InitOptions o;
  o.protection = a.protect == "encrypt" ? security::Protection::encrypt : security::Protection::sign;
  o.days = a.days;
  const auto r = security::init(rg, a.out, o);
  std::printf("security init: %s for %s (%s, valid %d days)%s\n", a.out.c_str(), a.more[0].c_str(),
              o.protection == security::Protection::encrypt ? "traffic encrypted" : "traffic signed", o.days,
              r.reused_ca ? ", the folder's CA kept" : ", a new CA");
  for (const auto& id : r.identities)
    std::printf("  identity %-20s %s\n", id.c_str(), id == security::kObserver ? "reads every topic, writes none (brickyard topic --security DIR)" : "");
  std::printf("the graph uses it with \"transport\": {\"security\": \"%s\"} (relative to the graph's folder); "
              "ca_key.pem signs: keep it off the car\n", a.out.c_str());
  return 0;
}

// `brickyard bag info RECORDING`: what a recording holds, without decoding a sample.
int cmd_bag(const Args& a) {
  if (a.target == "play") {
    if (a.more.size() != 1) usage_error("bag play", "needs one recording (brickyard bag play RECORDING)");
    BagPlayOptions o;
    o.file = a.more[0];
    o.domain = a.domain.value_or(0);
    o.rate = a.rate;
    o.only = a.only;
    o.security = a.security;
    o.identity = a.identity;
    return bag_play(o);
  }
  if (a.target != "info")
    usage_error(a.target.empty() ? "bag" : "bag " + a.target, a.target.empty() ? "needs a command (brickyard bag info | play RECORDING)"
                                                                             : "unknown bag command (brickyard bag info | play RECORDING)");
  if (a.more.size() != 1) usage_error("bag info", "needs one recording (brickyard run GRAPH --record FILE)");
  const std::string& file = a.more[0];
  RecordingInfo info;
  std::vector<TopicStats> topics;
  try {
    if (is_mcap_file(file)) {
      read_mcap_recording(file, info, topics);
    } else {
      info = read_recording_info(file);
      topics = read_topic_stats(file);
    }
  } catch (const std::exception& e) {
    usage_error(file, e.what());
  }
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  std::int64_t first = 0;
  bool any = false;
  for (const auto& t : topics)
    if (t.count) first = any ? std::min(first, t.first_ns) : t.first_ns, any = true;
  auto rate = [](const TopicStats& t) {
    return t.count > 1 && t.last_ns > t.first_ns ? static_cast<double>(t.count - 1) / (static_cast<double>(t.last_ns - t.first_ns) * 1e-9) : 0.0;
  };
  if (a.json) {
    nlohmann::json j = {{"file", file}, {"bytes", ec ? 0 : size}, {"clock", info.clock}, {"messages", info.messages},
                        {"start_s", static_cast<double>(first) * 1e-9}, {"end_s", static_cast<double>(info.last_ns) * 1e-9}};
    j["topics"] = nlohmann::json::array();
    for (const auto& t : topics)
      j["topics"].push_back({{"name", t.name}, {"type", t.type}, {"count", t.count}, {"bytes", t.bytes},
                             {"first_s", static_cast<double>(t.first_ns) * 1e-9}, {"last_s", static_cast<double>(t.last_ns) * 1e-9},
                             {"rate_hz", rate(t)}});
    if (!info.damage.empty()) j["damage"] = info.damage;
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("file      %s (%.1f MB)\nclock     %s\nspan      %.3f s to %.3f s (%.3f s)\nmessages  %llu\n", file.c_str(),
                ec ? 0.0 : static_cast<double>(size) / 1e6, info.clock.c_str(), static_cast<double>(first) * 1e-9,
                static_cast<double>(info.last_ns) * 1e-9, static_cast<double>(info.last_ns - first) * 1e-9,
                static_cast<unsigned long long>(info.messages));
    std::size_t wn = 5, wt = 4;
    for (const auto& t : topics) wn = std::max(wn, t.name.size()), wt = std::max(wt, t.type.size());
    std::printf("\n%-*s  %-*s  %10s  %9s  %12s\n", static_cast<int>(wn), "topic", static_cast<int>(wt), "type", "count", "rate Hz", "MB");
    for (const auto& t : topics)
      std::printf("%-*s  %-*s  %10llu  %9.2f  %12.3f\n", static_cast<int>(wn), t.name.c_str(), static_cast<int>(wt), t.type.c_str(),
                  static_cast<unsigned long long>(t.count), rate(t), static_cast<double>(t.bytes) / 1e6);
  }
  // A damaged file is read up to the damage (above), then refused: what it lacks is unknown.
  if (!info.damage.empty()) {
    std::fprintf(stderr, "error: %s: %s (what is above was read before it)\n", file.c_str(), info.damage.c_str());
    return 2;
  }
  return 0;
}

int run_graph(const Args& a, GraphDecl g, bool validate_only) {
  Registry reg = load_registry(a, &g);
  ResolvedGraph rg = resolve_graph(g, reg, a.process, run_node_checks);
  if (!a.quiet)
    for (const auto& n : rg.notices) std::fprintf(stderr, "notice: %s\n", n.c_str());
  // What each plugin's configure would refuse, every node's together, before anything starts.
  if (auto failed = run_node_checks(rg); !failed.empty()) throw InvalidInput(std::move(failed));
  // DDS security: the identity this process runs as, its files checked before anything starts.
  // Several processes in one participant would need one identity that writes for all of them,
  // which would let a stolen key forge any topic: refused.
  DdsSecurity security;
  if (!g.transport.security.empty()) {
    const bool many_here = a.process.empty() && rg.processes.size() > 1;
    if (g.clock.sim && rg.processes.size() > 1 && !a.one_process && !validate_only)
      usage_error(g.where("/transport/security"), "a split run on the sim clock (its processes in lockstep) does not run secured yet: its clock topics have no permissions; use the real clock");
    if (many_here && !validate_only && a.one_process) {
      std::string names;
      for (const auto& p : rg.processes) names += (names.empty() ? "" : ", ") + p;
      usage_error(g.where("/transport/security"), "a run of processes " + names +
                                                      " in one participant: each identity may write only its own process's topics; run each process (--process NAME, or supervised on the real clock)");
    }
    security = security::check_run(g, many_here ? std::string() : a.process.empty() ? *rg.processes.begin() : a.process, rg.processes);
  }
  if (validate_only) {
    std::size_t wires = g.wires.size();
    std::cout << a.target << ": valid — " << rg.nodes.size() << " nodes, " << wires << " wires, "
              << rg.processes.size() << " process(es), " << (g.clock.sim ? "sim" : "real") << " clock\n";
    return 0;
  }
  if (!a.out.empty()) {
    std::error_code ec;
    fs::create_directories(a.out, ec);
    if (ec) usage_error("--out " + a.out, "cannot create the folder: " + ec.message());
  }
  if (!a.out.empty()) refuse_foreign_files(a.out);
  if (a.one_process && !a.process.empty()) usage_error("--one-process", "cannot go with --process");
  if (a.record_cloud_precision > 0 && a.record.empty())
    usage_error("--record-cloud-precision", "needs --record FILE (the --out folder's recording leaves the clouds out)");
  if (a.process.empty() && !a.one_process && rg.processes.size() > 1) {
    // A split graph: each process a child of this one (cli/supervisor.hpp); on the sim clock they
    // step in lockstep (exec/lockstep.hpp).
    if (!a.record.empty()) usage_error("--record", "a supervised run records each process into --out DIR/PROCESS/recording.mcap; use --out (or --process, or --one-process)");
    if (a.live_port || g.live.port) usage_error("--live", "a supervised run serves nothing live itself; use --process NAME --live PORT for the process to watch (or --one-process)");
    if (a.pace > 0 && !g.clock.sim) usage_error("--pace", "the graph runs on the real clock, which needs no pacing");
    SuperviseOptions so;
    so.graph_file = a.target;
    so.child_flags = a.child_flags;
    so.duration_s = a.duration ? a.duration : g.clock.duration_s;
    so.domain = a.domain.value_or(g.transport.domain);
    so.out = a.out;
    so.quiet = a.quiet;
    return supervise(g, so);
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RunOptions opt;
  opt.duration_s = a.duration;
  opt.seed = a.seed;
  opt.process = a.process;
  opt.domain = a.domain;
  opt.quiet = a.quiet;
  opt.record = a.record;
  opt.progress_s = a.progress;
  opt.record_only = a.record_only;
  opt.record_compression = a.record_compression;
  opt.record_cloud_precision = a.record_cloud_precision;
  opt.profile = a.profile;
  opt.threads = a.threads;
  opt.security = security;
  opt.live_port = a.live_port ? a.live_port : g.live.port;  // the flag, else the graph's "live"
  opt.live_address = a.live_address_set ? a.live_address : g.live.address;
  opt.live_cloud_hz = a.live_cloud_hz ? *a.live_cloud_hz : g.live.cloud_hz.value_or(20.0);
  opt.pace = a.pace;
  if (a.pace > 0 && !g.clock.sim) usage_error("--pace", "the graph runs on the real clock, which needs no pacing");
  if (!a.record_only.empty() && a.record.empty()) usage_error("--record-only", "needs --record FILE");
  // --out keeps the run: its summary, a recording of everything but the point clouds (those
  // are large; --record takes them) and the report drawn from it. The folder's own recording
  // is the run's output, replaced by the next run into it (a --record FILE never is).
  // One process of a multi-process graph records its own wires into its folder (a supervisor
  // gives each its own), and draws no report: the report needs the whole run.
  const bool record_out = !a.out.empty() && !a.no_report;
  const bool report = record_out && a.process.empty();
  if (!a.out.empty()) {
    // What an earlier run left in the folder goes — its report, and its recording when the
    // folder's own (its summary says so) — so nothing stale is drawn; a recording made there
    // with --record is never removed: the run refuses instead.
    const fs::path dir(a.out);
    std::error_code ec;
    std::string ours_name;  // the recording the folder's last run wrote (its summary says)
    {
      std::ifstream old(dir / "summary.json");
      try {
        const auto j = nlohmann::json::parse(old);
        if (j.contains("recording") && j["recording"].is_object()) ours_name = j["recording"].value("file", "");
      } catch (...) {
      }
    }
    for (const char* name : {kOutRecording, "recording.db3"}) {  // (.db3: what --out wrote before MCAP)
      const fs::path rec = dir / name;
      if (!fs::exists(rec, ec)) continue;
      if (ours_name != name) usage_error("--out " + a.out, rec.string() + " was not written by --out (a --record file?): move it or use another folder");
      if (!a.record.empty() && fs::equivalent(a.record, rec, ec)) usage_error("--record " + a.record, "is the --out folder's own recording");
      fs::remove(rec, ec);
    }
    fs::remove(dir / "report.html", ec);
    fs::remove(dir / "summary.json", ec);
    // An earlier run here that was killed left its recording unclosed, under its temporary name.
    for (const char* end : {"", "-wal", "-shm"}) fs::remove(dir / (std::string(kOutRecording) + ".part" + end), ec);
  }
  if (record_out && a.record.empty()) {
    opt.record = (fs::path(a.out) / kOutRecording).string();
    opt.record_skip_types = {"brickyard::msgs::PointCloud", "brickyard::msgs::ClusterList"};
  }
  RunSummary s;
  crash_guard::install(a.out.empty() ? std::string() : (fs::path(a.out) / "summary.json").string());
  struct Disarm {  // however this scope is left: the run is over, exit() and a slow teardown are not a crash
    ~Disarm() { crash_guard::run_ended(); }
  } disarm;
  {
    Executive ex(rg, opt);
    s = ex.run();
    crash_guard::run_ended();
  }
  if (!a.quiet) std::fputs(summary_table(s.json).c_str(), stderr);
  if (a.profile) std::fputs(profile_table(s.json).c_str(), stderr);
  std::fprintf(stderr, "[brickyard] %s: %s (sim %.3f s, wall %.3f s)\n", to_string(s.result), s.reason.c_str(),
               s.sim_time_s, s.wall_time_s);
  // The folder's own recording is named relative to the folder: the summary of two identical
  // runs into two folders is the same.
  if (record_out && a.record.empty() && s.json.contains("recording")) s.json["recording"]["file"] = kOutRecording;
  if (!a.out.empty()) {
    // Whole or not at all: a full disk leaves no half a summary.
    try {
      brickyard::io::write_whole_file((fs::path(a.out) / "summary.json").string(), s.json.dump(2) + "\n");
    } catch (const brickyard::io::WriteError& e) {
      std::fprintf(stderr, "error: %s; the run's result was: %s\n", e.what(), to_string(s.result));
      return 1;
    }
  }
  if (report && s.result != RunResult::invalid_input && s.json.contains("recording")) {
    const int rc = run_report(a.out, a.quiet);
    if (rc != 0) std::fprintf(stderr, "[brickyard] warning: no report (brickyard-report exit %d); the run's result stands\n", rc);
  }
  if (s.result == RunResult::invalid_input) return 2;
  return s.result == RunResult::failed ? 1 : 0;
}

int cmd_report(const Args& a) {
  if (a.target.empty()) usage_error("report", "needs a run folder (brickyard run --out DIR)");
  return run_report(a.target, false);
}

// Every plugin found, or with a NAME only that one (exit 2 naming the known ones when none has it).
int cmd_plugins(const Args& a) {
  Registry reg = load_registry(a, nullptr);
  std::vector<const PluginEntry*> shown;
  for (const auto& p : reg.plugins())
    if (a.target.empty() || p.manifest.name == a.target) shown.push_back(&p);
  if (!a.target.empty() && shown.empty()) {
    std::string known;
    for (const auto& p : reg.plugins()) known += (known.empty() ? "" : ", ") + p.manifest.name;
    std::fprintf(stderr, "error: plugins %s: no plugin of that name (known: %s)\n", a.target.c_str(), known.c_str());
    return 2;
  }
  if (a.json) {
    nlohmann::json j;
    j["plugins"] = nlohmann::json::array();
    for (const auto* p : shown) j["plugins"].push_back(manifest_to_json(*p));
    j["errors"] = nlohmann::json::array();
    for (const auto& lp : reg.problems()) j["errors"].push_back({{"library", lp.library}, {"problems", lp.problems}});
    std::cout << j.dump(2) << "\n";
  } else {
    for (const auto* p : shown) std::cout << plugin_text(*p);
  }
  for (const auto& lp : reg.problems())
    for (const auto& p : lp.problems) std::fprintf(stderr, "error: %s: %s\n", lp.library.c_str(), p.c_str());
  return reg.problems().empty() ? 0 : 2;
}

int cmd_graph(const Args& a) {
  if (a.target.empty()) usage_error("graph", "needs a graph file");
  if (!a.dot) usage_error("graph", "choose an output format: --dot");
  GraphDecl g = load_graph_file(a.target, a.sets, a.args);
  Registry reg = load_registry(a, &g);
  resolve_graph(g, reg);
  std::cout << graph_dot(g, &reg);
  return 0;
}

int cmd_new_plugin(const Args& a) {
  if (a.target.empty()) usage_error("new-plugin", "needs a NAME");
  if (a.dir.empty()) usage_error("new-plugin", "needs --dir DIR");
  scaffold_plugin(a.target, a.dir, find_template_dir());
  std::cout << "wrote plugin project " << a.target << " in " << a.dir << "\n"
            << "build it:  cmake -S " << a.dir << " -B " << a.dir << "/build -DCMAKE_PREFIX_PATH=<brickyard prefix> && cmake --build "
            << a.dir << "/build\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" || std::string(argv[1]) == "help")) {
      std::cout << kUsage;
      return 0;
    }
    if (argc >= 2 && std::string(argv[1]) == "--version") {
      std::cout << "brickyard " << BRICKYARD_SDK_VERSION << " (plugin ABI " << BRICKYARD_ABI_MAJOR << "." << BRICKYARD_ABI_MINOR << ")\n";
      return 0;
    }
    Args a = parse_args(argc, argv);
    if (a.command == "run") return cmd_run(a, false);
    if (a.command == "validate") return cmd_run(a, true);
    if (a.command == "plugins") return cmd_plugins(a);
    if (a.command == "graph") return cmd_graph(a);
    if (a.command == "report") return cmd_report(a);
    if (a.command == "new-plugin") return cmd_new_plugin(a);
    if (a.command == "map") return cmd_map(a);
    if (a.command == "bag") return cmd_bag(a);
    if (a.command == "security") return cmd_security(a);
    if (a.command == "topic") {
      if (a.more.size() > 1) usage_error(a.more[1], "unexpected argument");
      TopicOptions o;
      o.verb = a.target;
      o.topic = a.more.empty() ? "" : a.more[0];
      o.domain = a.domain.value_or(0);
      o.duration = a.duration;
      o.count = a.count;
      o.security = a.security;
      o.identity = a.identity;
      return topic_command(o);
    }
    usage_error(a.command, "unknown command (commands: run, validate, plugins, graph, report, map, bag, topic, security, new-plugin)");
  } catch (const InvalidInput& e) {
    std::cerr << format_diagnostics(e.diagnostics());
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
