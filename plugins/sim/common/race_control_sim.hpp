#pragma once
// The simulated race control (sim.race_control, docs/race-control.md): a script of flags played
// as base_to_car_summary frames at frame_hz, each with the heartbeat one more than the last (its
// 4 bits wrap), the car's laps counted from the truth's station along the track (a lap ends
// where the station falls back past the line), and silences in which no frame goes out.
// Framework-free; the plugin owns the bus.
#include "vehicle_interface/common/race_control.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::sim {

namespace vi = brickyard::vehicle_interface;

// One entry of the script: from t on, these flags (or, silent, no frame at all).
struct FlagEntry {
  double t = 0;
  bool silent = false;
  int track_code = 0, vehicle_code = 0, target_mph = 0;  // as sent
  vi::TrackFlag track = vi::TrackFlag::none;              // as the codes name them (the judge's)
  vi::VehicleFlag vehicle = vi::VehicleFlag::none;
  std::string text;  // "yellow (3), none (1), 60 mph" or "silent"
};

// A JSON list of {"t": s, "track_flag": name or code, "vehicle_flag": name or code (default
// "none"), "target_speed_mph": mph (default 0)} or {"t": s, "silent": true}, times increasing;
// names are green, yellow, red, orange / none, checkered, black, purple, sent with `codes`.
// nullopt and `error` naming the entry's pointer ("/2/track_flag: ...") when it is not one.
std::optional<std::vector<FlagEntry>> parse_flag_script(const std::string& json, const vi::FlagCodes& codes, std::string& error);

class SimRaceControl {
 public:
  SimRaceControl(std::vector<FlagEntry> script, double frame_hz, int rank);
  // The car's station along the track at t (the truth's `s`): counts its laps.
  void station(double s);
  int laps() const { return laps_; }

  struct Tick {
    std::optional<vi::RaceSummary> frame;  // a frame due now
    const FlagEntry* began = nullptr;      // the entry that took effect now: its first frame, or its silence
  };
  Tick step(int64_t now_ns);

 private:
  std::vector<FlagEntry> script_;
  int64_t period_ns_;
  int rank_;
  size_t next_ = 0;           // the next entry to take effect
  const FlagEntry* now_ = nullptr;
  bool announced_ = true;     // the entry in force has taken effect
  int64_t next_frame_ns_ = 0;
  int heartbeat_ = 0, laps_ = 0;
  std::optional<double> last_s_;
  double lap_distance_ = 0;
};

}  // namespace brickyard::sim
