#pragma once
// The AV-21 as unit tests take it: from its vehicle file, as every plugin does.
#include "vehicle/vehicle.hpp"

inline brickyard::vehicle::Vehicle av21_vehicle() {
  return brickyard::vehicle::load_vehicle(BRICKYARD_SOURCE_DIR "/data/vehicles/av21.json");
}
