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
}  // namespace

BestPos bestpos_of(const GnssFixValues& fix, const LocalDatum& datum, GpsTime t) {
  BestPos m;
  m.header.framing = Oem7Framing::binary;
  m.header.time_status = TimeStatus::fine_steering;
  m.header.week = static_cast<uint16_t>(t.week);
  m.header.milliseconds = static_cast<uint32_t>(std::llround(t.seconds_of_week * 1000));
  const bool solution = fix.valid && fix.fix_type > 0;
  m.solution_status = solution ? SolutionStatus::computed : SolutionStatus::insufficient_obs;
  m.position_type = solution ? position_type_of(fix.fix_type) : PositionType::none;
  const Geodetic g = datum.to_geodetic(Eigen::Vector3d(fix.x, fix.y, fix.z));
  m.latitude_deg = g.latitude_deg, m.longitude_deg = g.longitude_deg;
  m.height_msl_m = g.height_m, m.undulation_m = 0;
  m.latitude_sigma_m = static_cast<float>(fix.sigma_y);
  m.longitude_sigma_m = static_cast<float>(fix.sigma_x);
  m.height_sigma_m = static_cast<float>(fix.sigma_z);
  return m;
}

}  // namespace brickyard::drivers
