#pragma once
// How busy a steering command is: the RMS of its rate between successive commands. A tracker
// that holds the line at speed moves the wheel slowly; one near the edge of stability oscillates
// and this grows many times over (docs/control.md). Framework-free.
#include <cmath>

namespace brickyard::control {

class SteeringActivity {
 public:
  // A command's steering (rad) at time t (s); commands out of order or at the same time are skipped.
  void add(double t, double steer) {
    if (seen_ && t > t_) {
      const double rate = (steer - steer_) / (t - t_);
      sum_sq_ += rate * rate * (t - t_);
      span_ += t - t_;
    }
    if (!seen_ || t > t_) t_ = t, steer_ = steer, seen_ = true;
  }
  // rad/s, weighted by time; 0 before two commands.
  double rate_rms() const { return span_ > 0 ? std::sqrt(sum_sq_ / span_) : 0.0; }

 private:
  bool seen_ = false;
  double t_ = 0, steer_ = 0, sum_sq_ = 0, span_ = 0;
};

}  // namespace brickyard::control
