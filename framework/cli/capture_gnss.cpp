#include "cli/capture_gnss.hpp"

#include "drivers/common/nmea0183.hpp"
#include "drivers/common/novatel_oem7.hpp"

#include <cmath>
#include <iterator>
#include <variant>

namespace brickyard::fw::cli {

namespace {

namespace dr = brickyard::drivers;

constexpr std::int64_t kNsPerMs = 1000000;
constexpr std::int64_t kNsPerDay = 86400LL * 1000000000;

struct Described {
  std::string type;
  std::optional<std::int64_t> time_ns;
};

// NMEA carries the time of day only: a time more than half a day before the last one is the
// next day's (the log went past midnight).
struct DayCount {
  std::optional<std::int64_t> last_ns;
  std::int64_t days_ns = 0;
  std::int64_t operator()(std::int64_t time_of_day_ns) {
    if (last_ns && time_of_day_ns + days_ns < *last_ns - kNsPerDay / 2) days_ns += kNsPerDay;
    last_ns = time_of_day_ns + days_ns;
    return *last_ns;
  }
};

Described describe(const dr::Oem7Message& m, DayCount&) {
  static const char* const kNames[] = {"BESTPOS", "BESTVEL", "INSPVAX", "RAWIMUSX"};  // Oem7Message's order
  const dr::Oem7Header& h = std::visit([](const auto& log) -> const dr::Oem7Header& { return log.header; }, m);
  const bool ascii = h.framing == dr::Oem7Framing::ascii || h.framing == dr::Oem7Framing::ascii_short;
  const bool short_header = h.framing == dr::Oem7Framing::binary_short || h.framing == dr::Oem7Framing::ascii_short;
  Described d{std::string(kNames[m.index()]) + (ascii ? "A" : "B"), std::nullopt};
  // Week and milliseconds mean nothing while the time status is UNKNOWN (a short header has no
  // status: its week says whether the receiver knew the time).
  if (h.week != 0 && (short_header || h.time_status != dr::TimeStatus::unknown))
    d.time_ns = (static_cast<std::int64_t>(h.week) * 604800000 + h.milliseconds) * kNsPerMs;
  return d;
}

Described describe(const dr::NmeaMessage& m, DayCount& days) {
  static const char* const kTypes[] = {"GGA", "RMC", "VTG", "GST"};  // NmeaMessage's order
  static_assert(std::size(kTypes) == std::variant_size_v<dr::NmeaMessage>);
  Described d{std::visit([](const auto& s) { return s.talker; }, m) + kTypes[m.index()], std::nullopt};
  std::optional<dr::NmeaTime> utc;
  if (const auto* gga = std::get_if<dr::NmeaGga>(&m)) utc = gga->utc;
  if (const auto* rmc = std::get_if<dr::NmeaRmc>(&m)) utc = rmc->utc;
  if (const auto* gst = std::get_if<dr::NmeaGst>(&m)) utc = gst->utc;
  if (utc) d.time_ns = days((utc->hours * 3600LL + utc->minutes * 60LL) * 1000000000 + std::llround(utc->seconds * 1e9));
  return d;
}

void take(GnssLogInfo& out, const Described& d, std::size_t end, bool with_chunks) {
  ++out.messages[d.type];
  if (d.time_ns) {
    ++out.timed;
    if (!out.first_ns || *d.time_ns < *out.first_ns) out.first_ns = d.time_ns;
    if (!out.last_ns || *d.time_ns > *out.last_ns) out.last_ns = d.time_ns;
  }
  if (with_chunks) out.chunks.push_back({end, d.time_ns});
}

// Fed one byte at a time when the chunks are wanted: a message is handed out on its last byte,
// so where it ends is known exactly.
template <class Decoder>
GnssLogInfo decode_with(std::span<const std::uint8_t> bytes, GnssLogProtocol protocol, bool with_chunks) {
  Decoder decoder;
  DayCount days;
  GnssLogInfo out;
  out.protocol = protocol;
  auto drain = [&](std::size_t end) {
    while (auto m = decoder.next()) take(out, describe(*m, days), end, with_chunks);
  };
  if (with_chunks) {
    for (std::size_t i = 0; i < bytes.size(); ++i) decoder.feed(&bytes[i], 1), drain(i + 1);
  } else {
    decoder.feed(bytes.data(), bytes.size());
  }
  decoder.finish();
  drain(bytes.size());
  if (with_chunks && (out.chunks.empty() ? !bytes.empty() : out.chunks.back().end < bytes.size()))
    out.chunks.push_back({bytes.size(), std::nullopt, false});
  out.counters = decoder.counters();
  return out;
}

}  // namespace

const char* to_string(GnssLogProtocol p) { return p == GnssLogProtocol::novatel_oem7 ? "novatel_oem7" : "nmea0183"; }

GnssLogInfo decode_gnss_log(std::span<const std::uint8_t> bytes, bool with_chunks) {
  GnssLogInfo oem7 = decode_with<dr::NovatelOem7Decoder>(bytes, GnssLogProtocol::novatel_oem7, false);
  GnssLogProtocol protocol = GnssLogProtocol::novatel_oem7;
  if (oem7.counters.decoded == 0) {
    // Neither decodes anything (a hostile log): the one that recognised its framing and refused it.
    const GnssLogInfo nmea = decode_with<dr::Nmea0183Decoder>(bytes, GnssLogProtocol::nmea0183, false);
    if (nmea.counters.decoded > 0 || nmea.counters.refused() > oem7.counters.refused()) {
      if (!with_chunks) return nmea;
      protocol = GnssLogProtocol::nmea0183;
    }
  }
  if (!with_chunks) return oem7;
  return protocol == GnssLogProtocol::novatel_oem7 ? decode_with<dr::NovatelOem7Decoder>(bytes, protocol, true)
                                                   : decode_with<dr::Nmea0183Decoder>(bytes, protocol, true);
}

}  // namespace brickyard::fw::cli
