#pragma once
// The other way round, for the simulator's side of the wire: a fix in the map frame as the
// BESTPOS a receiver would send (gnss_fix_values.hpp reads it back). Framework-free. Heights go
// out as above mean sea level with an undulation of 0 (the simulator has no geoid), which the
// reader adds back: the ellipsoidal height is the fix's.
#include "gnss_fix_values.hpp"
#include "gnss_time.hpp"

namespace brickyard::drivers {

// Fix type 3 goes out as NARROW_INT, 2 NARROW_FLOAT, 1 SINGLE; an invalid fix or type 0 as
// INSUFFICIENT_OBS with position type NONE. The header's time is `t` with time status FINESTEERING.
BestPos bestpos_of(const GnssFixValues& fix, const LocalDatum& datum, GpsTime t);

}  // namespace brickyard::drivers
