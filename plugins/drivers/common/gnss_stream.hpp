#pragma once
// A GNSS receiver's byte stream to fixes, framework-free: the protocol's decoder (OEM7 or NMEA
// 0183), then each position report to a fix in the map frame (gnss_fix_values.hpp). Bytes in any
// chunking; no I/O, no clock (the adapter stamps each fix: device_clock.hpp). Every report that is
// decoded but gives no fix is counted under one reason.
#include "gnss_fix_values.hpp"
#include "novatel_oem7.hpp"
#include "nmea0183.hpp"
#include "raw_imu.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string_view>

namespace brickyard::drivers {

enum class GnssProtocol { novatel_oem7, nmea0183 };
// Which OEM7 log is the position: the receiver's (BESTPOS) or the INS's (INSPVAX).
enum class Oem7PositionLog { bestpos, inspvax };

struct GnssStreamParams {
  GnssProtocol protocol = GnssProtocol::novatel_oem7;
  Oem7PositionLog position_log = Oem7PositionLog::bestpos;
  Datum datum;
  GgaSigmas gga;
  RawImuScale imu;  // RAWIMUSX's scale: unset, its samples are counted and dropped
};

struct GnssStreamCounters {
  uint64_t fixes = 0;         // fixes handed out (valid or not)
  uint64_t invalid = 0;       // of them, the receiver said not valid (no solution, INS not aligned)
  uint64_t other_datum = 0;   // BESTPOS in a datum other than WGS84: dropped
  uint64_t unusable = 0;      // a position that is not one (non-finite, out of range, GGA without HDOP)
  uint64_t other_reports = 0; // decoded reports that are not the position (BESTVEL, RMC, VTG, ...)
  uint64_t imu_samples = 0;   // RAWIMUSX samples handed out
  uint64_t imu_unscaled = 0;  // RAWIMUSX samples dropped: no scale given
  uint64_t gst_sigmas = 0;    // GGA fixes whose sigmas came from the receiver's GST (else HDOP's rule)
};

class GnssStream {
 public:
  explicit GnssStream(const GnssStreamParams& p);

  void feed(const uint8_t* data, size_t size);
  void feed(std::string_view text) { feed(reinterpret_cast<const uint8_t*>(text.data()), text.size()); }
  std::optional<GnssFixValues> next();
  std::optional<ImuValues> next_imu();
  void finish();  // the stream ended: a report cut short is counted truncated

  const GnssStreamCounters& counters() const { return counters_; }
  const DecodeCounters& decoder() const;

 private:
  void take(const Oem7Message& m);
  void take(const NmeaMessage& m);
  void drain();
  void keep(const std::optional<GnssFixValues>& f);

  GnssStreamParams p_;
  LocalDatum datum_;
  NovatelOem7Decoder oem7_;
  Nmea0183Decoder nmea_;
  GstSigmas gst_;
  std::deque<GnssFixValues> ready_;
  std::deque<ImuValues> imu_ready_;
  GnssStreamCounters counters_;
};

}  // namespace brickyard::drivers
