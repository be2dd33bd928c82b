#pragma once
// The car's side of the drive-by-wire, without the bus or the framework: the stack's commands in,
// the Raptor's reports in, and each step the frames due out — the three actuator commands, the
// gear and the team's heartbeat (ct_report), each at its own rate with its rolling counter — as
// the command watchdog allows (dbw_watchdog.hpp) and the gear shifter chooses (gear_shifter.hpp);
// race control's base_to_car_summary read and its flags looped back in ct_report (race_control.hpp).
// The plugin (vehicle_interface.raptor_dbw) moves the frames to and from a bus and the values to
// and from messages. docs/vehicle-interface.md. Framework-free; times in ns of the run's clock.
#include "dbw_watchdog.hpp"
#include "gear_shifter.hpp"
#include "path_stop.hpp"
#include "race_control.hpp"
#include "report_monitor.hpp"
#include "rolling_counter.hpp"
#include "vehicle_can_mapping.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

struct RaptorInterfaceParams {
  // Each command's rate, in kRaptorCommands' order: brake, accelerator, steering, gear, ct_report.
  std::array<double, kRaptorCommands.size()> rates_hz = {100, 100, 100, 100, 100};
  DbwWatchdogParams watchdog;
  ShiftParams shift;
  double report_timeout_s = 0.1;  // a report silent this long is named
  int ct_state = 1;               // the team's state in ct_report (the car's rules give the codes)
  int vehicle_number = 0;         // ct_report's veh_num
  RaceControlParams race_control;  // the flag codes and the heartbeat's timeout
};

struct InterfaceStep {
  std::vector<CanFrame> frames;        // due now, in kRaptorCommands' order
  std::vector<std::string> warnings;   // reports fallen silent
  std::string state_change;            // the watchdog's change, if any (with the stop's distance and time)
  std::vector<std::string> notes;      // race control's flags changed, or it is heard again
  bool race_control_changed = false;   // a base_to_car_summary read, or race control heard or lost
};

struct InterfaceCounts {
  uint64_t commands = 0;        // from the stack
  uint64_t bad_commands = 0;    // not finite: refused, not driven
  uint64_t frames_sent = 0;
  uint64_t clamped = 0;         // command values beyond what their signals carry
  uint64_t other_frames = 0;    // frames on the bus that are no report of ours
  uint64_t bad_reports = 0;     // reports too short, or with values out of their range
  uint64_t heartbeats = 0;      // ct_reports sent
  uint64_t path_stops = 0;      // stops steered along the last path
  uint64_t held_stops = 0;      // stops on the held wheel (no stop along a path, or no fresh path or estimate)
};

class RaptorInterface {
 public:
  // Without `race`, base_to_car_summary frames are other frames and the acks stay 0.
  RaptorInterface(VehicleCanMapping mapping, RaptorInterfaceParams p, std::optional<RaceControlDbc> race = std::nullopt);

  // A command from the stack: "" or why it was refused (then it does not count as a fresh command).
  std::string command(const motion::Command& c);
  // Frames read off the bus at `now_ns`: "" or, for the first few problems, what was wrong
  // (a counter that skipped, a frame too short; all are counted).
  std::vector<std::string> receive(const std::vector<CanFrame>& frames, int64_t now_ns);
  // One step: the watchdog, the gear and the frames due at `now_ns`.
  InterfaceStep step(int64_t now_ns);
  // A stop steered along the stack's last path (path_stop.hpp) instead of on the held wheel; fed
  // through path_stop().
  void stop_on_path(PathStop stop) { path_stop_.emplace(std::move(stop)); }
  PathStop* path_stop() { return path_stop_ ? &*path_stop_ : nullptr; }

  const VehicleCanMapping& mapping() const { return mapping_; }
  const DbwReports& reports() const { return reports_; }
  const ReportMonitor& monitor() const { return monitor_; }
  const DbwWatchdog& watchdog() const { return watchdog_; }
  const GearShifter& shifter() const { return shifter_; }
  const InterfaceCounts& counts() const { return counts_; }
  const DbwSetpoint& setpoint() const { return setpoint_; }
  const RaceControlMonitor& race_control() const { return race_; }
  // The car's speed from the reports heard within report_timeout_s (the wheels' mean, else the
  // powertrain's), if any.
  std::optional<double> speed(int64_t now_ns) const;

 private:
  bool fresh_report(RaptorMessage m, int64_t now_ns) const;
  // A race control frame: true when `f` was one (read into race_, its problem said).
  bool race_frame(const CanFrame& f, int64_t now_ns, const std::function<void(std::string)>& say);
  void send_due(int64_t now_ns, bool heartbeat, InterfaceStep& out);
  // While the watchdog stops the car: the path stop's wheel in place of the held one.
  void steer_stop(double now_s, int64_t now_ns, WatchdogOutput& w, std::optional<double> v);

  VehicleCanMapping mapping_;
  RaptorInterfaceParams p_;
  DbwWatchdog watchdog_;
  GearShifter shifter_;
  ReportMonitor monitor_;
  std::array<CounterSender, kRaptorCommands.size()> counters_;
  std::array<int64_t, kRaptorCommands.size()> next_due_ns_{};
  std::array<int64_t, kRaptorCommands.size()> period_ns_{};
  bool started_ = false, fresh_ = false;
  motion::Command newest_;
  DbwSetpoint setpoint_;
  DbwReports reports_;
  InterfaceCounts counts_;
  DbwState last_state_ = DbwState::waiting;
  uint64_t problems_said_ = 0;
  std::optional<RaceControlDbc> race_dbc_;
  RaceControlMonitor race_;
  std::vector<std::string> race_notes_;  // since the last step
  bool race_read_ = false;
  std::optional<PathStop> path_stop_;
};

}  // namespace brickyard::vehicle_interface
