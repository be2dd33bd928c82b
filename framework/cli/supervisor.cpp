#include "cli/supervisor.hpp"
#include "io/whole_file.hpp"
#include "exec/crash_guard.hpp"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

extern char** environ;

namespace brickyard::fw {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

volatile sig_atomic_t g_signals = 0;
void on_signal(int) { g_signals = g_signals + 1; }
void on_child(int) {}  // only to wake the poll below when a child ends

// Children are stopped with SIGINT and have 2 s to end (their own watchdog); past this they are killed.
constexpr double kStopGrace_s = 5.0;
// On the sim clock, past transport.end_timeout_s after a process ended: its peers' own waits for
// its end (Lockstep::finish), then their last samples acknowledged (5 s) and their ending (2 s).
constexpr double kEndSlack_s = 10.0;
constexpr double kMaxBackoff_s = 5.0;
// A restart with less of the run left than this is not worth making.
constexpr double kLeastRun_s = 0.5;

std::string signal_name(int sig) {
  const char* abbrev = sigabbrev_np(sig);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(sig);
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

struct Child {
  std::string name;
  std::vector<std::string> nodes;
  ProcessDecl policy;
  enum class State { waiting, running, done } state = State::waiting;
  pid_t pid = -1;
  int out_fd = -1;
  std::string partial;  // output not yet ended by a newline
  Clock::time_point start_at;
  double started_s = 0;
  int restarts = 0;
  bool stopped = false;  // asked by the supervisor to end
  std::string dir;       // this run's --out folder
  std::string shm_list;  // where it lists its shared-memory files (crash_guard)
  std::string black_box;  // where it keeps what each of its threads runs (crash_guard::BlackBox)
  nlohmann::json runs = nlohmann::json::array();
};

// The child's summary.json, when it wrote one.
nlohmann::json own_summary(const Child& c) {
  nlohmann::json own;
  std::ifstream f(fs::path(c.dir) / "summary.json");
  try {
    if (f) own = nlohmann::json::parse(f);
  } catch (...) {
  }
  return own;
}

// How it ended, for people: its signal (with what its black box says it was running: it could
// not say) or its exit code.
std::string how_it_ended(const Child& c, int code, int sig) {
  std::string how = sig ? "was killed by " + signal_name(sig) : code == 127 ? "could not be started (exit 127)" : "exited with code " + std::to_string(code);
  if (sig) {
    std::string running;
    crash_guard::BlackBox box{};
    std::ifstream f(c.black_box, std::ios::binary);
    if (f.read(reinterpret_cast<char*>(&box), sizeof box)) {
      for (auto& s : box.slots) {
        s.node[sizeof s.node - 1] = s.phase[sizeof s.phase - 1] = '\0';
        if (s.node[0]) running += std::string(running.empty() ? "" : ", ") + "node '" + s.node + "' was in its " + s.phase;
      }
      how += running.empty() ? " (no node was in a plugin call)" : " while " + running;
    }
  }
  return how;
}

// The run that just ended, added to the child's runs (the supervisor's summary lists them).
void add_run(Child& c, const nlohmann::json& own, const std::string& reason, int code, int sig, double at) {
  nlohmann::json run = {{"out", fs::path(c.dir).filename().string()}, {"pid", c.pid}, {"started_s", c.started_s}, {"ended_s", at},
                        {"result", own.is_object() ? own.value("result", "") : "failed"}, {"reason", reason}};
  if (sig) run["signal"] = signal_name(sig);
  else run["exit_code"] = code;
  if (c.stopped) run["stopped_by_supervisor"] = true;
  c.runs.push_back(run);
}

// SIGINT and SIGTERM count (the watch loop acts on them), SIGCHLD wakes its poll.
void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;  // no SA_RESTART: poll returns at once
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sa.sa_handler = on_child;
  sigaction(SIGCHLD, &sa, nullptr);
}

class Supervisor {
 public:
  Supervisor(const GraphDecl& g, const SuperviseOptions& o) : g_(g), o_(o), t0_(Clock::now()) {}
  int run();

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  void say(const std::string& line, bool always = false) {
    if (o_.quiet && !always) return;
    std::fprintf(stderr, "[brickyard] %s\n", line.c_str());
  }
  void spawn(Child& c);
  void relay(Child& c, bool to_end);
  void ended(Child& c, int status);
  void collect_shared_memory(const Child& c, bool clean);
  void write_child_summary(const Child& c, const std::string& how, double at);
  void ended_cleanly(const Child& c, const std::string& reason);
  void apply_restart_policy(Child& c, const std::string& what, double at);
  void stop_all(int sig);
  void fail(const std::string& why) {
    if (!failed_) failed_ = why;
  }
  void write_summary(const std::string& result, const std::string& reason);
  void prepare_folders();
  void make_children();
  void watch();
  void wait_for_children();
  void kill_overdue();
  void stop_overdue_lockstep_peers();
  int conclude();

  const GraphDecl& g_;
  const SuperviseOptions& o_;
  Clock::time_point t0_;
  std::string self_, base_, tmp_;
  std::vector<Child> children_;
  int spawns_ = 0;
  std::vector<std::string> shm_files_;  // every child's shared-memory files, removed at the end
  std::optional<std::string> failed_, invalid_, finished_by_;
  bool stopping_ = false, interrupted_ = false;
  Clock::time_point stop_deadline_;
  std::optional<std::pair<std::string, Clock::time_point>> first_end_;  // the sim clock: the first process to end, when
};

void Supervisor::spawn(Child& c) {
  c.dir = (fs::path(base_) / (c.restarts ? c.name + ".restart" + std::to_string(c.restarts) : c.name)).string();
  c.shm_list = (fs::path(tmp_) / (c.name + "." + std::to_string(c.restarts) + ".shm")).string();
  std::vector<std::string> argv = {self_, "run", o_.graph_file, "--process", c.name, "--domain", std::to_string(o_.domain), "--out", c.dir};
  if (o_.duration_s) {
    // The real clock: what is left of the run (a restarted process ends with the others); the
    // sim clock: the whole, to the bit (every process of the lockstep ends at the same instant).
    char d[32];
    if (g_.clock.sim) std::snprintf(d, sizeof d, "%.17g", *o_.duration_s);
    else std::snprintf(d, sizeof d, "%.3f", std::max(*o_.duration_s - elapsed(), 0.001));
    argv.insert(argv.end(), {"--duration", d});
  }
  argv.insert(argv.end(), o_.child_flags.begin(), o_.child_flags.end());
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "BRICKYARD_SHM_LIST=", 19) != 0 && std::strncmp(*e, "BRICKYARD_PARTICIPANT_ID=", 25) != 0 &&
        std::strncmp(*e, "BRICKYARD_BLACKBOX=", 19) != 0)
      env.emplace_back(*e);
  env.push_back("BRICKYARD_SHM_LIST=" + c.shm_list);
  c.black_box = (fs::path(tmp_) / (c.name + "." + std::to_string(c.restarts) + ".box")).string();
  env.push_back("BRICKYARD_BLACKBOX=" + c.black_box);
  // A participant id of its own, never a dead process's (transport/dds.cpp says why).
  env.push_back("BRICKYARD_PARTICIPANT_ID=" + std::to_string(spawns_++ % kSupervisedParticipants));
  std::vector<char*> av, ev;
  for (auto& s : argv) av.push_back(s.data());
  for (auto& s : env) ev.push_back(s.data());
  av.push_back(nullptr);
  ev.push_back(nullptr);
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot start a process: ") + std::strerror(errno));
  if (pid == 0) {
    // The child: its own process group (a Ctrl-C at the terminal reaches the supervisor, which
    // stops the children in order), told to end when the supervisor dies, its output to the pipe.
    // SIGPIPE ignored (kept across exec): were the supervisor killed, the child's next line to the
    // pipe would kill it before it wrote its summary; it ends on the parent-death SIGHUP instead
    // (a signal of its own: the kernel may send it more than once, and it must not count as the
    // second Ctrl-C that forces an exit).
    setpgid(0, 0);
    signal(SIGPIPE, SIG_IGN);
    prctl(PR_SET_PDEATHSIG, SIGHUP);
    if (getppid() != parent) _exit(130);
    dup2(fds[1], 1);
    dup2(fds[1], 2);
    execve(av[0], av.data(), ev.data());
    _exit(127);
  }
  close(fds[1]);
  fcntl(fds[0], F_SETFL, fcntl(fds[0], F_GETFL) | O_NONBLOCK);
  c.pid = pid;
  c.out_fd = fds[0];
  c.state = Child::State::running;
  c.stopped = false;
  c.started_s = elapsed();
  char line[160];
  std::snprintf(line, sizeof line, "process '%s' started (pid %d) at %.3f s%s", c.name.c_str(), static_cast<int>(pid), c.started_s,
                c.restarts ? (", restart " + std::to_string(c.restarts)).c_str() : "");
  say(line, c.restarts > 0);
}

// What a child writes goes out line by line under its name.
void Supervisor::relay(Child& c, bool to_end) {
  if (c.out_fd < 0) return;
  char buf[8192];
  for (;;) {
    const ssize_t n = read(c.out_fd, buf, sizeof buf);
    if (n > 0) {
      c.partial.append(buf, static_cast<std::size_t>(n));
      std::size_t at;
      while ((at = c.partial.find('\n')) != std::string::npos) {
        std::fprintf(stderr, "[%s] %s\n", c.name.c_str(), c.partial.substr(0, at).c_str());
        c.partial.erase(0, at + 1);
      }
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN && !to_end) return;
    if (n < 0 && errno == EAGAIN) {  // the child is gone; a grandchild may hold the pipe: wait a little
      pollfd p{c.out_fd, POLLIN, 0};
      if (poll(&p, 1, 200) > 0) continue;
    }
    break;  // end of file, or nothing more to wait for
  }
  if (!c.partial.empty()) std::fprintf(stderr, "[%s] %s\n", c.name.c_str(), c.partial.c_str());
  c.partial.clear();
  close(c.out_fd);
  c.out_fd = -1;
}

void Supervisor::stop_all(int sig) {
  if (!stopping_) stop_deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kStopGrace_s));
  stopping_ = true;
  for (auto& c : children_) {
    if (c.state == Child::State::waiting) c.state = Child::State::done;  // a restart not made
    if (c.state != Child::State::running) continue;
    c.stopped = true;
    kill(c.pid, sig);
  }
}

// A child has ended: how, what it said of itself, what it leaves, and what happens next.
void Supervisor::ended(Child& c, int status) {
  relay(c, true);
  c.state = Child::State::done;
  if (g_.clock.sim && !first_end_) first_end_ = {c.name, Clock::now()};
  const double at = elapsed();
  int code = -1, sig = 0;
  if (WIFEXITED(status)) code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status)) sig = WTERMSIG(status);
  const nlohmann::json own = own_summary(c);
  const std::string reason = own.is_object() ? own.value("reason", "") : "";
  // Stopped and ended as interrupted: clean, unless its crash guard had to force the exit (a node
  // stuck in its step past the 2 s a stop allows): that is a hang, and fails the run.
  const bool forced = own.is_object() && own.value("forced_exit", false);
  const bool clean = code == 0 || (c.stopped && code == 130 && !forced);
  collect_shared_memory(c, clean);
  const std::string how = how_it_ended(c, code, sig);
  if (!own.is_object()) write_child_summary(c, how, at);
  add_run(c, own, reason, code, sig, at);
  c.pid = -1;

  if (code == 2) {
    invalid_ = "process '" + c.name + "': " + (reason.empty() ? "invalid input" : reason);
    say("process '" + c.name + "' refused its input (exit 2): stopping the others", true);
    stop_all(SIGINT);
    return;
  }
  if (clean) {
    ended_cleanly(c, reason);
    return;
  }
  const std::string what = "process '" + c.name + "' (nodes " + join(c.nodes) + ") " + how + (reason.empty() ? "" : ": " + reason);
  say(what, true);
  if (!c.policy.may_die) fail(what);
  if (c.stopped || stopping_) return;
  apply_restart_policy(c, what, at);
}

// What its participant made in /dev/shm (it listed the files). A dead one's segment goes now
// (a crash handler may have removed it already). Port files stay until every process has
// ended: a peer still has them mapped and sends to them, and a restarted process opens the
// same ports (were they unlinked now, it would never hear that peer). Then they all go, a clean
// process's too: a dead peer's reference keeps Fast DDS from removing them at its exit.
void Supervisor::collect_shared_memory(const Child& c, bool clean) {
  std::ifstream list(c.shm_list);
  for (std::string file; std::getline(list, file);)
    if (file.rfind("/dev/shm/", 0) == 0) {
      std::error_code ec;
      if (!clean && file.find("fastrtps_port") == std::string::npos) fs::remove(file, ec);
      shm_files_.push_back(file);
    }
}

// It could not say anything (SIGKILL, or dead before its run began): the supervisor writes its summary.
void Supervisor::write_child_summary(const Child& c, const std::string& how, double at) {
  nlohmann::json s = {{"graph", g_.name}, {"graph_file", g_.file}, {"process", c.name}, {"result", "failed"},
                      {"reason", "process '" + c.name + "' " + how + " and left no summary (written by its supervisor)"},
                      {"clock", g_.clock.sim ? "sim" : "real"}, {"wall_time_s", at - c.started_s}, {"nodes", nlohmann::json::object()}};
  for (const auto& n : c.nodes) s["nodes"][n] = {{"plugin", g_.nodes.at(n).plugin}};
  std::error_code ec;
  fs::create_directories(c.dir, ec);
  std::ofstream(fs::path(c.dir) / "summary.json") << s.dump(2) << "\n";
}

void Supervisor::ended_cleanly(const Child& c, const std::string& reason) {
  say("process '" + c.name + "' ended" + (reason.empty() ? "" : ": " + reason));
  // The first process to end on its own ends the run (its referee, its sink, its duration). On
  // the sim clock the others end at the same event by themselves, perhaps later in wall time.
  if (!c.stopped && !stopping_ && g_.clock.sim) {
    if (!finished_by_) finished_by_ = "process '" + c.name + "': " + reason;
  } else if (!c.stopped && !stopping_) {
    finished_by_ = "process '" + c.name + "': " + reason;
    if (std::any_of(children_.begin(), children_.end(), [](const Child& o) { return o.state != Child::State::done; }))
      say("stopping the other processes");
    stop_all(SIGINT);
  }
}

// A child that failed, not stopped by the supervisor: restarted after its backoff when its policy
// says so and it has restarts and the run time left.
void Supervisor::apply_restart_policy(Child& c, const std::string& what, double at) {
  // The others go on whatever died: a car interface among them keeps its car safe (it brakes on
  // its command watchdog) rather than being stopped; the verdict is kept.
  if (c.policy.restart != ProcessDecl::Restart::on_failure) {
    say(c.policy.may_die ? "the graph lets process '" + c.name + "' die; the others go on"
        : g_.clock.sim   ? "the run has failed (process '" + c.name + "' may not die); the others, in lockstep with it, end too"
                         : "the others go on; the run has failed (process '" + c.name + "' may not die)",
        true);
    return;
  }
  if (c.restarts >= c.policy.max_restarts) {
    say("process '" + c.name + "': no restart left (max_restarts " + std::to_string(c.policy.max_restarts) + ")", true);
    if (!c.policy.may_die) fail(what + "; restarted " + std::to_string(c.restarts) + " times, no restart left");
    return;
  }
  const double backoff = std::min(c.policy.backoff_s * static_cast<double>(1u << std::min(c.restarts, 16)), kMaxBackoff_s);
  if (o_.duration_s && *o_.duration_s - at - backoff < kLeastRun_s) {
    say("process '" + c.name + "' is not restarted: the run is nearly over", true);
    return;
  }
  ++c.restarts;
  c.state = Child::State::waiting;
  c.start_at = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(backoff));
  char line[160];
  std::snprintf(line, sizeof line, "restarting process '%s' in %.2f s (restart %d of %d)", c.name.c_str(), backoff, c.restarts,
                c.policy.max_restarts);
  say(line, true);
}

void Supervisor::write_summary(const std::string& result, const std::string& reason) {
  if (o_.out.empty()) return;
  nlohmann::json j = {{"graph", g_.name}, {"graph_file", g_.file}, {"result", result}, {"reason", reason}, {"clock", g_.clock.sim ? "sim" : "real"},
                      {"process", "supervisor"}, {"wall_time_s", elapsed()}, {"processes", nlohmann::json::object()}};
  // What watching cost: the supervisor's own CPU time beside its children's (docs/reliability.md).
  auto cpu = [](int who) {
    rusage u{};
    getrusage(who, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
  };
  j["cpu_s"] = {{"supervisor", cpu(RUSAGE_SELF)}, {"processes", cpu(RUSAGE_CHILDREN)}};
  for (const auto& c : children_)
    j["processes"][c.name] = {{"nodes", c.nodes}, {"restart", c.policy.restart == ProcessDecl::Restart::on_failure ? "on-failure" : "never"},
                              {"may_die", c.policy.may_die}, {"restarts", c.restarts}, {"runs", c.runs}};
  try {
    io::write_whole_file((fs::path(o_.out) / "summary.json").string(), j.dump(2) + "\n");
  } catch (const io::WriteError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
}

// What the folder's last supervised run made goes (its summary lists its processes' folders).
void Supervisor::prepare_folders() {
  std::error_code ec;
  self_ = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw std::runtime_error("cannot find this executable (/proc/self/exe)");
  char tmpl[] = "/tmp/brickyard-supervisor-XXXXXX";
  if (!mkdtemp(tmpl)) throw std::runtime_error(std::string("cannot make a temporary folder: ") + std::strerror(errno));
  tmp_ = tmpl;
  base_ = o_.out.empty() ? tmp_ : o_.out;
  if (!o_.out.empty()) {
    std::ifstream old(fs::path(o_.out) / "summary.json");
    try {
      const auto j = nlohmann::json::parse(old);
      if (j.value("process", "") == "supervisor")
        for (const auto& [_, p] : j.at("processes").items())
          for (const auto& r : p.at("runs")) {
            const std::string sub = r.value("out", "");
            if (!sub.empty() && sub.find('/') == std::string::npos && sub != "." && sub != "..") fs::remove_all(fs::path(o_.out) / sub, ec);
          }
    } catch (...) {
    }
    fs::remove(fs::path(o_.out) / "summary.json", ec);
  }
}

// A child per process the graph's nodes name, in the order of their names.
void Supervisor::make_children() {
  std::map<std::string, std::vector<std::string>> nodes;
  for (const auto& [name, n] : g_.nodes) nodes[n.process].push_back(name);
  for (const auto& [p, names] : nodes) {
    Child c;
    c.name = p;
    c.nodes = names;
    c.policy = process_policy(g_, p);
    c.start_at = t0_;
    children_.push_back(std::move(c));
  }
}

// Asleep until a child speaks or ends (SIGCHLD), a signal comes, or a restart or a stop is due:
// watching costs next to nothing (cpu_s in the summary). What the children said is relayed.
void Supervisor::wait_for_children() {
  std::vector<pollfd> fds;
  std::vector<Child*> who;
  for (auto& c : children_)
    if (c.out_fd >= 0) fds.push_back({c.out_fd, POLLIN, 0}), who.push_back(&c);
  auto wake = Clock::now() + std::chrono::milliseconds(250);
  for (const auto& c : children_)
    if (c.state == Child::State::waiting) wake = std::min(wake, c.start_at);
  if (stopping_) wake = std::min(wake, stop_deadline_);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(wake - Clock::now()).count();
  poll(fds.data(), fds.size(), static_cast<int>(std::clamp<long long>(ms + 1, 0, 250)));
  for (std::size_t i = 0; i < fds.size(); ++i)
    if (fds[i].revents) relay(*who[i], false);
}

// The children still running past the stop's grace are killed.
void Supervisor::kill_overdue() {
  for (auto& c : children_)
    if (c.state == Child::State::running) {
      say("process '" + c.name + "' did not end within " + std::to_string(static_cast<int>(kStopGrace_s)) + " s of being stopped: killed", true);
      kill(c.pid, SIGKILL);
    }
  stop_deadline_ = Clock::now() + std::chrono::hours(1);
}

// On the sim clock the processes end together (exec/lockstep.hpp): one still running well past
// end_timeout_s after another ended is held by something its own watchdogs do not see (it once
// kept a failed run alive until CTest killed it, 17 minutes). It is stopped, killed past the
// grace, and fails the run, named.
void Supervisor::stop_overdue_lockstep_peers() {
  if (!first_end_ || stopping_) return;
  const double limit = g_.transport.end_timeout_s + kEndSlack_s;
  if (std::chrono::duration<double>(Clock::now() - first_end_->second).count() < limit) return;
  for (const auto& c : children_)
    if (c.state == Child::State::running) {
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.3g s", limit);
      const std::string what = "process '" + c.name + "' did not end within " + secs + " of process '" + first_end_->first +
                               "''s end (on the sim clock the processes end together; transport.end_timeout_s)";
      say(what + ": stopped", true);
      fail(what);
    }
  stop_all(SIGINT);
}

// Until every child is done: signals acted on, children started when due, their ends handled.
void Supervisor::watch() {
  int signals_seen = 0;
  for (;;) {
    if (g_signals > signals_seen) {
      signals_seen = g_signals;
      interrupted_ = true;
      // The first signal stops the children in order; a second tells them to end now.
      if (signals_seen == 1) say("interrupted: stopping every process", true);
      stop_all(signals_seen == 1 ? SIGINT : SIGTERM);
    }
    for (auto& c : children_)
      if (c.state == Child::State::waiting && !stopping_ && Clock::now() >= c.start_at) spawn(c);
    wait_for_children();
    for (auto& c : children_) {
      if (c.state != Child::State::running) continue;
      int status = 0;
      if (waitpid(c.pid, &status, WNOHANG) == c.pid) ended(c, status);
    }
    stop_overdue_lockstep_peers();
    if (stopping_ && Clock::now() > stop_deadline_) kill_overdue();
    if (std::all_of(children_.begin(), children_.end(), [](const Child& c) { return c.state == Child::State::done; })) break;
  }
}

// Every process is accounted for: what is left of them goes, and the verdict (the exit code).
int Supervisor::conclude() {
  std::error_code ec;
  fs::remove_all(tmp_, ec);
  for (const auto& file : shm_files_) fs::remove(file, ec);
  for (const auto& c : children_)
    if (!c.runs.empty() && c.runs.back().value("result", "") == "failed" && !c.policy.may_die)
      fail("process '" + c.name + "': " + c.runs.back().value("reason", std::string("failed")));
  std::string result = "success", reason = finished_by_.value_or("every process ended");
  int rc = 0;
  if (invalid_) result = "invalid_input", reason = *invalid_, rc = 2;
  else if (failed_) result = "failed", reason = *failed_, rc = 1;
  else if (interrupted_) result = "interrupted", reason = "interrupted";  // a clean stop on a signal, as one process ends
  write_summary(result, reason);
  std::fprintf(stderr, "[brickyard] %s: %s (supervised %zu processes, wall %.3f s)\n", result.c_str(), reason.c_str(), children_.size(), elapsed());
  return rc;
}

int Supervisor::run() {
  prepare_folders();
  make_children();
  install_signal_handlers();
  std::string plan;
  for (const auto& c : children_) plan += (plan.empty() ? "" : "; ") + c.name + " (" + join(c.nodes) + ")";
  say("supervising " + std::to_string(children_.size()) + " processes: " + plan);
  watch();
  return conclude();
}

}  // namespace

int supervise(const GraphDecl& g, const SuperviseOptions& o) { return Supervisor(g, o).run(); }

}  // namespace brickyard::fw