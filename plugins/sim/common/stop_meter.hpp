#pragma once
// How far a car runs from the moment its stop begins until it stands: its speed integrated
// (trapezoids) over the samples that follow. The simulated drive-by-wire measures its own stop
// with it, the stop a dead stack leaves to it. Framework-free.
#include <cmath>

namespace brickyard::sim {

class StopMeter {
 public:
  explicit StopMeter(double stopped_speed_mps = 0.1) : stopped_speed_(stopped_speed_mps) {}

  // The stop begins at t (s) at this speed (m/s); a stop already measured is replaced.
  void begin(double t, double speed) {
    measuring_ = true, stood_ = false;
    t_ = t, v_ = std::abs(speed), from_speed_ = v_, distance_ = 0;
  }
  // The stop called off before the car stood (commands came back): nothing measured.
  void abandon() { measuring_ = false; }
  // The car's speed at t, after begin.
  void sample(double t, double speed) {
    if (!measuring_ || t <= t_) return;
    const double v = std::abs(speed);
    distance_ += 0.5 * (v + v_) * (t - t_);
    t_ = t, v_ = v;
    if (v < stopped_speed_) measuring_ = false, stood_ = true;
  }

  bool measuring() const { return measuring_; }
  bool stood() const { return stood_; }                // the last stop ended standing
  double from_speed_mps() const { return from_speed_; }  // its speed when it began
  double distance_m() const { return distance_; }        // how far it ran (so far, while measuring)

 private:
  double stopped_speed_;
  bool measuring_ = false, stood_ = false;
  double t_ = 0, v_ = 0, from_speed_ = 0, distance_ = 0;
};

}  // namespace brickyard::sim
