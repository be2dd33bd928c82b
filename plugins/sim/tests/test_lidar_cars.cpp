// Other cars in the LiDAR's frames (issue 46), called directly: where a car is met, what it hides,
// the two scans' same bits with cars, and a frame with no car near left as it was.
#include "sim/common/lidar.hpp"
#include "sim/common/track.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::sim;

namespace {

// A walled straight of 1 km and back (a long thin oval), 7.5 m either side.
WorldSpec walled_straight() {
  WorldSpec w;
  for (double s = 0; s < 1000; s += 5) {
    w.line.x.push_back(s);
    w.line.y.push_back(0);
  }
  for (int i = 0; i < 60; ++i) {
    const double a = -M_PI / 2 + M_PI * i / 60;
    w.line.x.push_back(1000 + 100 * std::cos(a));
    w.line.y.push_back(100 + 100 * std::sin(a));
  }
  for (double s = 1000; s > 0; s -= 5) {
    w.line.x.push_back(s);
    w.line.y.push_back(200);
  }
  for (int i = 0; i < 60; ++i) {
    const double a = M_PI / 2 + M_PI * i / 60;
    w.line.x.push_back(100 * std::cos(a));
    w.line.y.push_back(100 + 100 * std::sin(a));
  }
  w.line.width_left.assign(w.line.x.size(), 7.5);
  w.line.width_right.assign(w.line.x.size(), 7.5);
  w.walls.left = w.walls.right = true;
  return w;
}

CarBody car_at(double x, double y, double yaw, double z = 0, double roll = 0) {
  CarBody c;
  c.world_from_body = Eigen::Translation3d(x, y, z) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  c.front = 3.9;
  c.rear = 1.0;
  c.half_width = 0.97;
  return c;
}

LidarSpec hydra(double noise = 0.02) {
  LidarSpec s;
  s.mount = {2.342, 0, 0.448};
  s.elevations = row_elevations(32, -15, 15, "horizon", 2);
  s.columns = 400;
  s.range_noise = noise;
  return s;
}

Eigen::Isometry3d level_at(double x, double y, double yaw = 0) {
  return Eigen::Translation3d(x, y, 0) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::Isometry3d::Identity();
}

PointBuffers frame(const LidarCaster& c, const Track& t, const Eigen::Isometry3d& body, const std::vector<CarBody>& cars,
                   std::uint64_t seed = 1) {
  Rng rng(seed);
  PointBuffers p;
  p.record_surface = true;
  c.scan(body, t.project(body.translation().x(), body.translation().y()).seg, rng, 1.0, p, cars);
  return p;
}

bool same(const PointBuffers& a, const PointBuffers& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity && a.surface == b.surface;
}

std::size_t count(const PointBuffers& p, Surface s) { return static_cast<std::size_t>(std::count(p.surface.begin(), p.surface.end(), s)); }

}  // namespace

// A car 30 m ahead on the line: its back is met at its range, every one of its points lies on its
// box, and it hides the road and walls behind it (fewer of their points than without it).
TEST(LidarCars, ACarAheadIsMetOnItsBoxAndHidesWhatIsBehind) {
  Track t(walled_straight());
  const LidarSpec spec = hydra(0.0);
  LidarCaster caster(t, spec);
  const Eigen::Isometry3d body = level_at(300, 0);
  const CarBody rival = car_at(330, 0, 0);
  const PointBuffers without = frame(caster, t, body, {}), with = frame(caster, t, body, {rival});
  ASSERT_GT(count(with, Surface::car), 50u);
  EXPECT_EQ(count(without, Surface::car), 0u);
  EXPECT_LT(count(with, Surface::road) + count(with, Surface::wall), count(without, Surface::road) + count(without, Surface::wall));
  const Eigen::Isometry3d world_from_sensor = body * Eigen::Translation3d(spec.mount);
  double nearest = 1e9;
  for (std::size_t i = 0; i < with.x.size(); ++i) {
    if (with.surface[i] != Surface::car) continue;
    const Eigen::Vector3d p = rival.world_from_body.inverse() * (world_from_sensor * Eigen::Vector3d(with.x[i], with.y[i], with.z[i]));
    EXPECT_TRUE(p.x() > -rival.rear - 1e-4 && p.x() < rival.front + 1e-4 && std::abs(p.y()) < rival.half_width + 1e-4 &&
                p.z() > rival.bottom - 1e-4 && p.z() < rival.top + 1e-4)
        << p.transpose();
    nearest = std::min(nearest, static_cast<double>(with.x[i]));
  }
  // Its back at 330 - 1.0 m, the sensor at 300 + 2.342 m: met square on, 26.658 m ahead.
  EXPECT_NEAR(nearest, 26.658, 1e-4);
}

// The lanes and ray by ray, one thread and two, give the same frame with cars, bit for bit, the
// sensor rolled (a car in a banked turn) and cars near and far, beside and across the line,
// rows above an escape included (a near car rises over the horizon rows).
TEST(LidarCars, LanesAndRaysOneByOneSeeTheSameCars) {
  Track t(walled_straight());
  for (double roll_deg : {0.0, 8.0}) {
    LidarSpec base = hydra();
    base.roll = roll_deg * M_PI / 180;
    LidarSpec ray_by_ray = base, two_threads = base;
    ray_by_ray.simd = false;
    two_threads.threads = 2;
    LidarCaster lanes(t, base), rays(t, ray_by_ray), both(t, two_threads);
    std::size_t seen = 0;
    for (double x : {150.0, 420.0, 700.0}) {
      const Eigen::Isometry3d body = level_at(x, 1.5, 0.02);
      const std::vector<CarBody> cars = {car_at(x + 8, -2.5, 0.1), car_at(x + 25, 3, -0.3, 0, 0.1), car_at(x + 90, 0, 0.0),
                                         car_at(x + 300, 0, 0.0)};
      const PointBuffers a = frame(lanes, t, body, cars, 7), b = frame(rays, t, body, cars, 7), c = frame(both, t, body, cars, 7);
      EXPECT_TRUE(same(a, b)) << "x " << x << ", roll " << roll_deg;
      EXPECT_TRUE(same(a, c)) << "x " << x << ", roll " << roll_deg;
      seen += count(a, Surface::car);
    }
    EXPECT_GT(seen, 500u);
  }
}

// Cars out of reach (behind the sensor's field of view, beyond its range) leave the frame as it
// is without them, bit for bit; the noise draws included.
TEST(LidarCars, CarsOutOfReachLeaveTheFrameAsItWas) {
  Track t(walled_straight());
  for (bool simd : {true, false}) {
    LidarSpec spec = hydra();
    spec.simd = simd;
    LidarCaster caster(t, spec);
    const Eigen::Isometry3d body = level_at(400, 0);
    const std::vector<CarBody> away = {car_at(380, 0, 0), car_at(400 + 260, 0, 0)};
    EXPECT_TRUE(same(frame(caster, t, body, {}, 3), frame(caster, t, body, away, 3))) << "simd " << simd;
  }
}

// A car straight across the sensor's back in a 360-degree sensor's view: its columns wrap past
// +-180 degrees, and it is still met on both sides of the wrap.
TEST(LidarCars, AFullTurnSensorSeesACarAcrossItsBack) {
  Track t(walled_straight());
  LidarSpec spec = hydra(0.0);
  spec.h_fov = 2 * M_PI;
  spec.columns = 1024;
  LidarCaster caster(t, spec);
  const PointBuffers p = frame(caster, t, level_at(400, 0), {car_at(390, 0, 0)});
  int left = 0, right = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i)
    if (p.surface[i] == Surface::car) (p.y[i] > 0 ? left : right) += 1;
  EXPECT_GT(left, 10);
  EXPECT_GT(right, 10);
}
