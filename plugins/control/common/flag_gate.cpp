#include "flag_gate.hpp"

#include <algorithm>
#include <cstdio>

namespace brickyard::control {

namespace {

bool stops(TrackFlag f) { return f != TrackFlag::green && f != TrackFlag::yellow && f != TrackFlag::orange; }
bool stops(VehicleFlag f) { return f != VehicleFlag::none && f != VehicleFlag::checkered; }
bool slows(TrackFlag f) { return f == TrackFlag::yellow || f == TrackFlag::orange; }

}  // namespace

const char* race_state_name(RaceState s) {
  switch (s) {
    case RaceState::waiting: return "WAITING";
    case RaceState::racing: return "RACING";
    case RaceState::caution: return "CAUTION";
    case RaceState::finishing: return "FINISHING";
    case RaceState::stopping: return "STOPPING";
    case RaceState::finished: return "FINISHED";
  }
  return "?";
}

std::string flag_line(const FlagTransition& tr, double t) {
  char at[64];
  std::snprintf(at, sizeof at, " at t = %.3f s: ", t);
  return std::string("race control: ") + race_state_name(tr.from) + " -> " + race_state_name(tr.to) + at + tr.reason;
}

void FlagGate::flags(const FlagInput& f) {
  if (!last_ || f.t >= last_->t) last_ = f;
}

void FlagGate::speed(double t, double v) {
  if (t < speed_t_) return;
  speed_t_ = t;
  speed_ = v;
}

bool FlagGate::capped() const {
  return last_ && (state_ == RaceState::caution || (state_ == RaceState::finishing && slows(last_->track)));
}

RaceState FlagGate::wanted(double t, std::string& why) {
  char text[160];
  if (state_ == RaceState::finished) return RaceState::finished;
  if (!last_ || (state_ == RaceState::waiting && !last_->heard)) {
    why = "race control not heard yet";
    return RaceState::waiting;
  }
  if (!last_->heard || t - last_->t > p_.timeout_s) {
    std::snprintf(text, sizeof text, "race control lost (%s): a controlled stop at %g m/s^2",
                  last_->heard ? "no RaceControl message" : "its heartbeat stopped", p_.stop_decel_mps2);
    why = text;
    return RaceState::stopping;
  }
  const FlagInput& f = *last_;
  if (stops(f.track) || stops(f.vehicle)) {
    std::snprintf(text, sizeof text, "track flag %s, vehicle flag %s: a controlled stop at %g m/s^2", track_flag_name(f.track),
                  vehicle_flag_name(f.vehicle), p_.stop_decel_mps2);
    why = text;
    return RaceState::stopping;
  }
  if (f.vehicle == VehicleFlag::checkered) {
    if (!checkered_lap_) checkered_lap_ = f.lap;
    const bool done = f.lap != *checkered_lap_;  // race control counted the lap: it is finished
    if (done) std::snprintf(text, sizeof text, "the CHECKERED flag's lap finished (lap count %d): a controlled stop", f.lap);
    else std::snprintf(text, sizeof text, "CHECKERED at lap count %d: finishing the lap", f.lap);
    why = text;
    return done ? RaceState::finished : RaceState::finishing;
  }
  checkered_lap_.reset();  // a checkered flag withdrawn
  if (slows(f.track)) {
    std::snprintf(text, sizeof text, "track flag %s: speed capped at %.1f m/s", track_flag_name(f.track), f.target_speed);
    why = text;
    return RaceState::caution;
  }
  why = "track flag GREEN: racing";
  return RaceState::racing;
}

FlagTransition FlagGate::update(double t) {
  std::string why;
  const RaceState to = wanted(t, why);
  if (to == state_) return {};
  FlagTransition tr{true, state_, to, std::move(why)};
  state_ = to;
  return tr;
}

motion::Command FlagGate::apply(motion::Command c, double t) const {
  const bool stop = state_ == RaceState::waiting || state_ == RaceState::stopping || state_ == RaceState::finished;
  const bool speed_known = t - speed_t_ <= p_.speed_timeout_s;
  if (stop || (capped() && !speed_known)) {
    c.throttle = 0;
    c.brake = std::max(c.brake, stop_brake_);
    c.target_speed = 0;
    return c;
  }
  if (!capped()) return c;
  const double cap = last_->target_speed, over = speed_ - cap;
  if (over > 0) {
    c.throttle = 0;
    c.brake = std::max(c.brake, std::min(stop_brake_, p_.speed_gain * over));
  } else {
    c.throttle = std::min(c.throttle, p_.speed_gain * -over);
  }
  c.target_speed = std::min(c.target_speed, cap);
  return c;
}

}  // namespace brickyard::control
