#pragma once
// The `vehicle` parameter of every plugin that needs the car's facts: the vehicle description
// file (libs/vehicle), found like any data file and loaded in configure. Plugin-side (SDK), shared
// by the adapters of several areas; the algorithms take the loaded vehicle::Vehicle.
#include <brickyard/plugin.hpp>

#include "vehicle/vehicle.hpp"

#include <array>
#include <string>
#include <vector>

namespace brickyard::plugins {

// The one default car; a settings struct initialises its vehicle file member with it.
inline constexpr const char* default_vehicle_file = "vehicles/av21.json";

// Binds `vehicle` to the std::string member at `path` (initialised to default_vehicle_file).
template <class S, class... M> ParamSpec& bind_vehicle(ParamBinding<S>& b, M... path) {
  return b.bind("vehicle", path...).doc("the car's description file (data/vehicles/)");
}

// Loads the file a `vehicle` parameter names. Throws BadInput naming the parameter and the file
// (and the JSON pointer) when it cannot be read.
// `path` is where the file was found (Context::find_file, CheckView::find_file).
inline vehicle::Vehicle read_vehicle_file(const std::string& path) {
  try {
    return vehicle::load_vehicle(path);
  } catch (const vehicle::VehicleFileError& e) {
    throw BadInput(std::string("parameter 'vehicle': ") + e.what());
  }
}
inline vehicle::Vehicle read_vehicle(Context& ctx, const std::string& file) { return read_vehicle_file(ctx.find_file(file)); }

// At validation (Manifest::check), the vehicle file a plugin's settings name, read and checked as
// configure will read it: a missing or broken file is refused before anything runs, naming the
// node. `Bindings` is the plugin's bindings function, `File` its settings' vehicle member:
//   .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>)
template <auto Bindings, auto File> void check_vehicle_file(const CheckView& v) {
  read_vehicle_file(v.find_file(Bindings().read(v.params()).*File));
}

// Where a sensor sits on the car: `given` (the graph's numbers: exactly 3) or, when it is empty,
// the vehicle file's mount named `mount` — its xyz (m), or with `rpy` its roll, pitch, yaw (deg).
// Throws BadInput naming `param` (not 3 numbers) or `mount_param` (a mount the car lacks).
inline std::array<double, 3> sensor_place(const vehicle::Vehicle& car, const std::string& car_file,
                                          const std::string& mount, const std::string& mount_param,
                                          const std::vector<double>& given, const std::string& param, bool rpy = false) {
  if (given.empty()) {
    try {
      const vehicle::Mount& m = car.mount(mount);
      return rpy ? m.rpy_deg : m.xyz;
    } catch (const vehicle::VehicleFileError& e) {
      throw BadInput("parameter '" + mount_param + "': " + car_file + ": " + e.what());
    }
  }
  if (given.size() != 3)
    throw BadInput("parameter '" + param + "': needs 3 numbers " + (rpy ? "(roll, pitch, yaw)" : "(x, y, z)") + ", has " +
                   std::to_string(given.size()));
  return {given[0], given[1], given[2]};
}

}  // namespace brickyard::plugins
