#include "cli/arguments.hpp"

#include "graph/diagnostics.hpp"
#include "graph/graph.hpp"  // kMaxDuration_s

#include <algorithm>
#include <set>

namespace brickyard::fw::cli {

void usage_error(const std::string& where, const std::string& msg) { throw InvalidInput(where, msg); }

namespace {

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

// Where the parse is in argv: an option's value is the argument after it, consumed.
struct Cursor {
  const std::vector<std::string>& v;
  std::size_t& i;

  std::string value() {
    if (i + 1 >= v.size()) usage_error(v[i], "needs a value");
    return v[++i];
  }
};

// Flags every process of a supervised run is given as they are.
void note_child_flag(Args& a, const std::vector<std::string>& v, std::size_t i) {
  static const std::set<std::string> kForwarded = {"--set", "--arg", "--seed", "--plugin-path", "--threads", "--progress", "--pace"};
  const std::string& f = v[i];
  if (kForwarded.count(f) && i + 1 < v.size()) a.child_flags.insert(a.child_flags.end(), {f, v[i + 1]});
  if (f == "--quiet" || f == "-q" || f == "--profile" || f == "--no-report") a.child_flags.push_back(f);
}

std::uint64_t parse_seed(const std::string& s) {
  // Up to 19 digits: every such number fits the 64-bit seed (stoull would throw on more).
  if (s.empty() || s.size() > 19 || s.find_first_not_of("0123456789") != std::string::npos)
    usage_error("--seed " + (s.size() > 40 ? s.substr(0, 40) + "…" : s), "expected a non-negative integer of at most 19 digits");
  return std::stoull(s);
}

int parse_threads(const std::string& s) {
  if (s.empty() || s.size() > 3 || s.find_first_not_of("0123456789") != std::string::npos || std::stoi(s) < 1 || std::stoi(s) > 64)
    usage_error("--threads " + s, "expected an integer from 1 to 64");
  return std::stoi(s);
}

// The options of a graph's run (run, validate, and the commands that run a graph); false: not one.
bool run_option(Args& a, const std::string& f, Cursor& c) {
  if (f == "--duration") {
    double d = parse_number(f, c.value());
    if (!(d > 0 && d <= kMaxDuration_s)) usage_error("--duration", "expected a positive number of seconds, at most 1e7");
    a.duration = d;
  } else if (f == "--set") a.sets.push_back(c.value());
  else if (f == "--arg") a.args.push_back(c.value());
  else if (f == "--seed") a.seed = parse_seed(c.value());
  else if (f == "--out") a.out = c.value();
  else if (f == "--process") a.process = c.value();
  else if (f == "--domain") {
    double d = parse_number(f, c.value());
    if (d < 0 || d > 232 || d != static_cast<int>(d)) usage_error("--domain", "expected an integer from 0 to 232");
    a.domain = static_cast<int>(d);
  } else if (f == "--plugin-path") a.plugin_paths.push_back(c.value());
  else if (f == "--dir") a.dir = c.value();
  else if (f == "--role") a.role = c.value();
  else if (f == "--pace") {
    // Bounded both ways: a factor of 1e-30 made the wait between steps overflow into none.
    a.pace = parse_number(f, c.value());
    if (!(a.pace >= 1e-3 && a.pace <= 1e6)) usage_error("--pace", "expected a factor of real time from 0.001 to 1e6");
  }
  else if (f == "--no-report") a.no_report = true;
  else if (f == "--one-process") a.one_process = true;
  else if (f == "--profile") a.profile = true;
  else if (f == "--threads") a.threads = parse_threads(c.value());
  else if (f == "--progress") {
    a.progress = parse_number(f, c.value());
    if (!(a.progress >= 0)) usage_error("--progress", "expected seconds, 0 or more");
  }
  else return false;
  return true;
}

// What a run records (--record and its companions); false: not one of these.
bool record_option(Args& a, const std::string& f, Cursor& c) {
  if (f == "--record") a.record = c.value();
  else if (f == "--record-compression") {
    a.record_compression = c.value();
    if (a.record_compression != "zstd" && a.record_compression != "lz4" && a.record_compression != "none")
      usage_error("--record-compression " + a.record_compression, "expected zstd, lz4 or none");
  }
  else if (f == "--record-scene") {
    const std::string v = c.value();
    if (v != "on" && v != "off") usage_error("--record-scene " + v, "expected on or off");
    a.record_scene = v == "on";
  }
  else if (f == "--record-profile") {
    a.record_profile = c.value();
    if (a.record_profile != "brickyard" && a.record_profile != "ros2")
      usage_error("--record-profile " + a.record_profile, "expected brickyard or ros2");
  }
  else if (f == "--record-cloud-precision") {
    a.record_cloud_precision = parse_number(f, c.value());
    if (!(a.record_cloud_precision > 0 && a.record_cloud_precision <= 0.1))
      usage_error("--record-cloud-precision", "expected metres, more than 0 and at most 0.1");
  }
  else if (f == "--record-only") a.record_only = patterns(f, c.value());
  else return false;
  return true;
}

// What a run serves live (--live and its companions); false: not one of these.
bool live_option(Args& a, const std::string& f, Cursor& c) {
  if (f == "--live") {
    const std::string v = c.value();
    if (v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos || std::stoi(v) > 65535)
      usage_error("--live " + v, "expected a port from 0 to 65535 (0: any free one)");
    a.live_port = std::stoi(v);
  } else if (f == "--live-address") a.live_address = c.value(), a.live_address_set = true;
  else if (f == "--live-cloud-hz") {
    a.live_cloud_hz = parse_number(f, c.value());
    if (!(*a.live_cloud_hz >= 0) || *a.live_cloud_hz > 1000)
      usage_error("--live-cloud-hz", "expected clouds a second from 0 (every one) to 1000");
  }
  else return false;
  return true;
}

// The options of bag play, topic and security init; false: not one of these.
bool tool_option(Args& a, const std::string& f, Cursor& c) {
  if (f == "--rate") {
    a.rate = parse_number(f, c.value());
    // capture play may send as fast as it can (0); bag play's DDS writers are always paced.
    if (a.command == "capture") {
      if (!(a.rate == 0 || (a.rate >= 1e-3 && a.rate <= 1e6)))
        usage_error("--rate", "expected a factor of the recorded pace, 0 (as fast as possible) or from 0.001 to 1e6");
    } else if (!(a.rate >= 1e-3 && a.rate <= 1e6)) usage_error("--rate", "expected a factor of the recorded speed from 0.001 to 1e6");
  } else if (f == "--only") a.only = patterns(f, c.value());
  else if (f == "--map") a.bag_map = c.value();
  else if (f == "--count") {
    const std::string v = c.value();
    if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos || std::stol(v) < 1)
      usage_error("--count " + v, "expected a whole number of samples, 1 or more");
    a.count = std::stol(v);
  }
  else if (f == "--security") a.security = c.value();
  else if (f == "--identity") a.identity = c.value();
  else if (f == "--naming") {
    const std::string v = c.value();
    if (v != "ros2" && v != "brickyard") usage_error("--naming " + v, "expected brickyard or ros2 (the graph's transport.naming)");
    a.ros2_naming = v == "ros2";
  }
  else if (f == "--protect") {
    a.protect = c.value();
    if (a.protect != "sign" && a.protect != "encrypt") usage_error("--protect " + a.protect, "expected sign or encrypt");
  } else if (f == "--days") {
    const std::string v = c.value();
    if (v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos || std::stoi(v) < 1 || std::stoi(v) > 3650)
      usage_error("--days " + v, "expected a whole number of days from 1 to 3650");
    a.days = std::stoi(v);
  }
  else return false;
  return true;
}

// The options of capture info and play; false: not one of these.
bool capture_option(Args& a, const std::string& f, Cursor& c) {
  if (f == "--to") a.to = c.value();
  else if (f == "--metadata") a.metadata = c.value();
  else if (f == "--loop") a.loop = true;
  else if (f == "--port") {
    const std::string v = c.value();
    if (v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos || std::stoi(v) < 1 || std::stoi(v) > 65535)
      usage_error("--port " + v, "expected a UDP port from 1 to 65535");
    a.port = std::stoi(v);
  }
  else return false;
  return true;
}

// The flags every command takes; false: not one of these.
bool output_option(Args& a, const std::string& f) {
  if (f == "--json") a.json = true;
  else if (f == "--dot") a.dot = true;
  else if (f == "--quiet" || f == "-q") a.quiet = true;
  else return false;
  return true;
}

// An argument that is no known option: the target, or one more positional argument of a command
// that takes them.
void positional(Args& a, const std::string& f) {
  if (f.rfind("--", 0) == 0) usage_error(f, "unknown option (see brickyard --help)");
  else if (a.target.empty()) a.target = f;
  else if (a.command == "map" || a.command == "bag" || a.command == "topic" || a.command == "security" ||
           a.command == "capture")
    a.more.push_back(f);
  else usage_error(f, "unexpected argument");
}

}  // namespace

Args parse_args(int argc, char** argv) {
  Args a;
  std::vector<std::string> v(argv + 1, argv + argc);
  if (v.empty()) usage_error("brickyard", "no command given (try --help)");
  a.command = v[0];
  for (std::size_t i = 1; i < v.size(); ++i) {
    const std::string& f = v[i];
    Cursor c{v, i};
    note_child_flag(a, v, i);
    if (!run_option(a, f, c) && !record_option(a, f, c) && !live_option(a, f, c) && !tool_option(a, f, c) && !capture_option(a, f, c) &&
        !output_option(a, f))
      positional(a, f);
  }
  return a;
}

}  // namespace brickyard::fw::cli
