#pragma once
// What a run writes to stderr while it runs: log lines and the progress line (sim time, the
// real-time factor and the nodes' status fields). On a terminal the progress line is one line
// updated in place, which a log line erases before it prints; elsewhere it is a plain line every
// few seconds. One lock orders every write, from any node's thread.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace brickyard::fw {

class Console {
 public:
  // At the start of a run. progress_s: RunOptions::progress_s (0: no line; < 0: 0.25 s on a
  // terminal, 5 s otherwise); quiet: no progress line at all.
  void start(bool quiet, double progress_s, std::chrono::steady_clock::time_point wall0);
  // A node whose status fields the line shows; lines show them in the order nodes were added.
  void add_node(const std::string& name);
  void set_status(const std::string& node, std::string_view field, std::string_view value);
  // Prints the progress line when it is due, or with last the final one (on a terminal only:
  // elsewhere the summary follows). sim_now_ns: the sim clock, when the run is on it.
  // extra: what else the line says (stale inputs), asked only when the line is printed.
  void progress(bool last, bool sim, std::int64_t sim_now_ns, const std::function<std::string()>& extra = {});
  // Calls print, which writes one line to stderr, under the lock, after erasing an open
  // progress line.
  template <class Print>
  void line(Print&& print) {
    std::lock_guard<std::mutex> l(log_m_);
    if (line_open_) { std::fputs("\r\033[K", stderr); line_open_ = false; }
    print();
  }

 private:
  std::mutex log_m_;
  // Status fields by node (in graph order), the line's timing.
  std::mutex status_m_;
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> status_;
  bool tty_ = false, line_open_ = false;
  double progress_every_s_ = 0;
  std::chrono::steady_clock::time_point wall0_, last_progress_;
};

}  // namespace brickyard::fw
