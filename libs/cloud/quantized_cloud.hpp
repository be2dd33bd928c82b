#pragma once
// A point cloud kept compact for a recording (`--record-cloud-precision M`, docs/recording.md):
// each coordinate rounded to a multiple of the precision and stored as its difference to the
// previous point's. A spinning LiDAR's consecutive points lie centimetres apart, so the differences
// are small integers; zigzag-coded (small of either sign → small unsigned) and laid out as byte
// planes (every point's low byte, then every point's next byte, ...), their high planes are almost
// all zero, and zstd packs them five to six times smaller than the float32 coordinates, whose low
// bits carry the sensor's noise. Lossy by at most half the precision a coordinate; intensity
// in 256 steps of its cloud's maximum. Framework-free: templates over any message with the
// PointCloud's and QuantizedPointCloud's accessors (the generated types), so this library needs
// no SDK; unit tests call it directly.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::cloud {

struct Quantized {
  double precision_m = 0;
  std::vector<std::uint8_t> steps;        // 12 bytes a point: 4 byte planes of x's steps, then y's, then z's
  std::vector<std::uint32_t> not_finite;  // points restored as NaN
  float intensity_max = 0;
  std::vector<std::uint8_t> intensity;    // empty when the cloud had none
};

// Throws std::invalid_argument when the precision is not in (0, 1] m or the arrays' lengths differ.
Quantized quantize(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
                   const std::vector<float>& intensity, double precision_m);

// The cloud again: x, y, z to within half the precision, intensity within half a step. Throws
// std::invalid_argument naming what does not fit (lengths, a precision, an index beyond the cloud).
void restore(const Quantized& q, std::vector<float>& x, std::vector<float>& y, std::vector<float>& z, std::vector<float>& intensity);

// The message types' adapters (brickyard::msgs::PointCloud ⇄ QuantizedPointCloud).
template <class Cloud, class Packed> Packed pack(const Cloud& c, double precision_m) {
  Quantized q = quantize(c.x(), c.y(), c.z(), c.intensity(), precision_m);
  Packed p;
  p.header(c.header());
  p.sensor_id(c.sensor_id());
  p.sensor_x(c.sensor_x()), p.sensor_y(c.sensor_y()), p.sensor_z(c.sensor_z());
  p.sensor_roll(c.sensor_roll()), p.sensor_pitch(c.sensor_pitch()), p.sensor_yaw(c.sensor_yaw());
  p.precision_m(q.precision_m);
  p.steps(std::move(q.steps));
  p.not_finite(std::move(q.not_finite));
  p.intensity_max(q.intensity_max);
  p.intensity(std::move(q.intensity));
  p.time_offset(c.time_offset());
  return p;
}

template <class Cloud, class Packed> Cloud unpack(const Packed& p) {
  Quantized q;
  q.precision_m = p.precision_m();
  q.steps = p.steps();
  q.not_finite = p.not_finite();
  q.intensity_max = p.intensity_max();
  q.intensity = p.intensity();
  Cloud c;
  c.header(p.header());
  c.sensor_id(p.sensor_id());
  c.sensor_x(p.sensor_x()), c.sensor_y(p.sensor_y()), c.sensor_z(p.sensor_z());
  c.sensor_roll(p.sensor_roll()), c.sensor_pitch(p.sensor_pitch()), c.sensor_yaw(p.sensor_yaw());
  restore(q, c.x(), c.y(), c.z(), c.intensity());
  if (!p.time_offset().empty() && p.time_offset().size() != c.x().size())
    throw std::invalid_argument("time_offset: " + std::to_string(p.time_offset().size()) + " times for " + std::to_string(c.x().size()) + " points");
  c.time_offset(p.time_offset());
  return c;
}

}  // namespace brickyard::cloud
