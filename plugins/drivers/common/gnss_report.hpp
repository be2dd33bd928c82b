#pragma once
// The other way round, for the simulator's side of the wire: a fix in the map frame as the
// BESTPOS a receiver would send (gnss_fix_values.hpp reads it back), and with the car's motion its
// BESTVEL and the SPAN INS's INSPVAX. Framework-free. Heights go out as above mean sea level with
// an undulation of 0 (the simulator has no geoid), which the reader adds back: the ellipsoidal
// height is the fix's.
#include "gnss_fix_values.hpp"
#include "gnss_time.hpp"

namespace brickyard::drivers {

// Fix type 3 goes out as NARROW_INT, 2 NARROW_FLOAT, 1 SINGLE; an invalid fix or type 0 as
// INSUFFICIENT_OBS with position type NONE. The header's time is `t` with time status FINESTEERING.
BestPos bestpos_of(const GnssFixValues& fix, const LocalDatum& datum, GpsTime t);

// The car's motion as a receiver measures it: velocity east, north, up (m/s, the map frame's axes)
// and attitude (rad: roll positive right side down, pitch positive nose up, yaw the map frame's
// heading, counter-clockwise from east).
struct MotionValues {
  double east_mps = 0, north_mps = 0, up_mps = 0;
  double roll = 0, pitch = 0, yaw = 0;
};

// The motion of a car whose state gives its body-frame velocity (vx forward, vy left, m/s), its
// heading (counter-clockwise from east) and its roll and pitch as rotations about its own x and y
// axes (so pitch positive nose down): its velocity in the map's axes, the up speed 0 (the state has
// none), pitch turned nose up.
MotionValues motion_of_car(double vx, double vy, double yaw, double roll, double pitch_about_y);

// BESTVEL: the speed over ground, its direction from true north (degrees clockwise) and the up
// speed; solution and velocity type as bestpos_of's for the fix.
BestVel bestvel_of(const GnssFixValues& fix, const MotionValues& motion, GpsTime t);

// INSPVAX: the fix's position and sigmas, the motion's velocity and attitude (azimuth clockwise
// from north, degrees), INS status SOLUTION_GOOD with position type INS_RTKFIXED, INS_RTKFLOAT
// or INS_PSRSP for fix types 3, 2, 1 (an invalid fix: INS inactive, type NONE). The velocity and
// attitude sigmas are left 0: the simulator's INS is its fixes and the car's true motion.
InsPvaX inspvax_of(const GnssFixValues& fix, const MotionValues& motion, const LocalDatum& datum, GpsTime t);

}  // namespace brickyard::drivers
