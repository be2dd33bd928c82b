#pragma once
// Race control on the car's CAN bus, without the bus or the framework (docs/race-control.md):
// base_to_car_summary (1200) found by name in the car's DBC and read into what race control says
// (flags, target speed, lap, rank, heartbeat); the heartbeat watched (race control heard while it
// changes, lost once it has not for timeout_s); the flags as the stack names them through the
// codes (parameters: the DBC gives none); and the codes looped back in ct_report's acks. The
// simulated race control packs the same message through the same class. Framework-free; times in
// ns of the run's clock.
#include "can_message.hpp"
#include "dbc.hpp"
#include "motion/race_flags.hpp"
#include "rolling_counter.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace brickyard::vehicle_interface {

using motion::TrackFlag;
using motion::VehicleFlag;

// The codes on the bus. The defaults are the IAC's (2021) as the teams' public code spells them
// (TrackCondition TC1_RED .. TC4_GREEN, VehicleSignal VS1_NULL, VS2_BLACK, VS4_CHECK, VS8_PURPLE);
// the car's DBC comments none of base_to_car_summary's signals. Vehicle code 0 reads as no flag too.
struct FlagCodes {
  int red = 1, orange = 2, yellow = 3, green = 4;
  int vehicle_none = 1, black = 2, checkered = 4, purple = 8;
};
// "" or why the codes cannot be told apart or carried by 4 bits ("track_flag_red": the parameter named).
std::string flag_codes_problem(const FlagCodes& c, std::string& param);
TrackFlag track_flag_for(const FlagCodes& c, int code);
VehicleFlag vehicle_flag_for(const FlagCodes& c, int code);
int track_code_of(const FlagCodes& c, TrackFlag f);      // the simulator's side; none/unknown: 0
int vehicle_code_of(const FlagCodes& c, VehicleFlag f);  // none: vehicle_none; unknown: 0

// base_to_car_summary's values.
struct RaceSummary {
  int heartbeat = 0, track_code = 0, vehicle_code = 0, rank = 0, lap = 0, lap_distance_m = 0, target_mph = 0;
};

struct RaceSummaryRead {
  RaceSummary summary;
  std::string error;  // non-empty: the frame could not be read (too short)
  std::vector<std::string> out_of_range;
};

class RaceControlDbc {
 public:
  // base_to_car_summary found in `db`, or nullopt and `error` naming `file`, the line and what is missing.
  static std::optional<RaceControlDbc> make(const DbcDatabase& db, const std::string& file, std::string& error);
  bool is_summary(const CanFrame& f) const { return f.id == message_.id && f.extended == message_.extended; }
  RaceSummaryRead read(const CanFrame& f) const;
  PackResult pack(const RaceSummary& s) const;
  uint32_t heartbeat_modulus() const { return heartbeat_modulus_; }  // 16: 4 bits, no declared range

 private:
  DbcMessage message_;
  uint32_t heartbeat_modulus_ = 16;
};

struct RaceControlParams {
  FlagCodes codes;
  double timeout_s = 1.0;  // the heartbeat unchanged this long: race control lost
};

// What the stack's RaceControl message carries.
struct RaceControlState {
  bool heard = false;
  std::optional<int64_t> heartbeat_changed_ns;  // nullopt: never heard
  RaceSummary last;                             // the last frame read
  TrackFlag track = TrackFlag::none;
  VehicleFlag vehicle = VehicleFlag::none;
  double target_speed_mps = 0;
  uint64_t frames = 0, bad_frames = 0, heartbeat_repeats = 0, heartbeat_skips = 0, losses = 0;
};

class RaceControlMonitor {
 public:
  RaceControlMonitor(RaceControlParams p, uint32_t heartbeat_modulus);
  // A frame read at now_ns: "" or what changed ("race control: track flag GREEN -> YELLOW (code 3), target 60 mph").
  std::string received(const RaceSummary& s, int64_t now_ns);
  void bad_frame() { ++state_.bad_frames; }
  // At now_ns: "" or the change of heard ("race control lost: heartbeat unchanged for 1 s", "race control heard").
  std::string check(int64_t now_ns);
  const RaceControlState& state() const { return state_; }
  double heartbeat_age_s(int64_t now_ns) const;  // -1: never heard
  // ct_report's acks: the codes last read, looped back (0 before any).
  int track_ack() const { return state_.frames ? state_.last.track_code : 0; }
  int vehicle_ack() const { return state_.frames ? state_.last.vehicle_code : 0; }

 private:
  RaceControlParams p_;
  CounterChecker heartbeat_;
  RaceControlState state_;
};

}  // namespace brickyard::vehicle_interface
