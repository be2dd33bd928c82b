#pragma once
// sim.vehicle's parameters, and what validation checks of them: the vehicle file, and a start on
// the road and clear of the other cars' (with `track` and `clear_of`: exit 2 before anything runs,
// naming the parameter; without `track` the start is checked once the world comes).
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"

#include "sim/common/car_on_track.hpp"
#include "sim/common/world_builder.hpp"

#include <memory>
#include <stdexcept>
#include <string>

namespace brickyard::sim {

struct VehicleSettings {
  double rate_hz = 500;  // the trigger's rate, and 1 / rate_hz the integration step
  double start_s = 0, start_d = 0, start_speed = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string track;            // the world's track file: the start checked at validation ("": once the world comes)
  std::string clear_of = "[]";  // [[s, d], ...]: the other cars' starts
  CommandWatchdogParams watchdog;
};

inline ParamBinding<VehicleSettings> vehicle_bindings() {
  ParamBinding<VehicleSettings> b;
  b.bind("rate_hz", &VehicleSettings::rate_hz).in_unit("Hz").range(100, 10000).doc("integration rate");
  b.bind("start_s", &VehicleSettings::start_s).in_unit("m").range(-1e5, 1e5).doc("start position along the centre line");
  b.bind("start_d", &VehicleSettings::start_d).in_unit("m").range(-100, 100).doc("start lateral offset, left positive");
  b.bind("start_speed", &VehicleSettings::start_speed).in_unit("m/s").range(0, 200);
  plugins::bind_vehicle(b, &VehicleSettings::vehicle);
  b.bind("track", &VehicleSettings::track)
      .doc("the world's track file (its sim.world's `track`): a start off the road is refused at validation; empty: at the first step, once the world comes");
  b.bind_json("clear_of", &VehicleSettings::clear_of)
      .doc("[[s, d], ...]: the other cars' starts (the same car); a start inside one is refused at validation");
  using W = CommandWatchdogParams;
  b.bind("command_timeout", &VehicleSettings::watchdog, &W::timeout_s).in_unit("s").range(0.01, 3600)
      .doc("commands stale this long (once they have come): throttle off, brake to a stop (the command watchdog)");
  b.bind("first_command_timeout", &VehicleSettings::watchdog, &W::first_timeout_s).in_unit("s").range(0.01, 3600)
      .doc("no command this long after the car exists: the same");
  b.bind("watchdog_brake", &VehicleSettings::watchdog, &W::brake).range(0, 1).doc("the brake pedal while the watchdog stops the car");
  return b;
}

// The road of the track file a `track` parameter names, as the world builds it (its banking and
// walls do not move the road's edges). Throws BadInput naming the parameter.
inline std::unique_ptr<Track> read_start_track(const std::string& path) {
  try {
    return std::make_unique<Track>(build_world(load_centerline_csv(path), "start check", default_bank(), WallSettings{}, "[]"));
  } catch (const TrackFileError& e) {
    throw BadInput(std::string("parameter 'track': track file ") + e.what());
  } catch (const WorldError& e) {
    throw BadInput(std::string("parameter 'track': ") + e.what());
  }
}

// The other cars' starts of `clear_of`. Throws BadInput naming the parameter and the JSON pointer.
inline std::vector<StartPlace> read_clear_of(const std::string& json_text) {
  try {
    return parse_starts(json_text);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("parameter 'clear_of': ") + e.what());
  }
}

// At validation (Manifest::check): the vehicle file; with `track`, the start on the road; a start
// inside one of `clear_of` (the track's length taken for s when known).
inline void check_start(const CheckView& v) {
  const VehicleSettings s = vehicle_bindings().read(v.params());
  const vehicle::Vehicle car = plugins::read_vehicle_file(v.find_file(s.vehicle));
  std::unique_ptr<Track> track;
  if (!s.track.empty()) track = read_start_track(v.find_file(s.track));
  if (track)
    if (const std::string off = off_the_road(*track, s.start_s, s.start_d, car.half_width); !off.empty())
      throw BadInput("parameter 'start_d': " + off);
  for (const StartPlace& other : read_clear_of(s.clear_of))
    if (const std::string in = start_inside({s.start_s, s.start_d}, other, car.front, car.rear, car.half_width, track ? track->length() : 0.0);
        !in.empty())
      throw BadInput("parameter 'start_s': " + in + " (clear_of)");
}

}  // namespace brickyard::sim
