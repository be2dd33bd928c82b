#include "system_manager.hpp"

#include <algorithm>
#include <cstdio>

namespace brickyard::control {

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::path: return "PATH";
    case Mode::wall: return "WALL_FOLLOW";
    case Mode::safe_stop: return "SAFE_STOP";
  }
  return "?";
}

void SystemManager::status(double t, LocStatus s) {
  // A status good enough to resume at holds from its first report after a worse one, or a silence.
  // The run's first such status hands the car over at once: a car held for want of its first
  // status (the stack started before its sensors) has lost nothing to recover from, as a stack
  // whose status comes from its first step drives at once.
  const bool silent = have_status_ && t - status_t_ > p_.status_timeout_s;
  if (s <= p_.resume_at && (!have_status_ || status_ > p_.resume_at || silent))
    normal_since_ = was_resumable_ ? t : t - p_.recover_after_s;
  was_resumable_ = was_resumable_ || s <= p_.resume_at;
  status_ = s;
  status_t_ = t;
  have_status_ = true;
}

void SystemManager::wall(double t, bool valid) {
  if (!valid) {
    wall_valid_since_ = 1e300;
    return;
  }
  // A run of valid walls starts again after an invalid one or a silence.
  if (wall_valid_since_ > t || t - wall_valid_t_ > p_.wall_timeout_s) wall_valid_since_ = t;
  wall_valid_t_ = t;
}

void SystemManager::path_command(double t) { path_cmd_t_ = std::max(path_cmd_t_, t); }
void SystemManager::wall_command(double t) { wall_cmd_t_ = std::max(wall_cmd_t_, t); }

void SystemManager::vehicle(double t, const VehicleHealth& h) {
  const bool well = !h.stopping && !h.handed_over && !h.steering_silent && !h.brake_silent;
  const bool was_well = vehicle_t_ > -1e299 && t - vehicle_t_ <= p_.vehicle_timeout_s && vehicle_fault(t).empty();
  // Until the car's side has once been well for recover_after_s it is still starting (the
  // drive-by-wire's reports not all heard yet): its first good status then hands the car over at
  // once, as the first NORMAL does; a car side that falls ill after that holds the full time.
  if (well && !was_well) well_run_since_ = t, vehicle_well_since_ = vehicle_started_ ? t : t - p_.recover_after_s;
  if (!well) well_run_since_ = vehicle_well_since_ = 1e300;
  vehicle_started_ = vehicle_started_ || (well && t - well_run_since_ >= p_.recover_after_s);
  handed_over_ = handed_over_ || h.handed_over;
  vehicle_ = h;
  vehicle_t_ = t;
}

std::string SystemManager::vehicle_fault(double t) const {
  if (!watch_vehicle_) return "";
  if (handed_over_) return "the vehicle interface handed the car to the drive-by-wire";
  const double last = vehicle_t_ > -1e299 ? vehicle_t_ : start_t_;
  if (t - last > p_.vehicle_timeout_s) {
    char b[96];
    std::snprintf(b, sizeof b, "the vehicle interface silent: no status for %.2f s", t - last);
    return b;
  }
  if (vehicle_.stopping) return "the vehicle interface is stopping the car: the commands do not reach it";
  if (vehicle_.steering_silent) return "the drive-by-wire's steering report silent: whether the car steers is not known";
  if (vehicle_.brake_silent) return "the drive-by-wire's brake report silent: whether the car brakes is not known";
  return "";
}

Transition SystemManager::go(Mode to, std::string reason) {
  Transition tr{true, mode_, to, std::move(reason)};
  mode_ = to;
  stopped_for_car_ = false;
  return tr;
}

Transition SystemManager::update(double t) {
  const bool stale = t - (have_status_ ? status_t_ : start_t_) > p_.status_timeout_s;
  const bool emergency = stale || status_ == LocStatus::emergency;
  const bool wall_ok = t - wall_valid_t_ <= p_.wall_timeout_s;
  // A controller is silent once its commands have come and then stopped for controller_timeout_s.
  auto silent = [&](double last) { return last > -1e299 && t - last > p_.controller_timeout_s; };
  const bool path_silent = silent(path_cmd_t_), wall_silent = silent(wall_cmd_t_);
  const std::string car_fault = vehicle_fault(t);
  const bool car_well = !watch_vehicle_ || (car_fault.empty() && t - vehicle_well_since_ >= p_.recover_after_s);
  const bool recovered = !stale && status_ <= p_.resume_at && t - normal_since_ >= p_.recover_after_s && !path_silent && car_well;
  if (!car_fault.empty() && mode_ != Mode::safe_stop) {
    Transition tr = go(Mode::safe_stop, car_fault);
    stopped_for_car_ = true;
    return tr;
  }
  const char* back = status_ == LocStatus::normal ? "localization NORMAL again: back to the path"
                                                  : "localization corrected again (WARNING): back to the path";
  switch (mode_) {
    case Mode::path:
      if (path_silent)
        return wall_ok && !wall_silent ? go(Mode::wall, "the path tracker's commands stopped: following the wall")
                                       : go(Mode::safe_stop, "the path tracker's commands stopped and no wall to follow");
      if (emergency)
        return wall_ok ? go(Mode::wall, stale ? "no localization status: following the wall" : "localization EMERGENCY: following the wall")
                       : go(Mode::safe_stop, stale ? "no localization status and no valid wall" : "localization EMERGENCY and no valid wall");
      break;
    case Mode::wall:
      if (recovered) return go(Mode::path, back);
      if (!wall_ok) return go(Mode::safe_stop, "wall estimate lost while following it");
      if (wall_silent) return go(Mode::safe_stop, "the wall follower's commands stopped");
      break;
    case Mode::safe_stop:
      if (recovered) return go(Mode::path, stopped_for_car_ ? "the car's side well again: back to the path" : back);
      if (p_.resume_on_wall && car_well && wall_ok && t - wall_valid_since_ >= p_.wall_resume_s && !wall_silent && wall_cmd_t_ > -1e299)
        return go(Mode::wall, "a valid wall again while localization is not back: following it");
      break;
  }
  return {};
}

Pedals cautious(const Pedals& wall, const Pedals& path, bool path_fresh) {
  if (!path_fresh) return wall;
  // The pedals that slow the car more (or speed it up less), not those of the lower target: each
  // law's pedals are worked out for its own line, and the lower target may brake the less.
  Pedals p = path.throttle - path.brake < wall.throttle - wall.brake ? path : wall;
  p.target_speed = std::min(wall.target_speed, path.target_speed);
  return p;
}

}  // namespace brickyard::control
