#pragma once
// Gravity as the map's level (docs/mapping.md "Gravity's level"). The roll and pitch
// the mapper takes from the ground (scan_mapper.hpp, level_on_ground) have no reference but the
// map's first frames: the ground ahead joins the map on frames levelled on the ground behind, and
// a small bias a frame adds up (IMS: the roll and the pitch about half a degree off within a lap,
// the height metres; docs/mapping.md). The accelerometer has the reference. Its specific
// force is the tyres' and the air's alone, so in the vehicle frame
//   f_y = v omega_z + dvy/dt + g sin(roll) cos(pitch)   and   f_x = dv/dt - g sin(pitch)
// (pitch nose-down positive). The sideslip's rate dvy/dt is degrees' worth from one sample to the
// next but integrates to the sideslip velocity's change, so over seconds it averages out; the
// mean of dv/dt over a window is the speed's change over it. Only the drift is taken from
// gravity: the mean of the mapper's attitude less gravity's over the same window (a bank ramps
// by 3.5 deg/s on IMS: a lagging mean of gravity's roll alone would be degrees behind; the
// difference of two means over the same times is not).
#include <cstdint>
#include <deque>

namespace brickyard::mapping {

constexpr double kGravity = 9.81;  // m/s^2, the simulator's and the fusion's

struct Tilt {
  double roll = 0, pitch = 0;  // rad
};

class GravityTilt {
 public:
  explicit GravityTilt(double window_s = 4.0) : window_ns_(static_cast<std::int64_t>(window_s * 1e9)) {}

  // One IMU sample (vehicle frame, m/s^2 and rad/s) with the car's speed then (m/s).
  void add_imu(std::int64_t t_ns, double f_x, double f_y, double yaw_rate, double speed);
  // A frame's attitude, as it joined the map.
  void add_frame(std::int64_t t_ns, double roll, double pitch);
  // The attitude's drift over the last window: its mean less gravity's. False until a whole
  // window of both is in, or while the car is slower than min_speed (m/s) in it (the start: the
  // speed's estimate still settling).
  bool drift(Tilt& out, double min_speed = 5.0) const;
  // What to turn out of the frame at `t_ns`: the part of the drift the time since the last call
  // asks for, all of it over about level_time_s (the drift is a window's mean, half a window
  // behind: a correction much faster than that overshoots). False, and zero, without a drift or on
  // the first call.
  bool correction(std::int64_t t_ns, double level_time_s, Tilt& out);

 private:
  struct Imu {
    std::int64_t t;
    double f_x, lateral, speed;  // lateral: f_y - v omega_z
  };
  struct Frame {
    std::int64_t t;
    double roll, pitch;
  };
  void trim(std::int64_t now);
  std::int64_t window_ns_;
  std::deque<Imu> imu_;
  std::deque<Frame> frames_;
  std::int64_t last_correction_ = -1;  // ns; none yet
};

}  // namespace brickyard::mapping
