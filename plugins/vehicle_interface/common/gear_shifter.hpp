#pragma once
// The gear the interface commands (gear_shift_cmd), by engine speed and the vehicle file's gear
// ratios: one gear up when the engine passes `up_rpm` in the gear engaged, one down when it falls
// under `down_rpm` and the gear below would stay under `up_rpm`, at most one shift per
// `min_interval_s` (the gearbox takes time, and the reported gear lags the command). `fixed_gear`
// above 0 holds that gear. docs/vehicle-interface.md. Framework-free.
#include "dbw_maps.hpp"

#include <string>

namespace brickyard::vehicle_interface {

struct ShiftParams {
  double up_rpm = 7000;        // 500 under the AV-21's 7 500 rpm redline
  double down_rpm = 4000;      // under every upshift's landing speed (docs: the check below)
  double min_interval_s = 0.5;
  int fixed_gear = 0;          // 0: shift by rpm
};

// Why the rules cannot work on this car (`what` empty: they can), and which of the parameters is
// wrong (`param`: "fixed_gear", "shift_up_rpm", "shift_down_rpm"): a fixed gear the car lacks,
// up_rpm above the redline, or a down_rpm at or above where an upshift lands (up_rpm x the
// closest pair of ratios): the car would shift down straight after shifting up.
struct ShiftProblem {
  std::string param, what;
};
ShiftProblem shift_problem(const ShiftParams& p, const DbwMaps& m);

class GearShifter {
 public:
  GearShifter(ShiftParams p, DbwMaps m) : p_(p), m_(std::move(m)) {}

  // Every step: the time, the gear engaged (0: not known; the one commanded is taken), the engine's
  // speed in it as reported (negative: not known; it is worked out from the speed through the
  // ratios) and the car's speed. Returns the gear to command; the first is the engaged one, or the
  // starting gear for the speed.
  int update(double now_s, int engaged, double rpm, double speed_mps);
  // The gear the car at rest or at `speed_mps` starts in: the lowest whose rpm stays under up_rpm.
  int starting_gear(double speed_mps) const;
  int desired() const { return desired_; }
  int shifts() const { return shifts_; }

 private:
  ShiftParams p_;
  DbwMaps m_;
  int desired_ = 0;  // 0 until the first update
  int shifts_ = 0;
  double last_shift_s_ = -1e300;
};

}  // namespace brickyard::vehicle_interface
