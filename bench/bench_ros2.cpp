// ROS 2's types at the edges (issue 45, docs/ros2.md): a 100k-point cloud as ROS 2's
// sensor_msgs/PointCloud2 read into our cloud's columns and written back (cdr/ros2_pointcloud.hpp),
// beside the baseline in the same run: a memcpy of the same bytes, there and back (both into
// buffers kept from round to round, as a player keeps them from frame to frame). Target: to ours
// and back <= 1 ms. Medians of the rounds; exits 1 when the round trip does not give the cloud back.
// usage: bench_ros2 [--quick]
#include "cdr/ros2_pointcloud.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

using brickyard::cdr::CloudColumns;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// A LiDAR frame's worth of points: positions within 100 m, intensity, each point's time.
CloudColumns cloud_of(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-100, 100), unit(0, 1);
  CloudColumns c;
  c.stamp_ns = 1'700'000'000'123'456'789;
  c.frame_id = "lidar_front";
  for (std::size_t i = 0; i < n; ++i) {
    c.x.push_back(pos(rng)), c.y.push_back(pos(rng)), c.z.push_back(0.05f * pos(rng));
    c.intensity.push_back(255 * unit(rng)), c.time_offset.push_back(0.1f * static_cast<float>(i) / static_cast<float>(n));
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && !std::strcmp(argv[1], "--quick");
  const int rounds = quick ? 15 : 101;
  const std::size_t points = 100'000;
  const CloudColumns cloud = cloud_of(points);
  const std::vector<unsigned char> wire = brickyard::cdr::write_pointcloud2(cloud);
  std::vector<double> ours, baseline;
  std::vector<unsigned char> copy(wire.size()), back(wire.size());
  // A player's buffers, kept from frame to frame as the baseline's are.
  CloudColumns read;
  std::vector<unsigned char> written;
  bool same = true;
  for (int r = 0; r < rounds; ++r) {
    const auto t0 = Clock::now();
    brickyard::cdr::read_pointcloud2(wire.data(), wire.size(), read);
    brickyard::cdr::write_pointcloud2(read, written);
    const auto t1 = Clock::now();
    std::memcpy(copy.data(), wire.data(), wire.size());
    std::memcpy(back.data(), copy.data(), copy.size());
    const auto t2 = Clock::now();
    ours.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    baseline.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    same = same && written == wire && back == wire;
  }
  std::printf("PointCloud2 of %zu points (%.1f MB: x, y, z, intensity, t), to our cloud and back, median of %d rounds:\n", points,
              static_cast<double>(wire.size()) / 1e6, rounds);
  std::printf("  ours  %.3f ms   baseline (memcpy of the bytes, there and back) %.3f ms   ratio %.1fx   target <= 1 ms: %s\n", median(ours),
              median(baseline), median(ours) / median(baseline), median(ours) <= 1.0 ? "met" : "NOT met");
  if (!same) {
    std::printf("FAIL: the cloud did not come back the same bytes\n");
    return 1;
  }
  return 0;
}
