#pragma once
// Plugin-side (SDK): the `dbc` and `vehicle` parameters of a plugin that speaks to the Raptor —
// the car's vehicle interface and the simulated drive-by-wire behind it — read into the one
// mapping both use, or refused naming the parameter, the file, the line and the name (exit 2).
#include <brickyard/plugin.hpp>

#include "vehicle_interface/common/vehicle_can_mapping.hpp"
#include "vehicle_param.hpp"

#include <string>

namespace brickyard::vehicle_interface {

inline constexpr const char* default_dbc_file = "vehicle_interface/CAN1-INDY-V14.dbc";

// The DBC a `dbc` parameter names, read; BadInput naming the file and the line otherwise.
// `files` finds a named file (Context, CheckView).
template <class Files> DbcDatabase load_car_dbc(const Files& files, const std::string& dbc_file) {
  const std::string dbc_path = files.find_file(dbc_file);
  DbcReadResult read = load_dbc_file(dbc_path);
  if (!read.ok()) throw BadInput("parameter 'dbc': " + (read.errors.empty() ? dbc_path : read.errors.front().text()));
  return std::move(*read.database);
}

// The mapping from the DBC `db` (read from `dbc_file`) and the vehicle file; `car` gets its car.
template <class Files>
VehicleCanMapping read_mapping(const Files& files, const DbcDatabase& db, const std::string& dbc_file, const std::string& vehicle_file,
                               vehicle::Vehicle& car) {
  std::string error;
  std::optional<RaptorDbc> dbc = RaptorDbc::make(db, dbc_file, error);
  if (!dbc) throw BadInput("parameter 'dbc': " + error);
  car = plugins::read_vehicle_file(files.find_file(vehicle_file));
  std::optional<DbwMaps> maps = dbw_maps(car, vehicle_file, error);
  if (!maps) throw BadInput("parameter 'vehicle': " + error);
  VehicleCanMapping mapping(std::move(*dbc), std::move(*maps));
  if (std::string why = mapping.capacity_problem(dbc_file); !why.empty()) throw BadInput("parameter 'dbc': " + why);
  return mapping;
}

// The same, the DBC read from the `dbc` parameter's file.
template <class Files>
VehicleCanMapping read_mapping(const Files& files, const std::string& dbc_file, const std::string& vehicle_file, vehicle::Vehicle& car) {
  return read_mapping(files, load_car_dbc(files, dbc_file), dbc_file, vehicle_file, car);
}

}  // namespace brickyard::vehicle_interface
