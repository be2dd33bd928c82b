#include "flag_judge.hpp"

#include <cmath>
#include <cstdio>

namespace brickyard::sim {

namespace {

std::string printf_string(const char* format, auto... args) {
  char text[320];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

bool slows(vi::TrackFlag f) { return f == vi::TrackFlag::yellow || f == vi::TrackFlag::orange; }

}  // namespace

void FlagJudge::start(Goal g) {
  g.from_odo = odo_;
  goal_ = std::move(g);
}

JudgeNotice FlagJudge::met(const Goal& g) {
  const double d = odo_ - g.from_odo;
  ++judged_;
  last_distance_ = d, last_allowed_ = g.allowed;
  const std::string reached = g.stop ? std::string("stopped") : printf_string("%.1f m/s reached", g.speed);
  const bool ok = d <= g.allowed;
  return {!ok, printf_string("%s: %s after %.1f m, %s the %.1f m allowed (the car needs %.1f m at %g m/s^2)", g.what.c_str(),
                             reached.c_str(), d, ok ? "within" : "beyond", g.allowed, g.needed, p_.decel_mps2)};
}

std::vector<JudgeNotice> FlagJudge::truth(double t, double x, double y, double v) {
  (void)t;
  if (x_) odo_ += std::hypot(x - *x_, y - *y_);
  x_ = x, y_ = y, v_ = v;
  if (!goal_) return {};
  const Goal g = *goal_;
  const double d = odo_ - g.from_odo;
  if (g.stop ? v < p_.stopped_speed_mps : v <= g.speed + p_.speed_tolerance_mps) {
    goal_.reset();
    return {met(g)};
  }
  if (d <= g.allowed) return {};
  goal_.reset();
  return {{true, printf_string("%s: still %.1f m/s after the %.1f m allowed (the car needs %.1f m at %g m/s^2)", g.what.c_str(), v,
                               g.allowed, g.needed, p_.decel_mps2)}};
}

std::vector<JudgeNotice> FlagJudge::flag(double t, const FlagEntry& e) {
  std::vector<JudgeNotice> out;
  if (goal_) out.push_back({false, goal_->what + ": not judged, " + e.text + " came first"});
  goal_.reset();
  awaiting_lap_ = false;
  const double stop = v_ * v_ / (2 * p_.decel_mps2);
  Goal g;
  if (e.silent) {
    g = {printf_string("silence at %.3f s from %.2f m/s", t, v_), 0, true, 0, stop, v_ * p_.silence_allowance_s + stop * (1 + p_.stop_margin)};
  } else if (e.track == vi::TrackFlag::green && (e.vehicle == vi::VehicleFlag::none || e.vehicle == vi::VehicleFlag::checkered)) {
    if (e.vehicle == vi::VehicleFlag::checkered)
      awaiting_lap_ = true, checkered_what_ = printf_string("checkered at %.3f s", t);
    return out;
  } else if (slows(e.track) && e.vehicle != vi::VehicleFlag::black && e.vehicle != vi::VehicleFlag::purple) {
    const double vt = e.target_mph * motion::kMetresPerSecondPerMph;
    const double need = std::max(0.0, v_ * v_ - vt * vt) / (2 * p_.decel_mps2);
    g = {printf_string("%s at %.3f s from %.2f m/s", motion::track_flag_name(e.track), t, v_), vt, false, 0, need, need};
    if (e.vehicle == vi::VehicleFlag::checkered)
      awaiting_lap_ = true, checkered_what_ = printf_string("checkered at %.3f s", t);
  } else {
    g = {printf_string("%s at %.3f s from %.2f m/s", e.text.c_str(), t, v_), 0, true, 0, stop, stop * (1 + p_.stop_margin)};
  }
  start(std::move(g));
  return out;
}

std::vector<JudgeNotice> FlagJudge::lap(double t, int laps) {
  if (!awaiting_lap_) return {};  // the first lap counted since the checkered flag: the lap it ends
  awaiting_lap_ = false;
  const double stop = v_ * v_ / (2 * p_.decel_mps2);
  std::vector<JudgeNotice> out{{false, printf_string("%s: the lap finished at %.3f s (lap count %d) at %.2f m/s", checkered_what_.c_str(), t, laps, v_)}};
  if (goal_) out.push_back({false, goal_->what + ": not judged, the lap finished first"});
  start({printf_string("%s: after the line", checkered_what_.c_str()), 0, true, 0, stop, stop * (1 + p_.stop_margin)});
  return out;
}

std::vector<JudgeNotice> FlagJudge::run_ended(double t) {
  std::vector<JudgeNotice> out;
  if (goal_) out.push_back({true, printf_string("%s: never met; the run ended at %.3f s at %.2f m/s", goal_->what.c_str(), t, v_)});
  if (awaiting_lap_) out.push_back({true, printf_string("%s: the lap never finished; the run ended at %.3f s", checkered_what_.c_str(), t)});
  goal_.reset();
  awaiting_lap_ = false;
  return out;
}

}  // namespace brickyard::sim
