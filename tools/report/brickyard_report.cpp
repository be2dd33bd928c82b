// brickyard-report RUN_DIR: one HTML file, RUN_DIR/report.html, with the figures that tell a
// run's story, drawn by gnuplot from RUN_DIR/recording.db3 and summary.json (a tour of the
// figures: docs/report.md). `brickyard report RUN_DIR` runs it, and `brickyard run --out DIR`
// does at the end of a run. Exit 2 with a message naming the file when the run folder is not
// usable or gnuplot is missing.
#include "figures.hpp"
#include "io/whole_file.hpp"
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
using brickyard::report::Figure;
using brickyard::report::RunData;
using brickyard::report::Writer;

namespace {

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
  const std::vector<Figure> figs = brickyard::report::figures(data, summary, w);
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
  // Whole or not at all: a full disk leaves the old report, never half of a new one.
  brickyard::io::write_whole_file((dir / "report.html").string(), h.str());
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
