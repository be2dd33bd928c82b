#include "exec/crash_guard.hpp"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <thread>

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

#include <dirent.h>
#include <sys/stat.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace brickyard::fw::crash_guard {

namespace {

// Everything the handlers touch is fixed-size and set up before the run: no allocation, no
// locks, nothing but write(2), open(2), unlink(2) and _exit(2) once a signal has come.
constexpr int kSlots = 64;  // threads running a plugin at once
struct Slot {
  std::atomic<const char*> node{nullptr}, phase{nullptr};
  std::atomic<long long> since_ms{0}, limit_ms{0};  // a step with a deadline: when it began, when to give up on it
};
Slot g_slots[kSlots];

// Under a supervisor (BRICKYARD_BLACKBOX names a file), each slot's node and phase are also kept
// as text in a file mapped shared: a process killed by SIGKILL cannot say what it was running,
// its supervisor reads it there (docs/reliability.md). Laid out as BlackBox in crash_guard.hpp.
BlackBox* g_box = nullptr;
void box_write(int slot, const char* node, const char* phase) {
  if (!g_box) return;
  BlackBox::Slot& b = g_box->slots[slot];
  std::snprintf(b.phase, sizeof b.phase, "%s", phase ? phase : "");
  std::snprintf(b.node, sizeof b.node, "%s", node ? node : "");
}
std::atomic<int> g_next_slot{0};
thread_local int t_slot = -1;
thread_local const char* t_node = nullptr;
thread_local const char* t_phase = nullptr;
thread_local char t_library[1024] = {0};  // the plugin library this thread is loading (Loading)

char g_summary[4096] = {0};
char g_summary_dir[4096] = {0};
std::set<std::string> g_before;  // /dev/shm before the transport (set and read outside any handler)
constexpr int kShm = 64;
char g_shm[kShm][256];
int g_shm_n = 0;
std::atomic<bool> g_armed{false};
std::atomic<int> g_signals{0};
std::atomic<long long> g_first_signal_ms{0};
std::atomic<long long> g_ended_ms{0};  // when the run reached its end (duration, or a stop) on its own

long long monotonic_ms() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);  // async-signal-safe
  return static_cast<long long>(ts.tv_sec) * 1000 + ts.tv_nsec / 1000000;
}

// A message built in a fixed buffer.
struct Text {
  char b[4096];
  std::size_t n = 0;
  Text& operator<<(const char* s) {
    for (; s && *s && n + 1 < sizeof b; ++s) b[n++] = *s;
    b[n] = '\0';
    return *this;
  }
};

const char* signal_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV (a segmentation fault)";
    case SIGBUS: return "SIGBUS (a bus error)";
    case SIGFPE: return "SIGFPE (an arithmetic fault)";
    case SIGILL: return "SIGILL (an illegal instruction)";
    case SIGABRT: return "SIGABRT (abort)";
    default: return "a fatal signal";
  }
}

// The reason on stderr and in the summary, the shared memory gone, then the exit.
[[noreturn]] void die(const Text& reason, int code) {
  Text line;
  line << "[brickyard] " << (code == 130 ? "interrupted" : "failed") << ": " << reason.b << "\n";
  (void)!write(2, line.b, line.n);
  if (g_summary[0]) {
    if (g_summary_dir[0]) mkdir(g_summary_dir, 0755);  // a crash before the run made its --out folder
    const int fd = open(g_summary, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      Text j;
      j << "{\"result\": \"" << (code == 130 ? "interrupted" : "failed") << "\", \"reason\": \"" << reason.b
        << "\", \"summary\": \"written by the crash handler: the run could not finish its own\", \"forced_exit\": true}\n";
      (void)!write(fd, j.b, j.n);
      close(fd);
    }
  }
  for (int i = 0; i < g_shm_n; ++i) unlink(g_shm[i]);
  _exit(code);
}

void on_fatal(int sig) {
  Text r;
  if (t_library[0])
    r << "plugin library " << t_library << " crashed with " << signal_name(sig) << " while it was being loaded (its load-time code)";
  else if (t_node) r << "node '" << t_node << "' crashed with " << signal_name(sig) << " in its " << (t_phase ? t_phase : "call");
  else r << "the process crashed with " << signal_name(sig) << " outside any node";
  r << "; the process ends here";
  die(r, 1);
}

void on_exit_called() {
  if (t_library[0]) {
    Text r;
    r << "plugin library " << t_library << " called exit() while it was being loaded (its load-time code); the run did not start";
    die(r, 1);
  }
  if (!g_armed.load()) return;
  Text r;
  if (t_node) r << "node '" << t_node << "' called exit() in its " << (t_phase ? t_phase : "call") << "; the run did not finish";
  else r << "exit() was called during the run; the run did not finish";
  die(r, 1);
}

// The nodes running a step right now, for a run that does not stop.
void name_running(Text& r) {
  bool any = false;
  for (auto& s : g_slots) {
    const char* node = s.node.load();
    if (!node) continue;
    r << (any ? ", " : "node '") << (any ? "'" : "") << node << "' (in its " << s.phase.load() << ")";
    any = true;
  }
  if (!any) r << "no node was running";
}

void watchdog() {
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    for (auto& slot : g_slots) {
      const long long limit = slot.limit_ms.load(), since = slot.since_ms.load();
      const char* node = slot.node.load();
      if (!g_armed.load() || limit <= 0 || !node || monotonic_ms() - since < limit) continue;
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.1f", static_cast<double>(monotonic_ms() - since) / 1000.0);
      Text r;
      const char* phase = slot.phase.load();
      const bool step = phase && std::strcmp(phase, "step") == 0;
      r << "node '" << node << "' has been in its " << (phase ? phase : "call") << " for " << secs << " s, far past "
        << (step ? "its step deadline" : "what a lifecycle call may take") << "; the process ends here";
      die(r, 1);
    }
    const long long ended = g_ended_ms.load();
    if (g_armed.load() && ended != 0 && g_first_signal_ms.load() == 0 && monotonic_ms() - ended >= 2000) {
      Text r;
      r << "the run reached its end but did not stop within 2 s: ";
      name_running(r);
      r << "; forced exit";
      die(r, 1);  // a failure, not an interruption: nobody asked it to stop early
    }
    const long long first = g_first_signal_ms.load();
    if (!g_armed.load() || first == 0 || monotonic_ms() - first < 2000) continue;
    Text r;
    r << "the run did not stop within 2 s of the signal: ";
    name_running(r);
    r << "; forced exit";
    die(r, 130);
  }
}

void install_handlers();  // the signal handlers, the exit() trap and the watchdog, once a process

}  // namespace

void set_summary_path(const std::string& summary_path) {
  std::snprintf(g_summary, sizeof g_summary, "%s", summary_path.c_str());
  const std::string dir = summary_path.empty() ? std::string() : std::filesystem::path(summary_path).parent_path().string();
  std::snprintf(g_summary_dir, sizeof g_summary_dir, "%s", dir.c_str());
}

void install(const std::string& summary_path) {
  set_summary_path(summary_path);
  g_armed = true;
  install_handlers();
}

Loading::Loading(const std::string& library) {
  install_handlers();
  std::snprintf(t_library, sizeof t_library, "%s", library.c_str());
}

Loading::~Loading() { t_library[0] = '\0'; }

namespace {

void install_handlers() {
  static bool once = false;
  if (once) return;
  once = true;
  struct sigaction sa {};
  sa.sa_handler = on_fatal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a fault inside the handler ends the process the default way
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(sig, &sa, nullptr);
  std::atexit(on_exit_called);
  std::thread(watchdog).detach();
  if (const char* file = std::getenv("BRICKYARD_BLACKBOX"); file && *file) {
    const int fd = ::open(file, O_RDWR | O_CREAT | O_TRUNC, 0600);
    if (fd >= 0 && ftruncate(fd, sizeof(BlackBox)) == 0) {
      void* p = mmap(nullptr, sizeof(BlackBox), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
      if (p != MAP_FAILED) g_box = static_cast<BlackBox*>(p);
    }
    if (fd >= 0) ::close(fd);
  }
}

}  // namespace

void snapshot_shared_memory() {
  g_before.clear();
  if (DIR* d = opendir("/dev/shm")) {
    while (dirent* e = readdir(d)) g_before.insert(std::string("/dev/shm/") + e->d_name);
    closedir(d);
  }
}

void note_shared_memory() {
  // The files under /dev/shm this process has mapped (Fast DDS's segments, port files and their
  // semaphores: it closes their descriptors once mapped, so /proc/self/maps, not fd/).
  g_shm_n = 0;
  FILE* f = std::fopen("/proc/self/maps", "r");
  if (!f) return;
  char line[512];
  while (std::fgets(line, sizeof line, f)) {
    const char* path = std::strstr(line, "/dev/shm/");
    if (!path || g_shm_n >= kShm) continue;
    char target[256];
    std::snprintf(target, sizeof target, "%s", path);
    target[std::strcspn(target, "\n")] = '\0';
    const char* deleted = std::strstr(target, " (deleted)");
    // Only what this process made (not there before its transport): a peer's segment it maps, or
    // a file of the domain's, is not its to remove.
    if (deleted || g_before.count(target)) continue;
    // Beside each Fast DDS file: its lock file (NAME_el), and for a port its semaphore.
    char el[256], sem[256];
    std::snprintf(el, sizeof el, "%s_el", target);
    const char* name = target + 9;
    sem[0] = '\0';
    if (std::strncmp(name, "fastrtps_port", 13) == 0) std::snprintf(sem, sizeof sem, "/dev/shm/sem.%s_mutex", name);
    for (const char* file : {static_cast<const char*>(target), static_cast<const char*>(el), static_cast<const char*>(sem)}) {
      if (!file[0] || g_shm_n >= kShm) continue;
      bool seen = false;
      for (int i = 0; i < g_shm_n; ++i) seen = seen || std::strcmp(g_shm[i], file) == 0;
      if (!seen) std::snprintf(g_shm[g_shm_n++], sizeof g_shm[0], "%s", file);
    }
  }
  std::fclose(f);
  // Under a supervisor, the list goes to the file it named: a process killed by SIGKILL cannot
  // remove its own files, its supervisor can (written whole, then renamed).
  if (const char* list = std::getenv("BRICKYARD_SHM_LIST"); list && *list) {
    const std::string part = std::string(list) + ".part";
    if (FILE* out = std::fopen(part.c_str(), "w")) {
      for (int i = 0; i < g_shm_n; ++i) std::fprintf(out, "%s\n", g_shm[i]);
      if (std::fclose(out) == 0) std::rename(part.c_str(), list);
    }
    // Its port files stay when it crashes: a peer still has them mapped and sends to them, and
    // the process restarted in its place opens the same ports; were they unlinked, the peer would
    // write into a file no one reads any more (a restarted process that never hears its peers).
    // The supervisor removes them once every process has ended.
    int kept = 0;
    for (int i = 0; i < g_shm_n; ++i)
      if (!std::strstr(g_shm[i], "fastrtps_port")) std::memmove(g_shm[kept++], g_shm[i], sizeof g_shm[0]);
    g_shm_n = kept;
  }
}

void run_ended() { g_armed = false; }

Ending::Ending() { g_ended_ms = monotonic_ms(); }
Ending::~Ending() { g_ended_ms = 0; }

void interrupted() {
  // Called from the signal handler: atomics and the exit path only.
  if (g_signals.fetch_add(1) == 0) {
    g_first_signal_ms = monotonic_ms();
    return;
  }
  if (!g_armed.load()) _exit(130);
  Text r;
  r << "a second signal: ";
  name_running(r);
  r << "; forced exit";
  die(r, 130);
}

Running::Running(const char* node, const char* phase, double hang_after_s) : node_(t_node), phase_(t_phase) {
  if (t_slot < 0) t_slot = g_next_slot.fetch_add(1) % kSlots;
  slot_ = t_slot;
  t_node = node;
  t_phase = phase;
  Slot& s = g_slots[slot_];
  s.limit_ms = 0;
  s.phase = phase;
  s.node = node;
  box_write(slot_, node, phase);
  if (hang_after_s > 0) {
    s.since_ms = monotonic_ms();
    s.limit_ms = static_cast<long long>(hang_after_s * 1000);
  }
}

Running::~Running() {
  t_node = node_;
  t_phase = phase_;
  Slot& s = g_slots[slot_];
  s.limit_ms = 0;
  s.node = node_;
  s.phase = phase_;
  box_write(slot_, node_, phase_);
}

}  // namespace brickyard::fw::crash_guard
