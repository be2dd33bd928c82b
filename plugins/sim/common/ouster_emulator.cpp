#include "ouster_emulator.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {
namespace {

// The caster's own rays are not used (each pixel is cast alone): one row, one column.
LidarSpec caster_spec(const OusterEmulatorParams& p) {
  LidarSpec s;
  s.columns = 1;
  s.elevations = {0.0};
  s.min_range = 0;
  s.max_range = p.max_range;
  s.range_noise = 0;
  return s;
}

// A return's photons as the signal field counts them: falling with the square of the range (a
// stand-in: what reads the field is told so in docs/simulator.md).
std::uint16_t signal_of(double reflectivity, double range) {
  constexpr double kPhotonsAtOneMetre = 2e5;
  return static_cast<std::uint16_t>(std::clamp(kPhotonsAtOneMetre * reflectivity / std::max(range * range, 1.0), 1.0, 65535.0));
}

}  // namespace

OusterEmulator::OusterEmulator(const Track& track, drivers::OusterMetadata metadata, OusterEmulatorParams params)
    : track_(track), metadata_(std::move(metadata)), p_(params), table_(metadata_), caster_(track, caster_spec(params)) {}

double OusterEmulator::reflectivity(Surface s) const {
  switch (s) {
    case Surface::road: return p_.reflectivity_road;
    case Surface::wall: return p_.reflectivity_wall;
    case Surface::grass: return p_.reflectivity_grass;
    case Surface::pylon: return p_.reflectivity_pylon;
    case Surface::car:  // the emulator casts the world alone: no car comes back from it
    case Surface::none: break;
  }
  return 0;
}

void OusterEmulator::size_frame(drivers::OusterFrame& out) const {
  const int w = metadata_.columns_per_frame, h = metadata_.pixels_per_column;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  out.width = w, out.height = h;
  out.timestamp_ns.assign(w, 0);
  out.encoder_count.assign(w, 0);
  out.status.assign(w, 0);
  out.received.assign(w, 0);
  for (auto* v : {&out.range_mm, &out.range2_mm}) v->assign(pixels, 0);
  for (auto* v : {&out.signal, &out.signal2, &out.near_ir}) v->assign(pixels, 0);
  for (auto* v : {&out.reflectivity, &out.reflectivity2, &out.flags, &out.flags2}) v->assign(pixels, 0);
}

void OusterEmulator::cast_pixel(const Eigen::Isometry3d& world_from_sensor, int seg, int row, int column, Rng& rng,
                                drivers::OusterFrame& out) const {
  const std::size_t i = out.pixel(row, column);
  // The pixel's ray in the sensor frame: p = r * direction + offset (millimetres), its origin the beam's.
  const float* d = &table_.direction()[3 * i];
  const float* o = &table_.offset_mm()[3 * i];
  const Eigen::Vector3d origin = world_from_sensor * (1e-3 * Eigen::Vector3d(o[0], o[1], o[2]));
  const Eigen::Vector3d direction = (world_from_sensor.linear() * Eigen::Vector3d(d[0], d[1], d[2])).normalized();
  const RayHit hit = caster_.cast(origin, direction, seg);
  if (hit.surface == Surface::none) return;
  const double range = hit.range + (p_.range_noise > 0 ? rng.normal_fast(p_.range_noise) : 0.0);
  if (p_.dropout > 0 && rng.uniform() < p_.dropout) return;
  if (range < p_.min_range || range > p_.max_range) return;
  const double lambertian = reflectivity(hit.surface) * hit.cos_incidence;
  out.range_mm[i] = static_cast<std::uint32_t>(std::lround(range * 1000));
  out.reflectivity[i] = static_cast<std::uint8_t>(std::clamp(std::lround(100 * lambertian), 0L, 255L));
  out.signal[i] = signal_of(lambertian, range);
}

void OusterEmulator::begin(std::uint64_t t0_ns, std::uint16_t frame_id, drivers::OusterFrame& out) const {
  size_frame(out);
  out.frame_id = frame_id;
  const int w = metadata_.columns_per_frame;
  const double column_ns = 1e9 / (metadata_.frames_per_second * static_cast<double>(w));
  out.columns_expected = metadata_.columns_in_window();
  out.columns_received = 0;
  for (int k = 0; k < out.columns_expected; ++k) {
    const int c = (metadata_.column_window_first + k) % w;
    out.timestamp_ns[c] = t0_ns + static_cast<std::uint64_t>(std::llround(k * column_ns));
    out.encoder_count[c] = static_cast<std::uint32_t>(static_cast<std::int64_t>(c) * 90112 / w);
  }
}

std::size_t OusterEmulator::cast_columns(const Eigen::Isometry3d& world_from_body, double x, double y, int first, int last,
                                         Rng& rng, drivers::OusterFrame& out) {
  const Eigen::Isometry3d world_from_sensor = world_from_body * p_.body_from_sensor;
  hint_ = track_.project(x, y, hint_).seg;
  const Eigen::Vector3d sensor = world_from_sensor.translation();
  const int seg = track_.project(sensor.x(), sensor.y(), hint_).seg;
  std::size_t rays = 0;
  for (int k = std::max(first, 0); k < std::min(last, out.columns_expected); ++k) {
    const int c = (metadata_.column_window_first + k) % out.width;
    out.status[c] = metadata_.profile == drivers::OusterProfile::legacy ? 0xFFFFFFFFu : 1u;
    if (!out.received[c]) ++out.columns_received;
    out.received[c] = 1;
    for (int r = 0; r < out.height; ++r, ++rays) cast_pixel(world_from_sensor, seg, r, c, rng, out);
  }
  return rays;
}

std::size_t OusterEmulator::scan(const Eigen::Isometry3d& world_from_body, double x, double y, std::uint64_t t0_ns,
                                 std::uint16_t frame_id, Rng& rng, drivers::OusterFrame& out) {
  begin(t0_ns, frame_id, out);
  return cast_columns(world_from_body, x, y, 0, out.columns_expected, rng, out);
}

}  // namespace brickyard::sim
