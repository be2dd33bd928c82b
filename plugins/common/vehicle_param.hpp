#pragma once
// The `vehicle` parameter of every plugin that needs the car's facts: the vehicle description
// file (libs/vehicle), found like any data file and loaded in configure. Plugin-side (SDK), shared
// by the adapters of several areas; the algorithms take the loaded vehicle::Vehicle.
#include <brickyard/plugin.hpp>

#include "vehicle/vehicle.hpp"

#include <string>

namespace brickyard::plugins {

// The one default car; a settings struct initialises its vehicle file member with it.
inline constexpr const char* default_vehicle_file = "vehicles/av21.json";

// Binds `vehicle` to the std::string member at `path` (initialised to default_vehicle_file).
template <class S, class... M> ParamSpec& bind_vehicle(ParamBinding<S>& b, M... path) {
  return b.bind("vehicle", path...).doc("the car's description file (data/vehicles/)");
}

// Loads the file a `vehicle` parameter names. Throws BadInput naming the parameter and the file
// (and the JSON pointer) when it cannot be read.
inline vehicle::Vehicle read_vehicle(Context& ctx, const std::string& file) {
  const std::string path = ctx.find_file(file);
  try {
    return vehicle::load_vehicle(path);
  } catch (const vehicle::VehicleFileError& e) {
    throw BadInput(std::string("parameter 'vehicle': ") + e.what());
  }
}

}  // namespace brickyard::plugins
