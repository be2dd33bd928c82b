#pragma once
// Plugin-side (SDK): what a driver's decoding did, as the node's metrics (summary.json).
#include <brickyard/context.hpp>

#include "drivers/common/decode_counters.hpp"
#include "drivers/common/latency_spread.hpp"
#include "drivers/gnss_source.hpp"
#include "drivers/ouster_imu_source.hpp"
#include "drivers/ouster_source.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace brickyard::drivers {

inline void report_decoder(Context& ctx, const DecodeCounters& c) {
  ctx.metric("decoded", static_cast<double>(c.decoded));
  ctx.metric("bad_checksum", static_cast<double>(c.bad_checksum));
  ctx.metric("truncated", static_cast<double>(c.truncated));
  ctx.metric("oversized", static_cast<double>(c.oversized));
  ctx.metric("unknown_message", static_cast<double>(c.unknown_message));
  ctx.metric("malformed", static_cast<double>(c.malformed));
  ctx.metric("skipped_bytes", static_cast<double>(c.skipped_bytes));
}

// The median, 99th percentile and largest of `values` under `name`_p50, _p99, _max (none when empty).
inline void report_spread(Context& ctx, const std::string& name, std::vector<double> values) {
  if (values.empty()) return;
  std::sort(values.begin(), values.end());
  auto at = [&](double q) { return values[static_cast<size_t>(q * static_cast<double>(values.size() - 1))]; };
  ctx.metric(name + "_p50", at(0.5));
  ctx.metric(name + "_p99", at(0.99));
  ctx.metric(name + "_max", values.back());
}

// From a message's last bytes at the host to its publication (common/latency_spread.hpp).
inline void report_wire_latency(Context& ctx, const LatencySpread& wire) {
  if (wire.count() == 0) return;
  ctx.metric("wire_to_message_s_p50", wire.quantile_s(0.5));
  ctx.metric("wire_to_message_s_p99", wire.quantile_s(0.99));
  ctx.metric("wire_to_message_s_max", wire.max_s());
}

// A live device's failures and how often it was opened again (reopening_device.hpp).
inline void report_device(Context& ctx, const ReopeningDevice* device) {
  if (!device) return;
  ctx.metric("device_failures", static_cast<double>(device->failures()));
  ctx.metric("device_reopened", static_cast<double>(device->reopened()));
}

inline void report_gnss(Context& ctx, const GnssSource& source, uint64_t fixes, uint64_t silences, const LatencySpread& wire) {
  const GnssStreamCounters& c = source.stream().counters();
  report_decoder(ctx, source.stream().decoder());
  ctx.metric("fixes", static_cast<double>(fixes));
  ctx.metric("invalid_fixes", static_cast<double>(c.invalid));
  ctx.metric("other_datum", static_cast<double>(c.other_datum));
  ctx.metric("unusable", static_cast<double>(c.unusable));
  ctx.metric("other_reports", static_cast<double>(c.other_reports));
  ctx.metric("imu_samples", static_cast<double>(c.imu_samples));
  ctx.metric("imu_unscaled", static_cast<double>(c.imu_unscaled));
  ctx.metric("gst_sigmas", static_cast<double>(c.gst_sigmas));
  ctx.metric("bytes", static_cast<double>(source.bytes()));
  report_device(ctx, source.device());
  ctx.metric("silences", static_cast<double>(silences));
  report_spread(ctx, "stamp_delay_s", source.delays_s());
  report_wire_latency(ctx, wire);
}

inline void report_ouster(Context& ctx, const OusterSource& source, uint64_t frames, uint64_t silences, const LatencySpread& wire) {
  const OusterCounters& c = source.decoder().counters();
  const std::pair<const char*, uint64_t> counts[] = {
      {"packets", c.packets}, {"decoded_packets", c.decoded}, {"bad_size", c.bad_size}, {"bad_crc", c.bad_crc},
      {"bad_packet_type", c.bad_packet_type}, {"wrong_sensor", c.wrong_sensor}, {"bad_column", c.bad_column},
      {"late", c.late}, {"out_of_order", c.out_of_order}, {"duplicate_columns", c.duplicate_columns},
      {"frames_complete", c.frames_complete}, {"frames_incomplete", c.frames_incomplete},
      {"missing_columns", c.missing_columns}, {"skipped_frames", c.skipped_frames}};
  for (const auto& [name, value] : counts) ctx.metric(name, static_cast<double>(value));
  if (const PcapCounters* p = source.capture()) {
    ctx.metric("capture_datagrams", static_cast<double>(p->datagrams));
    ctx.metric("capture_refused", static_cast<double>(p->refused()));
  }
  ctx.metric("frames", static_cast<double>(frames));
  report_device(ctx, source.device());
  ctx.metric("silences", static_cast<double>(silences));
  report_spread(ctx, "stamp_delay_s", source.delays_s());
  report_wire_latency(ctx, wire);
}

inline void report_ouster_imu(Context& ctx, const OusterImuSource& source, uint64_t samples, uint64_t silences, const LatencySpread& wire) {
  const OusterImuCounters& c = source.counters();
  ctx.metric("packets", static_cast<double>(c.packets));
  ctx.metric("malformed", static_cast<double>(c.malformed));
  if (const PcapCounters* p = source.capture()) {
    ctx.metric("capture_datagrams", static_cast<double>(p->datagrams));
    ctx.metric("capture_refused", static_cast<double>(p->refused()));
  }
  ctx.metric("samples", static_cast<double>(samples));
  report_device(ctx, source.device());
  ctx.metric("silences", static_cast<double>(silences));
  report_spread(ctx, "stamp_delay_s", source.delays_s());
  report_wire_latency(ctx, wire);
}

}  // namespace brickyard::drivers
