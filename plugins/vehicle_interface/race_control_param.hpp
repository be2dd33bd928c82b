#pragma once
// Plugin-side (SDK): race control's parameters, shared by the car's vehicle interface and the
// simulated race control: the flag codes on the bus (defaults: common/race_control.hpp's
// FlagCodes, docs/race-control.md) and base_to_car_summary found in the car's DBC. A problem is
// BadInput naming the parameter (exit 2).
#include <brickyard/plugin.hpp>

#include "vehicle_interface/common/race_control.hpp"
#include "vehicle_interface/mapping_param.hpp"

#include <string>

namespace brickyard::vehicle_interface {

// Binds the eight codes to the FlagCodes member at `path`.
template <class S, class... M> void bind_flag_codes(ParamBinding<S>& b, M... path) {
  using C = FlagCodes;
  const char* track = "race control's code on the bus (base_to_car_summary's track_flag) for this track flag";
  const char* car = "race control's code on the bus (base_to_car_summary's veh_flag) for this vehicle flag";
  b.bind("track_flag_red", path..., &C::red).range(0, 15).doc(track);
  b.bind("track_flag_orange", path..., &C::orange).range(0, 15).doc(track);
  b.bind("track_flag_yellow", path..., &C::yellow).range(0, 15).doc(track);
  b.bind("track_flag_green", path..., &C::green).range(0, 15).doc(track);
  b.bind("vehicle_flag_none", path..., &C::vehicle_none).range(0, 15).doc("no flag for this car (0 reads as none too)");
  b.bind("vehicle_flag_black", path..., &C::black).range(1, 15).doc(car);
  b.bind("vehicle_flag_checkered", path..., &C::checkered).range(1, 15).doc(car);
  b.bind("vehicle_flag_purple", path..., &C::purple).range(1, 15).doc(car);
}

inline void check_flag_codes(const FlagCodes& c) {
  std::string param;
  if (std::string why = flag_codes_problem(c, param); !why.empty()) throw BadInput("parameter '" + param + "': " + why);
}

// base_to_car_summary of the DBC a `dbc` parameter names.
inline RaceControlDbc read_race_control_dbc(const DbcDatabase& db, const std::string& dbc_file) {
  std::string error;
  std::optional<RaceControlDbc> rc = RaceControlDbc::make(db, dbc_file, error);
  if (!rc) throw BadInput("parameter 'dbc': " + error);
  return std::move(*rc);
}

template <class Files> RaceControlDbc read_race_control_dbc(const Files& files, const std::string& dbc_file) {
  return read_race_control_dbc(load_car_dbc(files, dbc_file), dbc_file);
}

}  // namespace brickyard::vehicle_interface
