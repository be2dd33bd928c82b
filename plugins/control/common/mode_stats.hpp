#pragma once
// The system manager's record of its modes for the run's summary, framework-free: the transitions
// (and the reason of the last), how often each mode was entered and how long it held.
#include "system_manager.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::control {

// The log line of a transition at time t (s).
std::string transition_line(const Transition& tr, double t);

class ModeStats {
 public:
  // One step at t: the transition SystemManager::update returned and the mode after it; the time
  // since the step before counts for that mode. Returns whether the mode is to be told (a
  // transition, or the first step).
  bool step(double t, const Transition& tr, Mode mode);
  std::uint64_t transitions() const { return transitions_; }
  std::uint64_t entered(Mode m) const { return entered_[static_cast<int>(m)]; }
  double time_in(Mode m) const { return time_in_[static_cast<int>(m)]; }
  const std::string& reason() const { return reason_; }  // the last transition's; empty before one
  // The summary's metrics: transitions, then entered_<MODE> and time_s_<MODE> for each mode.
  std::vector<std::pair<std::string, double>> metrics() const;

 private:
  std::uint64_t transitions_ = 0, entered_[3] = {0, 0, 0};
  double time_in_[3] = {0, 0, 0}, last_t_ = -1;
  std::string reason_;
};

}  // namespace brickyard::control
