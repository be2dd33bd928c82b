// The per-point helpers every cloud passes through: what they keep and the bits they compute.
#include "perception/common/cell_map.hpp"
#include "perception/common/frame_set.hpp"
#include "perception/common/huge_pages.hpp"
#include "perception/common/points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace brickyard::perception {
namespace {

TEST(Points, InRangeKeepsFiniteCoordinatesWithinTheLimit) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(in_range(Point(0, -0.0f, 1)));
  EXPECT_TRUE(in_range(Point(kMaxCoordinate, -kMaxCoordinate, 0)));
  EXPECT_FALSE(in_range(Point(std::nextafter(kMaxCoordinate, inf), 0, 0)));
  EXPECT_FALSE(in_range(Point(0, -std::nextafter(kMaxCoordinate, inf), 0)));
  EXPECT_FALSE(in_range(Point(0, 0, nan)));
  EXPECT_FALSE(in_range(Point(-inf, 0, 0)));
  EXPECT_FALSE(in_range(Point(0, inf, 0)));
}

// The vehicle frame's points are the bits Eigen's r * p + o gives (the frames recorded before
// the transform was written out are the same).
TEST(Points, TransformedIsEigensProductBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-150, 150), angle(-3.2f, 3.2f);
  int differing = 0;
  for (int pose = 0; pose < 200; ++pose) {
    const SensorPose s{coord(rng) * 0.01, coord(rng) * 0.01, 1.5, angle(rng) * 0.05, angle(rng) * 0.05, angle(rng)};
    const Eigen::Isometry3f t = s.vehicle_from_sensor();
    const Eigen::Matrix3f r = t.linear();
    const Eigen::Vector3f o = t.translation();
    for (int i = 0; i < 500; ++i) {
      const float x = coord(rng), y = coord(rng), z = coord(rng) * 0.1f;
      const Point eigen = r * Eigen::Vector3f(x, y, z) + o;
      const Point ours = transformed(r, o, x, y, z);
      differing += std::memcmp(eigen.data(), ours.data(), sizeof(float) * 3) != 0;
    }
  }
  EXPECT_EQ(differing, 0);
}

TEST(Points, AppendInVehicleFrameDropsWhatIsOutOfRange) {
  const std::vector<float> x{1, std::numeric_limits<float>::quiet_NaN(), 3, 2e4f}, y{0, 0, 1, 0}, z{0, 0, 0, 0};
  Points out{Point(9, 9, 9)};
  append_in_vehicle_frame(SensorPose{1, 0, 0, 0, 0, 0}, x.data(), y.data(), z.data(), x.size(), out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[1], Point(2, 0, 0));
  EXPECT_EQ(out[2], Point(4, 1, 0));
}

TEST(HugePages, BigBlocksAreTwoMebibyteAlignedSmallOnesAreNot) {
  std::vector<std::uint64_t, HugePageAllocator<std::uint64_t>> big(3 << 18, 5), small(100, 6);  // 6 MiB, 800 B
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % HugePageAllocator<int>::kHuge, 0u);
  EXPECT_EQ(big.back(), 5u);
  EXPECT_EQ(small.back(), 6u);
  big.resize(10);
  big.shrink_to_fit();  // from the huge path back to operator new's
  EXPECT_EQ(big.front(), 5u);
}

TEST(HugePages, ACellMapPastTwoMebibytesFindsEveryKey) {
  CellMap<std::uint32_t> map;
  map.reset(0);
  bool inserted;
  for (std::uint32_t k = 0; k < 300000; ++k) map.find_or_insert(cell_key(k % 1000, k / 1000, 1), k, inserted);  // grows to 16 MiB
  ASSERT_EQ(map.size(), 300000u);
  for (std::uint32_t k = 0; k < 300000; k += 997) {
    const std::uint32_t* v = map.find(cell_key(k % 1000, k / 1000, 1));
    ASSERT_NE(v, nullptr);
    EXPECT_EQ(*v, k);
  }
  EXPECT_EQ(map.find(cell_key(5, 5, 2)), nullptr);
}

}  // namespace
}  // namespace brickyard::perception
