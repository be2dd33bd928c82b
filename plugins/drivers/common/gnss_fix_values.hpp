#pragma once
// A receiver's report to the stack's fix, framework-free: OEM7 BESTPOS and INSPVAX, NMEA GGA, each
// to a position in the map frame (local_datum.hpp) with a 1-sigma per axis and the stack's fix
// type (GnssFix: 0 none, 1 single, 2 float RTK, 3 fixed RTK). The rules, with their sources, are
// in docs/drivers-formats.md ("From a log to a fix").
#include "local_datum.hpp"
#include "nmea0183_messages.hpp"
#include "oem7_messages.hpp"

#include <cstdint>
#include <optional>

namespace brickyard::drivers {

struct GnssFixValues {
  double x = 0, y = 0, z = 0;                    // map frame, m
  double sigma_x = 0, sigma_y = 0, sigma_z = 0;  // east, north, up, m
  uint8_t fix_type = 0;
  bool valid = false;
  // When the receiver measured it, in its own time scale (GPS time since 1980-01-06 for OEM7;
  // UTC time of day for NMEA), ns, if the report says. Integer nanoseconds: a double of GPS
  // seconds (1.4e9) has steps of 0.24 us, and a stamp carried through it would miss its instant.
  std::optional<int64_t> device_time_ns;
};

// The stack's fix type of an OEM7 position type: RTK integer solutions (with or without the INS)
// 3, RTK float 2, any other solution 1 (single, differential, SBAS, PPP, propagated), none 0.
uint8_t fix_type_of(PositionType type);
// Of a GGA quality indicator: 4 fixed RTK 3, 5 float RTK 2, 1/2/6/9 (GNSS, differential, dead
// reckoning, SBAS) 1; 0 (no fix), 7 (manual input) and 8 (simulator mode) none.
uint8_t fix_type_of_gga(int quality);

// BESTPOS: its sigmas as reported (longitude's east, latitude's north). Nothing for a datum other
// than WGS84, which the map's datum is given in (the caller counts it).
std::optional<GnssFixValues> fix_from(const BestPos& m, const LocalDatum& datum);
// INSPVAX: the INS's position; valid while the INS says its solution is good (or free-running).
std::optional<GnssFixValues> fix_from(const InsPvaX& m, const LocalDatum& datum);

// GGA carries no sigma: HDOP times a user range error per quality (GgaSigmas), the height's
// twice the horizontal (no VDOP in GGA). A GGA without a position or a HDOP is not a fix.
struct GgaSigmas {
  double rtk_fixed_m = 0.02, rtk_float_m = 0.2, differential_m = 0.7, single_m = 3.0;  // per unit HDOP
};
std::optional<GnssFixValues> fix_from(const NmeaGga& m, const LocalDatum& datum, const GgaSigmas& sigmas = {});

// A receiver's own sigmas for its GGA fixes, from its GST sentences (east the longitude's, north
// the latitude's, up the height's). An epoch's GST comes beside its GGA, before it or (most
// receivers) after it: a GST of the GGA's own time serves it; one of the epoch before serves it
// when that epoch's GGA had the same fix type and is at most max_age_s older: the sigmas then
// one epoch late, never across a change of solution (an RTK fix lost takes the HDOP rule at once).
class GstSigmas {
 public:
  explicit GstSigmas(double max_age_s = 1.5) : max_age_s_(max_age_s) {}
  // Kept when it has a time and the three sigmas.
  void gst(const NmeaGst& m);
  // A GGA's fix (from fix_from): its sigmas set from a GST that serves it; whether one did.
  bool apply(const NmeaGga& gga, GnssFixValues& f);

 private:
  double max_age_s_;
  std::optional<NmeaGst> gst_;
  std::optional<double> gst_s_, last_gga_s_;  // seconds of the UTC day
  uint8_t last_gga_fix_type_ = 0;
};

}  // namespace brickyard::drivers
