#pragma once
// The simulated drive-by-wire: the Raptor's side of the car's CAN bus (docs/vehicle-interface.md,
// "The simulator behind the bus"). It reads the command frames the vehicle interface sends
// (rolling counters checked: a frame whose counter repeats the last is a stuck sender and does
// not count as fresh; one that skips is counted and taken), turns them back through the same maps
// (vehicle_interface/common) into the command sim.vehicle drives, and packs the reports from the
// simulated car. Like the real one it has its own safety: when the actuator commands stop coming
// for command_timeout_s, or the team's heartbeat (ct_report's counter) stops for
// heartbeat_timeout_s, it releases the throttle and brakes at timeout_brake, holding the last
// steering angle, and reports adlink_hb_lost while the heartbeat is gone. `loss` drops that
// share of the frames each way at random (seeded), a lossy bus. Framework-free.
#include "sim/common/rng.hpp"
#include "vehicle_interface/common/rolling_counter.hpp"
#include "vehicle_interface/common/vehicle_can_mapping.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace brickyard::sim {

struct SimDbwParams {
  double command_timeout_s = 0.2;        // the actuator commands
  double heartbeat_timeout_s = 0.2;      // ct_report
  double first_command_timeout_s = 2.0;  // from the first step, before any command came
  double timeout_brake = 0.6;            // the brake pedal (0..1) of its own stop, as sim.vehicle's watchdog
  // Its own stop's wheel: false, the last commanded angle held; true, centred (straight ahead).
  // The real Raptor's is not public; each fails somewhere: a held angle of a fraction of a degree
  // on a straight at 84 m/s curves into the wall within 140 m, a centred wheel in a turn runs to
  // its outside wall (docs/car-on-wires.md).
  bool centre_steering = false;
  double loss = 0;                       // share of frames lost each way
};

// What the simulated car gives the reports.
struct SimCarReading {
  double wheel_fl = 0, wheel_fr = 0, wheel_rl = 0, wheel_rr = 0;  // m/s
  double steer = 0;                                               // road-wheel angle now, rad
  double speed = 0;                                               // m/s
};

struct SimDbwCounts {
  uint64_t frames_in = 0, lost_in = 0, lost_out = 0, other_frames = 0, bad_frames = 0;
  std::array<uint64_t, 5> received{}, skips{}, repeats{};  // per command, kRaptorCommands' order
  uint64_t timeouts = 0;          // times its own stop began (commands or heartbeat)
  uint64_t heartbeat_losses = 0;  // times the heartbeat went
};

class SimDriveByWire {
 public:
  SimDriveByWire(vehicle_interface::VehicleCanMapping mapping, SimDbwParams p, uint64_t seed);

  // Frames off the bus at `now_ns` (each may be lost first).
  void receive(const std::vector<vehicle_interface::CanFrame>& frames, int64_t now_ns);
  // The command for the car now.
  motion::Command command(int64_t now_ns);
  // The report frames for the car as it is (some may be lost).
  std::vector<vehicle_interface::CanFrame> reports(const SimCarReading& car);

  const SimDbwCounts& counts() const { return counts_; }
  bool stopping() const { return stopping_; }
  bool heartbeat_lost() const { return heartbeat_lost_; }
  int engaged_gear() const { return gear_; }
  const vehicle_interface::DbwSetpoint& setpoint() const { return setpoint_; }

 private:
  bool lose() { return p_.loss > 0 && rng_.uniform() < p_.loss; }
  void take(const vehicle_interface::ReadFrame& r, int64_t now_ns);

  vehicle_interface::VehicleCanMapping mapping_;
  SimDbwParams p_;
  Rng rng_;
  vehicle_interface::DbwSetpoint setpoint_;
  std::array<vehicle_interface::CounterChecker, 5> checkers_;
  std::array<int64_t, 5> fresh_ns_;  // each command's last fresh frame (-1: none yet)
  std::array<vehicle_interface::CounterSender, vehicle_interface::kRaptorReports.size()> report_counters_;
  int64_t start_ns_ = -1;
  bool stopping_ = false, heartbeat_lost_ = false;
  motion::Command applied_;
  int gear_ = 0;
  SimDbwCounts counts_;
};

}  // namespace brickyard::sim
