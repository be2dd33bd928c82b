#include "ouster_xyz.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

namespace brickyard::drivers {

namespace {

using Vec3 = std::array<double, 3>;

// A row-major 4x4 homogeneous transform applied to a point (w = 1) or a direction (w = 0).
Vec3 apply(const std::array<double, 16>& m, const Vec3& v, double w) {
  Vec3 out{};
  for (int i = 0; i < 3; ++i) out[i] = m[4 * i] * v[0] + m[4 * i + 1] * v[1] + m[4 * i + 2] * v[2] + m[4 * i + 3] * w;
  return out;
}

struct BeamPixel {
  Vec3 direction;  // lidar frame, unit
  Vec3 offset;     // lidar frame, mm: the point at range r is r * direction + offset
};

BeamPixel beam_pixel(const OusterMetadata& m, int row, int column) {
  const double two_pi = 2.0 * std::numbers::pi;
  const double encoder = two_pi * (1.0 - static_cast<double>(column) / m.columns_per_frame);
  const double azimuth = -two_pi * m.beam_azimuth_deg[row] / 360.0;
  const double altitude = two_pi * m.beam_altitude_deg[row] / 360.0;
  const double n_x = m.beam_to_lidar[3];
  const double n_z = m.beam_to_lidar[11];
  const double n = std::hypot(n_x, n_z);
  BeamPixel b;
  b.direction = {std::cos(encoder + azimuth) * std::cos(altitude), std::sin(encoder + azimuth) * std::cos(altitude),
                 std::sin(altitude)};
  b.offset = {n_x * std::cos(encoder) - n * b.direction[0], n_x * std::sin(encoder) - n * b.direction[1],
              n_z - n * b.direction[2]};
  return b;
}

// The frame's arrived columns as runs [first, last), in order.
std::vector<std::pair<size_t, size_t>> received_runs(const OusterFrame& f) {
  std::vector<std::pair<size_t, size_t>> runs;
  const size_t w = std::min(static_cast<size_t>(f.width), f.received.size());
  for (size_t c = 0; c < w;) {
    if (!f.received[c]) { ++c; continue; }
    const size_t first = c;
    while (c < w && f.received[c]) ++c;
    runs.emplace_back(first, c);
  }
  return runs;
}

}  // namespace

OusterXyzTable::OusterXyzTable(const OusterMetadata& m) : width_(m.columns_per_frame), height_(m.pixels_per_column) {
  const size_t n = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  direction_.resize(3 * n);
  offset_mm_.resize(3 * n);
  for (int row = 0; row < height_; ++row) {
    for (int column = 0; column < width_; ++column) {
      BeamPixel b = beam_pixel(m, row, column);
      Vec3 d = apply(m.lidar_to_sensor, b.direction, 0.0);
      Vec3 o = apply(m.lidar_to_sensor, b.offset, 1.0);
      const size_t at = 3 * (static_cast<size_t>(row) * width_ + column);
      for (int k = 0; k < 3; ++k) {
        direction_[at + k] = static_cast<float>(d[k]);
        offset_mm_[at + k] = static_cast<float>(o[k]);
      }
    }
  }
}

void OusterCloud::clear() {
  x.clear();
  y.clear();
  z.clear();
  intensity.clear();
  time_ns.clear();
  pixel.clear();
}

void ouster_frame_to_cloud(const OusterFrame& frame, const OusterXyzTable& table, OusterCloud& cloud,
                           bool second_return) {
  cloud.clear();
  const std::vector<uint32_t>& range = second_return ? frame.range2_mm : frame.range_mm;
  const std::vector<uint8_t>& reflectivity = second_return ? frame.reflectivity2 : frame.reflectivity;
  if (frame.width != table.width() || frame.height != table.height() || range.size() != table.direction().size() / 3) {
    return;  // a frame of another sensor or mode: no points rather than wrong ones
  }
  // Only the columns that arrived hold returns (finish_ouster_frame zeroed the rest): a windowed
  // sensor's frame is mostly columns it does not fire. Sized to the returns (fresh memory for every
  // pixel was page faults for nothing), written in place row by row (a division a point for its
  // column cost as much as the rest).
  const std::vector<std::pair<size_t, size_t>> runs = received_runs(frame);
  const size_t width = static_cast<size_t>(frame.width), height = static_cast<size_t>(frame.height);
  size_t returns = 0;
  for (size_t row = 0; row < height; ++row)
    for (const auto& [first, last] : runs)
      for (size_t i = row * width + first; i < row * width + last; ++i) returns += range[i] != 0;
  for (auto* v : {&cloud.x, &cloud.y, &cloud.z, &cloud.intensity}) v->resize(returns);
  cloud.time_ns.resize(returns);
  cloud.pixel.resize(returns);
  const float* dir = table.direction().data();
  const float* off = table.offset_mm().data();
  size_t k = 0;
  for (size_t row = 0; row < height; ++row) {
    for (const auto& [first, last] : runs) {
      for (size_t column = first, i = row * width + first; column < last; ++column, ++i) {
        if (range[i] == 0) continue;
        const float r = static_cast<float>(range[i]);
        cloud.x[k] = (r * dir[3 * i] + off[3 * i]) * 1e-3f;
        cloud.y[k] = (r * dir[3 * i + 1] + off[3 * i + 1]) * 1e-3f;
        cloud.z[k] = (r * dir[3 * i + 2] + off[3 * i + 2]) * 1e-3f;
        cloud.intensity[k] = static_cast<float>(reflectivity[i]);
        cloud.time_ns[k] = frame.timestamp_ns[column];
        cloud.pixel[k] = static_cast<uint32_t>(i);
        ++k;
      }
    }
  }
}

}  // namespace brickyard::drivers
