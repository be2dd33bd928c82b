#include "cli/capture_report.hpp"

#include <nlohmann/json.hpp>

#include <iostream>

namespace brickyard::fw::cli {

namespace {

using nlohmann::json;

double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

json tally(const PortTally& t) {
  return {{"datagrams", t.datagrams}, {"bytes", t.bytes}, {"first_s", seconds(t.first_ns)}, {"last_s", seconds(t.last_ns)},
          {"span_s", seconds(t.last_ns - t.first_ns)}, {"rate_hz", rate_per_s(t)}};
}

json counters(const drivers::PcapCounters& c) {
  return {{"records", c.records}, {"datagrams", c.datagrams}, {"not_udp", c.not_udp}, {"truncated", c.truncated},
          {"malformed", c.malformed}, {"fragments", c.fragments}, {"reassembled", c.reassembled},
          {"fragments_dropped", c.fragments_dropped}, {"refused", c.refused()}};
}

json counters(const drivers::OusterCounters& c) {
  return {{"packets", c.packets}, {"decoded", c.decoded}, {"bad_size", c.bad_size}, {"bad_crc", c.bad_crc},
          {"bad_packet_type", c.bad_packet_type}, {"wrong_sensor", c.wrong_sensor}, {"bad_column", c.bad_column},
          {"late", c.late}, {"out_of_order", c.out_of_order}, {"duplicate_columns", c.duplicate_columns},
          {"invalid_columns", c.invalid_columns}, {"frames_complete", c.frames_complete},
          {"frames_incomplete", c.frames_incomplete}, {"missing_columns", c.missing_columns},
          {"skipped_frames", c.skipped_frames}, {"refused", c.refused()}};
}

json counters(const drivers::DecodeCounters& c) {
  return {{"decoded", c.decoded}, {"bad_checksum", c.bad_checksum}, {"truncated", c.truncated}, {"oversized", c.oversized},
          {"unknown_message", c.unknown_message}, {"malformed", c.malformed}, {"skipped_bytes", c.skipped_bytes},
          {"refused", c.refused()}};
}

json ouster(const OusterInfo& o) {
  const drivers::OusterMetadata& m = o.metadata;
  json j = {{"metadata", o.metadata_path}, {"product_line", m.product_line}, {"profile", drivers::to_string(m.profile)},
            {"lidar_mode", m.lidar_mode}, {"serial_number", m.serial_number}, {"port", o.port}, {"counters", counters(o.counters)}};
  j["frames"] = json::array();
  for (const auto& f : o.frames)
    j["frames"].push_back({{"frame_id", f.frame_id}, {"columns_expected", f.columns_expected}, {"columns_received", f.columns_received},
                           {"complete", f.columns_expected > 0 && f.columns_received == f.columns_expected}});
  return j;
}

}  // namespace

void print_pcap_json(const std::string& file, std::uint64_t bytes, const PcapInfo& info) {
  json j = {{"file", file}, {"bytes", bytes}, {"format", "pcap"}, {"counters", counters(info.counters)}, {"udp", tally(info.all)}};
  j["ports"] = json::array();
  for (const auto& [port, t] : info.ports) {
    json p = tally(t);
    p["port"] = port;
    j["ports"].push_back(p);
  }
  if (info.ouster) j["ouster"] = ouster(*info.ouster);
  std::cout << j.dump(2) << "\n";
}

void print_gnss_json(const std::string& file, std::uint64_t bytes, const GnssLogInfo& info) {
  json j = {{"file", file}, {"bytes", bytes}, {"format", "gnss_log"}, {"protocol", to_string(info.protocol)},
            {"messages", info.messages}, {"counters", counters(info.counters)}, {"timed", info.timed}};
  // OEM7's times are GPS time (since 1980-01-06); NMEA's the UTC time of day.
  j["time"] = info.protocol == GnssLogProtocol::novatel_oem7 ? "gps" : "utc_time_of_day";
  if (info.first_ns && info.last_ns) {
    j["first_s"] = seconds(*info.first_ns);
    j["last_s"] = seconds(*info.last_ns);
    j["span_s"] = seconds(*info.last_ns - *info.first_ns);
    if (info.protocol == GnssLogProtocol::novatel_oem7) {
      constexpr std::int64_t kNsPerWeek = 604800LL * 1000000000;
      j["first_gps_week"] = *info.first_ns / kNsPerWeek;
      j["first_gps_seconds_of_week"] = seconds(*info.first_ns % kNsPerWeek);
    }
  }
  std::cout << j.dump(2) << "\n";
}

}  // namespace brickyard::fw::cli
