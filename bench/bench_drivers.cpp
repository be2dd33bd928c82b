// The drivers' decoders (issue 42), each beside a baseline measured in the same run, one thread:
//  1. Ouster OS-2-128 at 1024x10 (data/lidar_packets, the vendor's capture): a whole frame's
//     packets decoded and assembled, then its points (xyz, a time each); the baseline reads the
//     same bytes (a sum over every 32-bit word). Target: decode and assemble <= 2 ms a frame.
//  2. The car's windowed sensor (data/vehicles/av21_ouster.json: the same OS-2-128 firing 361 of
//     its 1024 columns, as configs/car.json's three): the work left when the window's last packet
//     comes (it decoded, the frame handed out, its points made), what the driver adds between the
//     wire and the message; the baseline reads that packet's bytes and the frame's points.
//  3. NovAtel BESTPOSA logs (data/gnss, NovAtel's capture) through the OEM7 decoder, CRCs
//     checked; the baseline finds their sync characters. Target: >= 100,000 logs a second.
// usage: bench_drivers [--quick]
#include "drivers/common/novatel_oem7.hpp"
#include "drivers/common/ouster_metadata.hpp"
#include "drivers/common/ouster_packet_format.hpp"
#include "drivers/common/ouster_packets.hpp"
#include "drivers/common/ouster_xyz.hpp"
#include "drivers/common/pcap_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace brickyard::drivers;

namespace {

using Clock = std::chrono::steady_clock;

std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class F> double ms_of(F&& f) {
  const auto t0 = Clock::now();
  f();
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The capture's lidar payloads of its first complete frame (the packets of one frame id).
std::vector<std::vector<uint8_t>> one_frame(const std::string& dir, const OusterMetadata& m, std::size_t packets_per_frame) {
  const std::string bytes = read_text(dir + "OS-2-128-U1_v2.3.0_1024x10.pcap");
  PcapReader reader(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  std::vector<std::vector<uint8_t>> out;
  while (auto d = reader.next())
    if (d->destination_port == m.udp_port_lidar && out.size() < packets_per_frame) out.emplace_back(d->payload.begin(), d->payload.end());
  return out;
}

int ouster(const std::string& dir, int runs) {
  OusterMetadata m;
  std::string error;
  if (!parse_ouster_metadata(read_text(dir + "OS-2-128-U1_v2.3.0_1024x10.json"), m, error))
    return std::fprintf(stderr, "bench_drivers: metadata: %s\n", error.c_str()), 1;
  OusterLidarDecoder probe(m);
  const std::size_t per_frame = static_cast<std::size_t>(m.columns_per_frame / probe.layout().columns_per_packet);
  const auto packets = one_frame(dir, m, per_frame);
  if (packets.size() < per_frame) return std::fprintf(stderr, "bench_drivers: %zu packets, a frame needs %zu\n", packets.size(), per_frame), 1;
  const OusterXyzTable table(m);
  std::vector<double> decode_ms, xyz_ms, read_ms;
  std::uint64_t sink = 0, points = 0, pixels = 0;
  // As a driver runs: the last frame's buffers given back to the decoder, one cloud kept.
  std::optional<OusterFrame> spare;
  OusterCloud cloud;
  for (int r = 0; r < runs; ++r) {
    OusterLidarDecoder decoder(m);
    if (spare) decoder.recycle(std::move(*spare));
    std::optional<OusterFrame> frame;
    decode_ms.push_back(ms_of([&] {
      for (const auto& p : packets) decoder.feed(p.data(), p.size());
      decoder.finish();
      frame = decoder.next();
    }));
    if (!frame) return std::fprintf(stderr, "bench_drivers: no frame\n"), 1;
    xyz_ms.push_back(ms_of([&] { ouster_frame_to_cloud(*frame, table, cloud); }));
    points = cloud.x.size();
    pixels = static_cast<std::uint64_t>(frame->width) * frame->height;
    read_ms.push_back(ms_of([&] {
      for (const auto& p : packets)
        for (std::size_t i = 0; i + 4 <= p.size(); i += 4) {
          std::uint32_t w;
          std::memcpy(&w, p.data() + i, 4);
          sink += w;
        }
    }));
    spare = std::move(frame);
  }
  std::printf("Ouster OS-2-128 1024x10, one frame (%zu packets, %llu pixels, %llu points with a return), %d runs, one thread\n",
              packets.size(), static_cast<unsigned long long>(pixels), static_cast<unsigned long long>(points), runs);
  std::printf("%-40s %10s %14s\n", "", "ms/frame", "ns/pixel");
  std::printf("%-40s %10.3f %14.2f\n", "ours: decode + assemble", median(decode_ms), 1e6 * median(decode_ms) / pixels);
  std::printf("%-40s %10.3f %14.2f\n", "ours: points (xyz, time)", median(xyz_ms), 1e6 * median(xyz_ms) / pixels);
  std::printf("%-40s %10.3f %14.2f\n", "baseline: reading the same bytes", median(read_ms), 1e6 * median(read_ms) / pixels);
  std::printf("decode + assemble / reading: %.1f (sink %llu)\n\n", median(decode_ms) / median(read_ms), static_cast<unsigned long long>(sink % 10));
  return 0;
}

// The window's packets of `packets` (those with a column the sensor fires).
std::vector<std::vector<uint8_t>> in_window(const std::vector<std::vector<uint8_t>>& packets, const OusterMetadata& m, const OusterPacketLayout& l) {
  std::vector<std::vector<uint8_t>> out;
  for (const auto& p : packets) {
    bool fires = false;
    for (int c = 0; c < l.columns_per_packet; ++c)
      fires = fires || m.column_in_window(read_ouster_column_header(l, p.data() + l.header_bytes + c * l.column_bytes()).measurement_id);
    if (fires) out.push_back(p);
  }
  return out;
}

int windowed(const std::string& data, int runs) {
  OusterMetadata full, m;
  std::string error;
  if (!parse_ouster_metadata(read_text(data + "lidar_packets/OS-2-128-U1_v2.3.0_1024x10.json"), full, error) ||
      !parse_ouster_metadata(read_text(data + "vehicles/av21_ouster.json"), m, error))
    return std::fprintf(stderr, "bench_drivers: metadata: %s\n", error.c_str()), 1;
  OusterLidarDecoder probe(m);
  const auto packets = in_window(one_frame(data + "lidar_packets/", full, static_cast<std::size_t>(full.columns_per_frame / probe.layout().columns_per_packet)),
                                 m, probe.layout());
  const OusterXyzTable table(m);
  OusterLidarDecoder decoder(m);
  OusterCloud cloud;
  std::vector<double> last_ms, read_ms;
  std::uint64_t sink = 0;
  std::size_t complete = 0;
  for (int r = 0; r < runs + 1; ++r) {  // the first round allocates
    std::vector<std::vector<uint8_t>> rotation = packets;
    for (auto& p : rotation) p[2] = static_cast<uint8_t>(r);  // a new frame id each rotation
    for (std::size_t i = 0; i + 1 < rotation.size(); ++i) decoder.feed(rotation[i].data(), rotation[i].size());
    std::optional<OusterFrame> frame;
    const double ms = ms_of([&] {
      decoder.feed(rotation.back().data(), rotation.back().size());
      frame = decoder.next();
      if (frame) ouster_frame_to_cloud(*frame, table, cloud);
    });
    if (!frame) return std::fprintf(stderr, "bench_drivers: the window's last packet handed out no frame\n"), 1;
    complete += frame->complete();
    decoder.recycle(std::move(*frame));
    const double read = ms_of([&] {
      for (std::size_t i = 0; i + 4 <= rotation.back().size(); i += 4) {
        std::uint32_t w;
        std::memcpy(&w, rotation.back().data() + i, 4);
        sink += w;
      }
      for (std::size_t i = 0; i < cloud.x.size(); ++i) sink += static_cast<std::uint64_t>(cloud.x[i] + cloud.y[i] + cloud.z[i]);
    });
    if (r > 0) last_ms.push_back(ms), read_ms.push_back(read);
  }
  std::printf("The car's windowed OS-2-128 (columns %d-%d: %zu packets a rotation, %zu points), %d rotations, one thread\n",
              m.column_window_first, m.column_window_last, packets.size(), cloud.x.size(), runs);
  std::printf("%-40s %10s\n", "", "ms/frame");
  std::printf("%-40s %10.3f\n", "ours: the last packet to its points", median(last_ms));
  std::printf("%-40s %10.3f\n", "baseline: reading it and the points", median(read_ms));
  std::printf("ours / baseline: %.1f (sink %llu)\n\n", median(last_ms) / median(read_ms), static_cast<unsigned long long>(sink % 10));
  return complete == static_cast<std::size_t>(runs + 1) ? 0 : (std::fprintf(stderr, "bench_drivers: %zu of %d rotations whole\n", complete, runs + 1), 1);
}

int novatel(const std::string& dir, int runs) {
  const std::string logs = read_text(dir + "novatel_BESTPOS.GPS");
  std::vector<double> decode_ms, read_ms;
  std::size_t decoded = 0, lines = 0;
  for (int r = 0; r < runs; ++r) {
    NovatelOem7Decoder decoder;
    decode_ms.push_back(ms_of([&] {
      decoder.feed(logs);
      decoded = 0;
      while (decoder.next()) ++decoded;
    }));
    read_ms.push_back(ms_of([&] { lines = static_cast<std::size_t>(std::count(logs.begin(), logs.end(), '#')); }));
  }
  std::printf("NovAtel BESTPOSA, %zu logs (%zu syncs, %zu bytes), CRCs checked, %d runs, one thread\n", decoded, lines, logs.size(), runs);
  std::printf("%-40s %14s\n", "", "logs/s");
  std::printf("%-40s %14.0f\n", "ours: OEM7 decoder", decoded / (median(decode_ms) / 1e3));
  std::printf("%-40s %14.0f\n", "baseline: finding the syncs ('#')", lines / (median(read_ms) / 1e3));
  return decoded == lines ? 0 : (std::fprintf(stderr, "bench_drivers: %zu of %zu logs decoded\n", decoded, lines), 1);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::string data = std::string(BRICKYARD_SOURCE_DIR) + "/data/";
  const int runs = quick ? 5 : 51;
  if (const int rc = ouster(data + "lidar_packets/", runs)) return rc;
  if (const int rc = windowed(data, runs)) return rc;
  return novatel(data + "gnss/", runs);
}
