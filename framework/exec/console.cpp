#include "exec/console.hpp"

#include <unistd.h>

namespace brickyard::fw {

void Console::start(bool quiet, double progress_s, std::chrono::steady_clock::time_point wall0) {
  wall0_ = last_progress_ = wall0;
  tty_ = !quiet && isatty(2);
  progress_every_s_ = quiet ? 0.0 : progress_s >= 0 ? progress_s : tty_ ? 0.25 : 5.0;
}

void Console::add_node(const std::string& name) { status_.push_back({name, {}}); }

void Console::set_status(const std::string& node, std::string_view field, std::string_view value) {
  std::lock_guard<std::mutex> l(status_m_);
  for (auto& [name, fields] : status_) {
    if (name != node) continue;
    for (auto& [f, v] : fields)
      if (f == field) { v = value; return; }
    fields.emplace_back(std::string(field), std::string(value));
    return;
  }
}

void Console::progress(bool last, bool sim, std::int64_t sim_now_ns, const std::function<std::string()>& extra) {
  if (progress_every_s_ <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (!last && now - last_progress_ < std::chrono::duration<double>(progress_every_s_)) return;
  if (last && !tty_) return;  // the summary follows
  last_progress_ = now;
  const double wall = std::chrono::duration<double>(now - wall0_).count();
  char head[96];
  if (sim) std::snprintf(head, sizeof head, "sim %.1f s (%.1fx real time)", sim_now_ns * 1e-9, wall > 0 ? sim_now_ns * 1e-9 / wall : 0.0);
  else std::snprintf(head, sizeof head, "t %.1f s", wall);
  std::string line = head;
  {
    std::lock_guard<std::mutex> l(status_m_);
    for (const auto& [node, fields] : status_)
      for (const auto& [f, v] : fields) line += " · " + f + " " + v;
  }
  if (extra)
    if (const std::string more = extra(); !more.empty()) line += " · " + more;
  std::lock_guard<std::mutex> l(log_m_);
  if (tty_) {
    std::fprintf(stderr, "\r\033[K%s%s", line.c_str(), last ? "\n" : "");
    line_open_ = !last;
  } else {
    std::fprintf(stderr, "[brickyard] progress: %s\n", line.c_str());
  }
}

}  // namespace brickyard::fw
