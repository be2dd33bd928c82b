#include "gnss_stream.hpp"

#include <type_traits>
#include <variant>

namespace brickyard::drivers {

GnssStream::GnssStream(const GnssStreamParams& p) : p_(p), datum_(p.datum) {}

const DecodeCounters& GnssStream::decoder() const {
  return p_.protocol == GnssProtocol::novatel_oem7 ? oem7_.counters() : nmea_.counters();
}

void GnssStream::feed(const uint8_t* data, size_t size) {
  if (p_.protocol == GnssProtocol::novatel_oem7) oem7_.feed(data, size);
  else nmea_.feed(data, size);
  drain();
}

void GnssStream::finish() {
  if (p_.protocol == GnssProtocol::novatel_oem7) oem7_.finish();
  else nmea_.finish();
  drain();
}

std::optional<GnssFixValues> GnssStream::next() {
  if (ready_.empty()) return std::nullopt;
  GnssFixValues f = ready_.front();
  ready_.pop_front();
  return f;
}

std::optional<ImuValues> GnssStream::next_imu() {
  if (imu_ready_.empty()) return std::nullopt;
  ImuValues v = imu_ready_.front();
  imu_ready_.pop_front();
  return v;
}

void GnssStream::drain() {
  if (p_.protocol == GnssProtocol::novatel_oem7)
    while (auto m = oem7_.next()) take(*m);
  else
    while (auto m = nmea_.next()) take(*m);
}

void GnssStream::keep(const std::optional<GnssFixValues>& f) {
  if (!f) {
    ++counters_.unusable;
    return;
  }
  ++counters_.fixes;
  counters_.invalid += !f->valid;
  ready_.push_back(*f);
}

void GnssStream::take(const Oem7Message& m) {
  if (const auto* pos = std::get_if<BestPos>(&m); pos && p_.position_log == Oem7PositionLog::bestpos) {
    if (pos->datum_id != kDatumWgs84) ++counters_.other_datum;
    else keep(fix_from(*pos, datum_));
  } else if (const auto* ins = std::get_if<InsPvaX>(&m); ins && p_.position_log == Oem7PositionLog::inspvax) {
    keep(fix_from(*ins, datum_));
  } else if (const auto* raw = std::get_if<RawImuSX>(&m)) {
    const std::optional<ImuValues> v = imu_from(*raw, p_.imu);
    if (v) imu_ready_.push_back(*v), ++counters_.imu_samples;
    else ++counters_.imu_unscaled;
  } else {
    ++counters_.other_reports;
  }
}

void GnssStream::take(const NmeaMessage& m) {
  if (const auto* gga = std::get_if<NmeaGga>(&m)) {
    std::optional<GnssFixValues> f = fix_from(*gga, datum_, p_.gga);
    if (f && gst_.apply(*gga, *f)) ++counters_.gst_sigmas;
    keep(f);
  } else if (const auto* gst = std::get_if<NmeaGst>(&m)) {
    gst_.gst(*gst);
  } else {
    ++counters_.other_reports;
  }
}

}  // namespace brickyard::drivers
