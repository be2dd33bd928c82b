#pragma once
// The localization manager: NORMAL / WARNING / EMERGENCY from the fate of each receiver's fixes.
// Framework-free.
//   WARNING   a receiver's latest fix was rejected, or it has sent none for fix_timeout_s;
//   EMERGENCY every receiver in that state for longer than emergency_after_s, unless an
//             independent witness of the pose (the map localizer's, on_witness) was taken within
//             witness_timeout_s: then WARNING, and the car keeps its path on the witness;
//   rising is immediate; falling goes one level at a time, each after recover_after_s without
//   the cause (hysteresis: one good epoch in a bad stretch does not clear the alarm).
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::estimation {

enum class Status : std::uint8_t { normal = 0, warning = 1, emergency = 2 };
const char* status_name(Status s);

struct ManagerParams {
  int receivers = 2;
  double emergency_after_s = 0.3;
  double recover_after_s = 1.0;
  double fix_timeout_s = 0.25;
  double witness_timeout_s = 0;  // s; 0: no witness keeps EMERGENCY away
};

class LocalizationManager {
 public:
  explicit LocalizationManager(ManagerParams p);
  // A fix of `receiver` at time t was accepted or rejected.
  void on_fix(int receiver, double t, bool accepted);
  // A pose of an independent witness (the map localizer's) was taken at time t.
  void on_witness(double t) { last_witness_ = t; }
  // The status at time t (call at every estimator step, t non-decreasing).
  Status update(double t);
  Status status() const { return status_; }
  const std::string& reason() const { return reason_; }

 private:
  ManagerParams p_;
  bool started_ = false;
  std::vector<double> last_fix_;
  std::vector<bool> last_ok_;
  double all_bad_since_ = -1;
  double last_witness_ = -1e300;
  double calm_since_ = -1;  // since when the cause of the current level has been gone
  Status status_ = Status::normal;
  std::string reason_;
};

}  // namespace brickyard::estimation
