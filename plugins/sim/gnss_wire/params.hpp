#pragma once
// sim.gnss_wire's parameters (plugin.cpp), read alike at validation and in configure. Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "drivers/common/raw_imu.hpp"
#include "drivers/datum_param.hpp"
#include "drivers/io/byte_source.hpp"

#include <string>
#include <vector>

namespace brickyard::drivers {

struct Settings {
  std::string sink;
  std::vector<double> datum;
  // GPS time at the run's zero, s since 1980-01-06: week 2400 (2026-01-04). A whole number of
  // milliseconds, so the log's millisecond field carries the fix's time exactly.
  double gps_start_s = 2400 * 604800.0;
  RawImuScale imu;
  int imu_type = 0;
  bool bestvel = false, inspvax = false;  // with each fix, beside its BESTPOS
};

inline ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind_required("sink", &Settings::sink).doc("where the logs go: udp://HOST:PORT, or tcp://HOST:PORT to listen on (docs/drivers-transports.md)");
  b.bind_required("datum", &Settings::datum).range(-1000, 10000).doc("the map frame's origin: latitude, longitude (deg, WGS84), height above the ellipsoid (m)");
  b.bind("gps_start_s", &Settings::gps_start_s).in_unit("s").range(0, 1e10).doc("GPS time at the run's zero");
  b.bind("imu_accel_per_count", &Settings::imu, &RawImuScale::accel_per_count).in_unit("m/s").range(0, 1).doc("RAWIMUSX's velocity scale factor");
  b.bind("imu_gyro_per_count", &Settings::imu, &RawImuScale::gyro_per_count).in_unit("rad").range(0, 1).doc("RAWIMUSX's angle scale factor");
  b.bind("imu_rate_hz", &Settings::imu, &RawImuScale::rate_hz).in_unit("Hz").range(0, 10000).doc("the IMU's output rate");
  b.bind("imu_type", &Settings::imu_type).range(0, 255).doc("RAWIMUSX's IMU type field");
  b.bind("bestvel", &Settings::bestvel).doc("with each fix its BESTVEL too: the car's speed and track over ground (needs truth)");
  b.bind("inspvax", &Settings::inspvax).doc("with each fix the SPAN INS's INSPVAX too: the fix with the car's velocity and attitude (needs truth)");
  return b;
}

inline void check(const CheckView& v) {
  const Settings s = bindings().read(v.params());
  read_datum_param(s.datum);
  if (const ParsedSource p = parse_source(s.sink); !p.spec) throw BadInput("parameter 'sink': " + p.error);
}

}  // namespace brickyard::drivers
