#pragma once
// NMEA 0183 GGA, RMC, VTG and GST sentences as plain structs, framework-free. A field the receiver left
// empty (no fix yet, no differential data) is an empty optional, never a made-up zero. Angles in
// degrees (north and east positive), speeds as sent (knots, km/h), times in UTC.
#include <optional>
#include <string>
#include <variant>

namespace brickyard::drivers {

inline constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;

struct NmeaTime {  // UTC time of day
  int hours = 0, minutes = 0;
  double seconds = 0;  // may reach 60.x in a leap second
};

struct NmeaDate {  // UTC date; the sentence's two-digit year read as 1980-2079 (GPS began in 1980)
  int year = 0, month = 0, day = 0;
};

// GGA: fix data. quality: 0 no fix, 1 GNSS, 2 differential, 4 RTK fixed, 5 RTK float,
// 6 dead reckoning, 7 manual, 8 simulator, 9 SBAS (receivers' usage; NovAtel's GPGGA page).
struct NmeaGga {
  std::string talker = "GP";  // "GP" GPS, "GN" several constellations, "GL", "GA", "GB" ...
  std::optional<NmeaTime> utc;
  std::optional<double> latitude_deg, longitude_deg;
  int quality = 0;
  std::optional<int> satellites_used;
  std::optional<double> hdop;
  std::optional<double> altitude_msl_m;      // antenna above mean sea level (the geoid)
  std::optional<double> undulation_m;        // geoid above the WGS84 ellipsoid
  std::optional<double> differential_age_s;
  std::string station_id;                    // differential base station; empty without one
};

// RMC: recommended minimum data. `mode` (NMEA 2.3+) and `nav_status` (NMEA 4.1+) are 0 when the
// sentence is of an older version that lacks them.
struct NmeaRmc {
  std::string talker = "GP";
  std::optional<NmeaTime> utc;
  bool valid = false;  // status A: data valid; V: receiver warning
  std::optional<double> latitude_deg, longitude_deg;
  std::optional<double> speed_knots;
  std::optional<double> course_true_deg;
  std::optional<NmeaDate> date;
  std::optional<double> magnetic_variation_deg;  // east positive
  char mode = 0;  // A autonomous, D differential, E estimated, F float RTK, R RTK, M manual, S simulator, N not valid
  char nav_status = 0;
};

// VTG: course and speed over ground.
struct NmeaVtg {
  std::string talker = "GP";
  std::optional<double> course_true_deg, course_magnetic_deg;
  std::optional<double> speed_knots, speed_kmh;
  char mode = 0;  // as RMC's; 0 before NMEA 2.3
};

// GST: the position's error statistics, 1 sigma, metres (the receiver's own estimate of its
// solution's error; its error ellipse's axes and orientation, and each coordinate's sigma). A
// receiver may leave any field empty (u-blox sends no ellipse).
struct NmeaGst {
  std::string talker = "GP";
  std::optional<NmeaTime> utc;
  std::optional<double> range_rms_m;
  std::optional<double> semi_major_m, semi_minor_m, orientation_deg;  // the ellipse, degrees from true north
  std::optional<double> latitude_sigma_m, longitude_sigma_m, height_sigma_m;
};

using NmeaMessage = std::variant<NmeaGga, NmeaRmc, NmeaVtg, NmeaGst>;

}  // namespace brickyard::drivers
