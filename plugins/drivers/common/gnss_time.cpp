#include "gnss_time.hpp"

#include <chrono>
#include <cmath>

namespace brickyard::drivers {

GpsTime gps_time_from_week_ms(uint16_t week, uint32_t milliseconds) {
  return GpsTime{week, static_cast<double>(milliseconds) / 1000.0};
}

double gps_seconds(GpsTime t) { return static_cast<double>(t.week) * kSecondsPerGpsWeek + t.seconds_of_week; }

double gps_to_unix_utc(GpsTime t, int gps_minus_utc_s) {
  // Whole seconds first, so the large epoch offset costs no precision in the fraction.
  double whole_weeks = static_cast<double>(t.week) * kSecondsPerGpsWeek;
  return static_cast<double>(kGpsEpochUnixSeconds - gps_minus_utc_s) + whole_weeks + t.seconds_of_week;
}

GpsTime unix_utc_to_gps(double unix_utc_s, int gps_minus_utc_s) {
  double since_epoch = unix_utc_s - static_cast<double>(kGpsEpochUnixSeconds - gps_minus_utc_s);
  if (!(since_epoch >= 0)) return GpsTime{};
  double week = std::floor(since_epoch / kSecondsPerGpsWeek);
  return GpsTime{static_cast<uint32_t>(week), since_epoch - week * kSecondsPerGpsWeek};
}

std::optional<double> utc_to_unix(int year, int month, int day, int hours, int minutes, double seconds) {
  using namespace std::chrono;
  year_month_day date{std::chrono::year{year}, std::chrono::month{static_cast<unsigned>(month)},
                      std::chrono::day{static_cast<unsigned>(day)}};
  if (!date.ok() || hours < 0 || hours > 23 || minutes < 0 || minutes > 59 || !(seconds >= 0 && seconds < 61))
    return std::nullopt;
  double days = static_cast<double>(sys_days(date).time_since_epoch().count());
  return days * 86400.0 + hours * 3600.0 + minutes * 60.0 + seconds;
}

}  // namespace brickyard::drivers
