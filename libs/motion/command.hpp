#pragma once
// What a controller asks of the car, framework-free: road-wheel angle and pedals. The control
// stack sends it; the simulated car and its ground-truth driver use the same struct.
namespace brickyard::motion {

struct Command {
  double steer = 0;         // rad, left positive
  double throttle = 0;      // 0..1
  double brake = 0;         // 0..1
  double target_speed = 0;  // m/s, what the pedals aim at
};

// Pedals from a speed error: proportional, throttle for positive, brake for negative.
inline void pedals_for(double target, double speed, double gain, Command& c) {
  const double u = gain * (target - speed);
  c.throttle = u > 0 ? (u < 1 ? u : 1) : 0;
  c.brake = u < 0 ? (-u < 1 ? -u : 1) : 0;
  c.target_speed = target;
}

}  // namespace brickyard::motion
