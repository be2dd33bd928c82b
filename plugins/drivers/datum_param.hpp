#pragma once
// Plugin-side (SDK): a `datum` parameter, [latitude_deg, longitude_deg, height_m], read, or
// refused naming it (exit 2). The receiver's driver and the simulator's wire read it alike: the
// two ends of a GNSS wire must agree on the map frame's origin.
#include <brickyard/context.hpp>

#include "drivers/common/local_datum.hpp"

#include <string>
#include <vector>

namespace brickyard::drivers {

inline Datum read_datum_param(const std::vector<double>& numbers) {
  if (numbers.size() != 3)
    throw BadInput("parameter 'datum': " + std::to_string(numbers.size()) + " numbers, not 3 (latitude, longitude, height)");
  const Datum d{numbers[0], numbers[1], numbers[2]};
  if (const std::string why = datum_problem(d); !why.empty()) throw BadInput("parameter 'datum': " + why);
  return d;
}

}  // namespace brickyard::drivers
