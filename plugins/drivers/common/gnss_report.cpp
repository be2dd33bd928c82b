#include "gnss_report.hpp"

#include <cmath>

namespace brickyard::drivers {

namespace {
PositionType position_type_of(uint8_t fix_type) {
  switch (fix_type) {
    case 3: return PositionType::narrow_int;
    case 2: return PositionType::narrow_float;
    case 1: return PositionType::single;
    default: return PositionType::none;
  }
}

PositionType ins_position_type_of(uint8_t fix_type) {
  switch (fix_type) {
    case 3: return PositionType::ins_rtkfixed;
    case 2: return PositionType::ins_rtkfloat;
    case 1: return PositionType::ins_psrsp;
    default: return PositionType::none;
  }
}

template <class Log> void stamp(Log& m, GpsTime t) {
  m.header.framing = Oem7Framing::binary;
  m.header.time_status = TimeStatus::fine_steering;
  m.header.week = static_cast<uint16_t>(t.week);
  m.header.milliseconds = static_cast<uint32_t>(std::llround(t.seconds_of_week * 1000));
}

bool has_solution(const GnssFixValues& fix) { return fix.valid && fix.fix_type > 0; }

// The fix's position by the datum and its sigmas, in the fields BESTPOS and INSPVAX share.
template <class Log> void place(Log& m, const GnssFixValues& fix, const LocalDatum& datum) {
  const Geodetic g = datum.to_geodetic(Eigen::Vector3d(fix.x, fix.y, fix.z));
  m.latitude_deg = g.latitude_deg, m.longitude_deg = g.longitude_deg;
  m.height_msl_m = g.height_m, m.undulation_m = 0;
  m.latitude_sigma_m = static_cast<float>(fix.sigma_y);
  m.longitude_sigma_m = static_cast<float>(fix.sigma_x);
  m.height_sigma_m = static_cast<float>(fix.sigma_z);
}

// Degrees clockwise from north in [0, 360) of a direction counter-clockwise from east (rad).
double azimuth_deg(double east_ccw_rad) {
  const double a = std::fmod(90.0 - east_ccw_rad * 180.0 / M_PI, 360.0);
  return a < 0 ? a + 360.0 : a;
}
}  // namespace

BestPos bestpos_of(const GnssFixValues& fix, const LocalDatum& datum, GpsTime t) {
  BestPos m;
  stamp(m, t);
  const bool solution = has_solution(fix);
  m.solution_status = solution ? SolutionStatus::computed : SolutionStatus::insufficient_obs;
  m.position_type = solution ? position_type_of(fix.fix_type) : PositionType::none;
  place(m, fix, datum);
  return m;
}

MotionValues motion_of_car(double vx, double vy, double yaw, double roll, double pitch_about_y) {
  MotionValues m;
  const double c = std::cos(yaw), s = std::sin(yaw);
  m.east_mps = c * vx - s * vy, m.north_mps = s * vx + c * vy;
  m.roll = roll, m.pitch = -pitch_about_y, m.yaw = yaw;
  return m;
}

BestVel bestvel_of(const GnssFixValues& fix, const MotionValues& motion, GpsTime t) {
  BestVel m;
  stamp(m, t);
  const bool solution = has_solution(fix);
  m.solution_status = solution ? SolutionStatus::computed : SolutionStatus::insufficient_obs;
  m.velocity_type = solution ? position_type_of(fix.fix_type) : PositionType::none;
  m.horizontal_speed_mps = std::hypot(motion.east_mps, motion.north_mps);
  m.track_over_ground_deg = azimuth_deg(std::atan2(motion.north_mps, motion.east_mps));
  m.vertical_speed_mps = motion.up_mps;
  return m;
}

InsPvaX inspvax_of(const GnssFixValues& fix, const MotionValues& motion, const LocalDatum& datum, GpsTime t) {
  InsPvaX m;
  stamp(m, t);
  const bool solution = has_solution(fix);
  m.ins_status = solution ? InsStatus::solution_good : InsStatus::inactive;
  m.position_type = solution ? ins_position_type_of(fix.fix_type) : PositionType::none;
  place(m, fix, datum);
  m.north_velocity_mps = motion.north_mps, m.east_velocity_mps = motion.east_mps, m.up_velocity_mps = motion.up_mps;
  m.roll_deg = motion.roll * 180.0 / M_PI, m.pitch_deg = motion.pitch * 180.0 / M_PI;
  m.azimuth_deg = azimuth_deg(motion.yaw);
  return m;
}

}  // namespace brickyard::drivers
