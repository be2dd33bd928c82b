// The simulated Ouster (common/ouster_emulator.hpp) against the driver that reads the real one: for
// each shipped sensor's metadata, a rotation on IMS written as packets, decoded by the driver's
// decoder and turned into points by its table; every point on the world's road, ground or walls.
#include "sim/common/ouster_emulator.hpp"

#include "drivers/common/ouster_packet_encode.hpp"
#include "drivers/common/ouster_packets.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace brickyard;
using namespace brickyard::sim;

namespace {

drivers::OusterMetadata metadata(const std::string& name) {
  std::ifstream in(std::string(BRICKYARD_SOURCE_DIR) + "/data/lidar_packets/" + name);
  std::stringstream text;
  text << in.rdbuf();
  drivers::OusterMetadata m;
  std::string error;
  EXPECT_TRUE(drivers::parse_ouster_metadata(text.str(), m, error)) << error;
  return m;
}

// IMS, flat, walls at both edges (on the edge itself: a wall point's |d| is the edge's).
WorldSpec walled_ims() {
  WorldSpec w;
  w.line = load_centerline_csv(std::string(BRICKYARD_SOURCE_DIR) + "/data/tracks/IMS.csv");
  w.walls.left = w.walls.right = true;
  return w;
}

Eigen::Isometry3d car_at(const Track& t, double s, double d) {
  const Frenet f = t.at(s, d);
  const Eigen::Vector2d p = t.position(f);
  return Eigen::Translation3d(p.x(), p.y(), 0) * Eigen::AngleAxisd(t.heading(f), Eigen::Vector3d::UnitZ());
}

}  // namespace

class OusterEmulatorOn : public ::testing::TestWithParam<const char*> {};

TEST_P(OusterEmulatorOn, ItsPacketsDecodeToPointsOnTheWorld) {
  const drivers::OusterMetadata m = metadata(GetParam());
  const Track track(walled_ims());
  OusterEmulatorParams p;
  p.range_noise = 0;
  p.body_from_sensor = Eigen::Translation3d(1.5, 0, 1.0) * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY());
  OusterEmulator sensor(track, m, p);
  const Eigen::Isometry3d body = car_at(track, 700, 2);  // turn 1 of IMS, the wall near
  Rng rng(7);
  drivers::OusterFrame frame;
  const std::size_t rays = sensor.scan(body, body.translation().x(), body.translation().y(), 1'000'000'000, 42, rng, frame);
  EXPECT_EQ(rays, static_cast<std::size_t>(m.columns_in_window()) * m.pixels_per_column);

  std::vector<std::vector<uint8_t>> packets;
  drivers::encode_ouster_packets(frame, m, packets);
  drivers::OusterLidarDecoder decoder(m);
  for (const auto& packet : packets) decoder.feed(packet.data(), packet.size());
  decoder.finish();
  std::optional<drivers::OusterFrame> got = decoder.next();
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->complete());
  EXPECT_EQ(decoder.counters().refused(), 0u);
  EXPECT_EQ(got->frame_id, 42);
  const double rotation_ns = 1e9 / m.frames_per_second;
  EXPECT_NEAR(static_cast<double>(got->timestamp_ns[m.column_window_first]), 1e9, 1);
  EXPECT_NEAR(static_cast<double>(got->timestamp_ns[(m.column_window_last + m.columns_per_frame) % m.columns_per_frame]),
              1e9 + rotation_ns * (m.columns_in_window() - 1) / m.columns_per_frame, 1);

  drivers::OusterCloud cloud;
  drivers::ouster_frame_to_cloud(*got, drivers::OusterXyzTable(m), cloud);
  ASSERT_GT(cloud.x.size(), rays / 4) << "most rays below the horizon meet the road or a wall";
  // The low-data-rate profile carries ranges in 8 mm steps; the others in millimetres.
  const double step = m.profile == drivers::OusterProfile::low_data_rate ? 0.008 : 0.001;
  const Eigen::Isometry3d world_from_sensor = body * p.body_from_sensor;
  int hint = -1, on_road = 0, on_wall = 0;
  for (std::size_t k = 0; k < cloud.x.size(); ++k) {
    const Eigen::Vector3d w = world_from_sensor * Eigen::Vector3d(cloud.x[k], cloud.y[k], cloud.z[k]);
    const Frenet f = track.project(w.x(), w.y(), hint);
    hint = f.seg;
    const double road = track.road_z(f);
    const double edge = f.d > 0 ? track.width_left(f.seg, f.u) : -track.width_right(f.seg, f.u);
    const bool road_point = std::abs(w.z() - road) < 2 * step + 1e-3;
    const bool wall_point = std::abs(f.d - edge) < 2 * step + 1e-2 && w.z() > road - 0.01;
    EXPECT_TRUE(road_point || wall_point) << "pixel " << cloud.pixel[k] << " at s " << f.s << " d " << f.d << " z " << w.z()
                                          << " (road " << road << ", edge " << edge << ")";
    on_road += road_point, on_wall += wall_point && !road_point;
  }
  EXPECT_GT(on_road, 0);
  EXPECT_GT(on_wall, 0);
}

INSTANTIATE_TEST_SUITE_P(ShippedSensors, OusterEmulatorOn,
                         ::testing::Values("OS-0-32-U1_v2.2.0_1024x10.json", "OS-1-32-G_v2.1.1_1024x10.json",
                                           "OS-2-128-U1_v2.3.0_1024x10.json", "OS-1-128_v2.3.0_1024x10.json"));
