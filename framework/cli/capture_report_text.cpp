#include "cli/capture_report.hpp"

#include <cinttypes>
#include <cstdio>
#include <ctime>

namespace brickyard::fw::cli {

namespace {

constexpr std::int64_t kNsPerS = 1000000000;
constexpr std::int64_t kNsPerWeek = 604800 * kNsPerS;
constexpr std::size_t kFramesListed = 10;  // text lists the first frames; --json lists them all

double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
unsigned long long u(std::uint64_t v) { return v; }

// A pcap record's time (Unix epoch) as UTC, to the microsecond.
std::string utc(std::int64_t ns) {
  const std::time_t s = static_cast<std::time_t>(ns / kNsPerS);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%06lldZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour,
                tm.tm_min, tm.tm_sec, static_cast<long long>(ns % kNsPerS / 1000));
  return text;
}

void print_head(const std::string& file, std::uint64_t bytes) {
  std::printf("file       %s (%llu bytes)\n", file.c_str(), u(bytes));
}

void print_ouster(const OusterInfo& o) {
  const drivers::OusterCounters& c = o.counters;
  std::printf("\nouster     %s, %s, %s, serial %llu (%s); lidar port %u\n", o.metadata.product_line.c_str(),
              drivers::to_string(o.metadata.profile), o.metadata.lidar_mode.c_str(), u(o.metadata.serial_number), o.metadata_path.c_str(),
              o.port);
  std::printf("packets    %llu fed, %llu decoded, %llu refused (bad size %llu, bad CRC %llu, bad packet type %llu, wrong sensor %llu, "
              "bad column %llu, late %llu)\n",
              u(c.packets), u(c.decoded), u(c.refused()), u(c.bad_size), u(c.bad_crc), u(c.bad_packet_type), u(c.wrong_sensor),
              u(c.bad_column), u(c.late));
  std::printf("columns    %llu out of order, %llu duplicate, %llu invalid\n", u(c.out_of_order), u(c.duplicate_columns),
              u(c.invalid_columns));
  std::printf("frames     %llu complete, %llu incomplete (%llu columns missing), %llu skipped\n", u(c.frames_complete),
              u(c.frames_incomplete), u(c.missing_columns), u(c.skipped_frames));
  if (!o.frames.empty()) std::printf("\n%8s  %9s  %9s\n", "frame id", "columns", "of window");
  for (std::size_t i = 0; i < o.frames.size() && i < kFramesListed; ++i)
    std::printf("%8u  %9d  %9d%s\n", o.frames[i].frame_id, o.frames[i].columns_received, o.frames[i].columns_expected,
                o.frames[i].columns_received == o.frames[i].columns_expected ? "" : "  incomplete");
  if (o.frames.size() > kFramesListed) std::printf("(%zu more: --json lists them all)\n", o.frames.size() - kFramesListed);
}

}  // namespace

void print_pcap_text(const std::string& file, std::uint64_t bytes, const PcapInfo& info) {
  const drivers::PcapCounters& c = info.counters;
  const PortTally& all = info.all;
  print_head(file, bytes);
  std::printf("format     pcap: %llu records, %llu UDP datagrams, %llu not UDP/IPv4 (skipped)\n", u(c.records), u(c.datagrams), u(c.not_udp));
  if (all.datagrams) {
    const double span = seconds(all.last_ns - all.first_ns);
    std::printf("span       %s to %s (%.6f s)\n", utc(all.first_ns).c_str(), utc(all.last_ns).c_str(), span);
    std::printf("rate       %.1f datagrams/s, %.2f Mbit/s of payload\n", rate_per_s(all),
                span > 0 ? static_cast<double>(all.bytes) * 8e-6 / span : 0.0);
  }
  std::printf("refused    %llu (truncated %llu, malformed %llu, fragments dropped %llu); fragments %llu, reassembled %llu\n", u(c.refused()),
              u(c.truncated), u(c.malformed), u(c.fragments_dropped), u(c.fragments), u(c.reassembled));
  std::printf("\n%5s  %10s  %12s  %9s\n", "port", "datagrams", "bytes", "rate Hz");
  for (const auto& [port, t] : info.ports) std::printf("%5u  %10llu  %12llu  %9.1f\n", port, u(t.datagrams), u(t.bytes), rate_per_s(t));
  if (info.ouster) print_ouster(*info.ouster);
}

void print_gnss_text(const std::string& file, std::uint64_t bytes, const GnssLogInfo& info) {
  const drivers::DecodeCounters& c = info.counters;
  const bool oem7 = info.protocol == GnssLogProtocol::novatel_oem7;
  print_head(file, bytes);
  std::printf("format     GNSS log, %s (%s)\n", oem7 ? "NovAtel OEM7" : "NMEA 0183", to_string(info.protocol));
  std::printf("messages   %llu decoded\n", u(c.decoded));
  for (const auto& [type, n] : info.messages) std::printf("  %-10s %llu\n", type.c_str(), u(n));
  std::printf("refused    %llu (bad checksum %llu, truncated %llu, oversized %llu, unknown message %llu, malformed %llu); "
              "%llu bytes skipped between messages\n",
              u(c.refused()), u(c.bad_checksum), u(c.truncated), u(c.oversized), u(c.unknown_message), u(c.malformed), u(c.skipped_bytes));
  if (c.decoded == 0) std::printf("note       nothing here decodes as an OEM7 log or an NMEA sentence\n");
  if (!info.first_ns || !info.last_ns) return;
  const std::int64_t first = *info.first_ns, last = *info.last_ns;
  if (oem7)
    std::printf("time       GPS week %lld %.3f s to week %lld %.3f s (%.3f s); %llu of %llu messages carry it\n",
                static_cast<long long>(first / kNsPerWeek), seconds(first % kNsPerWeek), static_cast<long long>(last / kNsPerWeek),
                seconds(last % kNsPerWeek), seconds(last - first), u(info.timed), u(c.decoded));
  else
    std::printf("time       UTC %02lld:%02lld:%06.3f to %.3f s later (time of day); %llu of %llu messages carry it\n",
                static_cast<long long>(first / kNsPerS / 3600 % 24), static_cast<long long>(first / kNsPerS / 60 % 60),
                seconds(first % (60 * kNsPerS)), seconds(last - first), u(info.timed), u(c.decoded));
}

}  // namespace brickyard::fw::cli
