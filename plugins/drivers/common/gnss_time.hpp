#pragma once
// GNSS receiver time to seconds, framework-free. OEM7 headers stamp logs in GPS time (week and
// milliseconds of week since 1980-01-06 00:00:00 UTC, a scale without leap seconds); NMEA sentences
// in UTC (time of day, and RMC's date). Turning GPS time into UTC takes the number of leap seconds
// between them, GPS - UTC: it is a parameter of every conversion here, never a hidden constant,
// because it changes whenever the IERS inserts a leap second. Its source: the GPS navigation
// message broadcasts it (delta t_LS, which receivers report, e.g. NovAtel's TIME log), and IERS
// Bulletin C announces each change. It has been 18 s since 2017-01-01 (the leap second of
// 2016-12-31 23:59:60 UTC); kGpsMinusUtc2017 names that value for callers that choose it.
// Seconds are doubles: about 0.24 us of resolution at today's Unix times.
#include <cstdint>
#include <optional>

namespace brickyard::drivers {

inline constexpr double kSecondsPerGpsWeek = 604800.0;
inline constexpr int64_t kGpsEpochUnixSeconds = 315964800;  // 1980-01-06T00:00:00Z
inline constexpr int kGpsMinusUtc2017 = 18;                 // GPS - UTC from 2017-01-01 until the next leap second

struct GpsTime {
  uint32_t week = 0;  // full week number since the GPS epoch (OEM7 does not wrap it at 1024)
  double seconds_of_week = 0;
};

// An OEM7 header's week and milliseconds.
GpsTime gps_time_from_week_ms(uint16_t week, uint32_t milliseconds);
// Seconds since the GPS epoch.
double gps_seconds(GpsTime t);
// Unix time (UTC, leap seconds excluded as POSIX counts) of a GPS time, given GPS - UTC.
double gps_to_unix_utc(GpsTime t, int gps_minus_utc_s);
// The inverse: the GPS week and seconds of a Unix (UTC) time, given GPS - UTC (week 0, second 0
// for a time before the GPS epoch, which has none).
GpsTime unix_utc_to_gps(double unix_utc_s, int gps_minus_utc_s);
// Unix time of a UTC calendar date and time of day (NMEA RMC); nothing for a date that does not
// exist. A leap second's 60th second reads as the next minute's first, as POSIX time has no room for it.
std::optional<double> utc_to_unix(int year, int month, int day, int hours, int minutes, double seconds);

}  // namespace brickyard::drivers
