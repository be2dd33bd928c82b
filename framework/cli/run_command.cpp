#include "cli/run_command.hpp"

#include "cli/command_table.hpp"
#include "cli/load_registry.hpp"
#include "cli/out_folder.hpp"
#include "cli/report.hpp"
#include "cli/summary_tables.hpp"
#include "cli/supervisor.hpp"
#include "exec/crash_guard.hpp"
#include "exec/executive.hpp"
#include "exec/node_checks.hpp"
#include "graph/diagnostics.hpp"
#include "graph/resolve.hpp"
#include "io/whole_file.hpp"
#include "record/recorder.hpp"
#include "security/default_keys.hpp"
#include "security/security_files.hpp"

#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace brickyard::fw::cli {
namespace {

namespace fs = std::filesystem;

void on_signal(int) {
  g_interrupt = true;
  crash_guard::interrupted();  // the run has 2 s from here; a second signal ends it at once
}

// A supervised process's supervisor died: the kernel sends SIGHUP (the supervisor's
// PR_SET_PDEATHSIG), once for each parent the process is handed to on the way (a thread of the
// dying supervisor, then init). The run ends as interrupted, saying why; never a forced exit.
void on_supervisor_death(int) {
  g_supervisor_gone = true;
  if (!g_interrupt.exchange(true)) crash_guard::interrupted();
}

// What the plugins' own checks and the host's refuse, every node's together, before anything starts.
void say_notices_and_check(const Args& a, const ResolvedGraph& rg) {
  if (!a.quiet)
    for (const auto& n : rg.notices) std::fprintf(stderr, "notice: %s\n", n.c_str());
  if (auto failed = run_node_checks(rg); !failed.empty()) throw InvalidInput(std::move(failed));
}

// A split run's keys when its graph names none: made for the graph on its first split run
// (security/default_keys.hpp), said once by the supervisor or a process started by hand.
std::string default_keys(const Args& a, const GraphDecl& g, const Registry& reg, bool said_here) {
  const auto keys = security::ensure_default_keys(resolve_graph(g, reg));
  if (said_here && !a.quiet)
    std::fprintf(stderr, "notice: %s#/transport/security names no folder: the run's processes are authenticated and their traffic "
                         "encrypted with keys %s for the graph in %s (\"off\" turns this off; docs/security.md)\n",
                 g.file.c_str(), keys.made ? "made now" : "made on its first split run", keys.dir.c_str());
  return keys.dir;
}

// DDS security: the identity this process runs as, its files checked before anything starts. A
// run that crosses processes is secured unless its graph says "off" (warned): with the graph's
// folder, or keys made for it. Several processes in one participant would need one identity
// that writes for all of them, which would let a stolen key forge any topic: refused with a
// folder; by default such a run has nothing crossing processes to secure.
DdsSecurity run_security(const Args& a, const GraphDecl& g, const ResolvedGraph& rg, const Registry& reg, bool validate_only) {
  const bool split = rg.processes.size() > 1 && !a.one_process;
  const bool said_here = !std::getenv("BRICKYARD_SHM_LIST");  // not a supervised child: its supervisor says it
  const bool many_here = a.process.empty() && rg.processes.size() > 1;
  GraphDecl secured = g;
  switch (security::security_choice(g)) {
    case security::SecurityChoice::off:
      if (split && !validate_only && said_here)
        std::fprintf(stderr, "warning: %s#/transport/security is \"off\": this run's processes meet over DDS unauthenticated and "
                             "unencrypted: any program on this machine on its domain can read every wire and write any input, "
                             "taking a process's name (docs/security.md)\n", g.file.c_str());
      return DdsSecurity{};
    case security::SecurityChoice::by_default:
      if (!split || validate_only) return DdsSecurity{};
      secured.transport.security = default_keys(a, g, reg, said_here);
      break;
    case security::SecurityChoice::folder:
      if (many_here && !validate_only && a.one_process) {
        std::string names;
        for (const auto& p : rg.processes) names += (names.empty() ? "" : ", ") + p;
        usage_error(g.where("/transport/security"), "a run of processes " + names +
                                                        " in one participant: each identity may write only its own process's topics; run each process (--process NAME, or supervised on the real clock)");
      }
      break;
  }
  return security::check_run(secured, many_here ? std::string() : a.process.empty() ? *rg.processes.begin() : a.process, rg.processes);
}

int say_valid(const Args& a, const GraphDecl& g, const ResolvedGraph& rg) {
  std::size_t wires = g.wires.size();
  std::cout << a.target << ": valid — " << rg.nodes.size() << " nodes, " << wires << " wires, "
            << rg.processes.size() << " process(es), " << (g.clock.sim ? "sim" : "real") << " clock\n";
  return 0;
}

// A split graph: each process a child of this one (cli/supervisor.hpp); on the sim clock they
// step in lockstep (exec/lockstep.hpp).
int supervise_run(const Args& a, const GraphDecl& g) {
  if (!a.record.empty()) usage_error("--record", "a supervised run records each process into --out DIR/PROCESS/recording.mcap; use --out (or --process, or --one-process)");
  if (a.live_port || g.live.port) usage_error("--live", "a supervised run serves nothing live itself; use --process NAME --live PORT for the process to watch (or --one-process)");
  if (a.pace > 0 && !g.clock.sim) usage_error("--pace", "the graph runs on the real clock, which needs no pacing");
  SuperviseOptions so;
  so.graph_file = a.target;
  so.child_flags = a.child_flags;
  so.duration_s = a.duration ? a.duration : g.clock.duration_s;
  so.domain = a.domain.value_or(g.transport.domain);
  // Each process takes a participant id of its own, up to 119 (cli/supervisor.cpp): on domain 232
  // their ports would pass 65535 and Fast DDS would refuse them once the run had started.
  if (so.domain > kLastSupervisedDomain)
    usage_error(a.domain ? "--domain" : a.target + "#/transport/domain", "a run split into processes needs a DDS domain id from 0 to " +
                                                                 std::to_string(kLastSupervisedDomain) + ", found " + std::to_string(so.domain));
  so.out = a.out;
  so.quiet = a.quiet;
  return supervise(g, so);
}

RunOptions run_options(const Args& a, const GraphDecl& g, const DdsSecurity& security) {
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
  opt.record_profile = a.record_profile;
  opt.record_scene = a.record_scene;
  if (a.record_profile == "ros2" && is_sqlite_recording(a.record))
    usage_error("--record-profile ros2", "MCAP's profile: --record " + a.record + " is SQLite (name a .mcap file)");
  opt.record_cloud_precision = a.record_cloud_precision;
  opt.profile = a.profile;
  opt.threads = a.threads;
  opt.security = security;
  opt.live_port = a.live_port ? a.live_port : g.live.port;  // the flag, else the graph's "live"
  opt.live_address = a.live_address_set ? a.live_address : g.live.address;
  opt.live_cloud_hz = a.live_cloud_hz ? *a.live_cloud_hz : g.live.cloud_hz.value_or(20.0);
  opt.pace = a.pace;
  return opt;
}

// The run itself, with the crash guard armed (exec/crash_guard.hpp): a plugin that takes the
// process down still leaves a summary in `out`.
RunSummary execute(const ResolvedGraph& rg, const RunOptions& opt, const std::string& out) {
  RunSummary s;
  crash_guard::install(out.empty() ? std::string() : (fs::path(out) / "summary.json").string());
  struct Disarm {  // however this scope is left: the run is over, exit() and a slow teardown are not a crash
    ~Disarm() { crash_guard::run_ended(); }
  } disarm;
  {
    Executive ex(rg, opt);
    s = ex.run();
    crash_guard::run_ended();
  }
  return s;
}

// What an ended run says and leaves: its tables and verdict on stderr, --out's summary.json and
// report; the exit code.
int finish_run(const Args& a, RunSummary& s, bool record_out, bool report) {
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

}  // namespace

int run_graph(const Args& a, GraphDecl g, bool validate_only) {
  if (!validate_only && !a.out.empty()) {  // a plugin library that crashes while loading leaves its summary there
    refuse_foreign_out_files(a.out);
    crash_guard::set_summary_path((fs::path(a.out) / "summary.json").string());
  }
  Registry reg = load_registry(a, &g);
  ResolvedGraph rg = resolve_graph(g, reg, a.process, run_node_checks);
  say_notices_and_check(a, rg);
  const DdsSecurity security = run_security(a, g, rg, reg, validate_only);
  if (validate_only) return say_valid(a, g, rg);
  if (!a.out.empty()) prepare_out_folder(a.out);
  if (a.one_process && !a.process.empty()) usage_error("--one-process", "cannot go with --process");
  if (a.record_cloud_precision > 0 && a.record.empty())
    usage_error("--record-cloud-precision", "needs --record FILE (the --out folder's recording leaves the clouds out)");
  if (a.process.empty() && !a.one_process && rg.processes.size() > 1) return supervise_run(a, g);
  if (std::getenv("BRICKYARD_SHM_LIST")) std::signal(SIGHUP, on_supervisor_death);  // set by the supervisor for its children only
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RunOptions opt = run_options(a, g, security);
  if (a.pace > 0 && !g.clock.sim) usage_error("--pace", "the graph runs on the real clock, which needs no pacing");
  if (!a.record_only.empty() && a.record.empty()) usage_error("--record-only", "needs --record FILE");
  // --out keeps the run: its summary, a recording of everything but the point clouds (those
  // are large; --record takes them) and the report drawn from it. The folder's own recording
  // is the run's output, replaced by the next run into it (a --record FILE never is).
  // One process of a multi-process graph records its own wires into its folder (a supervisor
  // gives each its own), and draws no report: the report needs the whole run.
  const bool record_out = !a.out.empty() && !a.no_report;
  const bool report = record_out && a.process.empty();
  if (!a.out.empty()) clear_earlier_run(a.out, a.record);
  if (record_out && a.record.empty()) {
    opt.record = (fs::path(a.out) / kOutRecording).string();
    opt.record_skip_types = {"brickyard::msgs::PointCloud", "brickyard::msgs::ClusterList"};
  }
  RunSummary s = execute(rg, opt, a.out);
  return finish_run(a, s, record_out, report);
}

int cmd_run(const Args& a, bool validate_only) {
  if (a.target.empty()) usage_error(a.command, "needs a graph file");
  return run_graph(a, load_graph_file(a.target, a.sets, a.args), validate_only);
}

}  // namespace brickyard::fw::cli
