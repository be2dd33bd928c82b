#pragma once
// What a run says and leaves when a plugin takes its process down (docs/reliability.md):
// a segmentation fault, abort(), a bus or arithmetic fault, or exit() from a step. The process
// cannot go on, but it does not die mute: a signal handler (async-signal-safe: write(2) and
// preformatted text only) prints which node was running and in which phase, writes a minimal
// summary.json when the run has an --out folder (marked "forced_exit": true, which a supervisor
// reads: such a process did not stop cleanly), removes the process's Fast DDS shared-memory
// files (a process killed by a signal leaves its segment in /dev/shm), and ends with exit code 1.
// The recording keeps what it wrote up to the last second (docs/recording.md).
//
// The same for a run that does not stop: after SIGINT or SIGTERM the run has 2 s to end; a node
// stuck in a step past that, or a second signal, forces the exit (code 130), naming the node. A
// run that reached its end on its own has 2 s too (Ending), then fails (code 1) naming it.
#include <string>

namespace brickyard::fw::crash_guard {

// What each thread of a supervised process is running, as text in a file mapped shared
// (BRICKYARD_BLACKBOX): read by the supervisor when the process died without a word (SIGKILL).
struct BlackBox {
  struct Slot {
    char node[64];
    char phase[16];
  };
  Slot slots[64];
};

// Installs the handlers (once per process) and arms the exit() trap for the run. summary_path:
// where a dead run's summary goes, or empty.
void install(const std::string& summary_path);
// Where a dead run's summary goes, before the run is armed (while plugin libraries load); its
// folder is made by the handler if need be.
void set_summary_path(const std::string& summary_path);
// Before the transport is made: what /dev/shm holds; right after: the files this process has
// mapped that were not there, its own, to remove on a crash.
void snapshot_shared_memory();
void note_shared_memory();
// Disarms the exit() trap and the interrupt watchdog: the run has ended normally.
void run_ended();
// While the run's threads are told to stop and joined after it reached its end on its own (its
// duration, a node's stop): past 2 s, a node stuck in a step forces the exit (code 1, failed),
// naming the node; else a hung step would keep a finished run alive for ever, saying nothing.
class Ending {
 public:
  Ending();
  ~Ending();
  Ending(const Ending&) = delete;
  Ending& operator=(const Ending&) = delete;
};
// The first SIGINT/SIGTERM: from now on the run has 2 s; a second one forces the exit at once.
void interrupted();

// Which plugin library this thread is opening: set around dlopen and the library's entry point,
// where the library's own load-time code (its static constructors) runs before any node exists.
// A library that crashes there, aborts or calls exit() is named, the summary written (at the
// path set_summary_path gave), and the process ends with exit code 1. Installs the handlers.
class Loading {
 public:
  explicit Loading(const std::string& library);
  ~Loading();
  Loading(const Loading&) = delete;
  Loading& operator=(const Loading&) = delete;
};

// Which node this thread is running, and in which phase (construction, configure, step, ...):
// set around every call into a plugin. hang_after_s > 0: a step still running that long cannot be
// waited for: the watchdog names it and ends the process (exit 1); one that returns late fails the
// run the ordinary way (the executive). The executive gives twice the step's deadline, at least a
// second past it (on the sim clock, for a deadline the graph did not set, kSimHang_s).
class Running {
 public:
  Running(const char* node, const char* phase, double hang_after_s = 0);
  ~Running();
  Running(const Running&) = delete;
  Running& operator=(const Running&) = delete;

 private:
  const char* node_;
  const char* phase_;
  int slot_;
};

}  // namespace brickyard::fw::crash_guard
