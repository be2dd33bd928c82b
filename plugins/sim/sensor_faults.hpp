#pragma once
// Adapter shared by the simulated sensors: reads the `faults` parameter into a FaultSchedule and
// turns its errors into BadInput naming the parameter. Its windows are in the run's time (RunTime).
#include <brickyard/context.hpp>

#include "sim/common/faults.hpp"
#include "sim/run_time.hpp"

namespace brickyard::sim {

inline FaultSchedule read_faults(const Params& p, std::size_t dims, const std::vector<std::string>& allowed) {
  try {
    return FaultSchedule(p.json("faults"), dims, allowed);
  } catch (const FaultError& e) {
    throw BadInput(std::string("parameter 'faults' ") + e.what());
  }
}

}  // namespace brickyard::sim
