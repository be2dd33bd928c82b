#include "mode_stats.hpp"

namespace brickyard::control {

std::string transition_line(const Transition& tr, double t) {
  return std::string(mode_name(tr.from)) + " -> " + mode_name(tr.to) + " at t = " + std::to_string(t) + " s: " + tr.reason;
}

bool ModeStats::step(double t, const Transition& tr, Mode mode) {
  if (tr.happened) {
    ++transitions_;
    ++entered_[static_cast<int>(tr.to)];
    reason_ = tr.reason;
  }
  const bool tell = tr.happened || last_t_ < 0;
  time_in_[static_cast<int>(mode)] += last_t_ < 0 ? 0.0 : t - last_t_;
  last_t_ = t;
  return tell;
}

std::vector<std::pair<std::string, double>> ModeStats::metrics() const {
  std::vector<std::pair<std::string, double>> m = {{"transitions", static_cast<double>(transitions_)}};
  for (Mode mode : {Mode::path, Mode::wall, Mode::safe_stop}) {
    m.emplace_back(std::string("entered_") + mode_name(mode), static_cast<double>(entered(mode)));
    m.emplace_back(std::string("time_s_") + mode_name(mode), time_in(mode));
  }
  return m;
}

}  // namespace brickyard::control
