// sensor_msgs/PointCloud2 to a cloud's columns and back (cdr/ros2_pointcloud.hpp): our own clouds
// round-trip exactly; a cloud as another driver lays it out (FLOAT64 axes, big-endian points,
// padding, a UINT16 intensity, a UINT32 time in ns, rows with slack, no-return points) is read by
// its fields; fields that make no points are refused naming the field, bytes that end early are a
// damaged sample naming the byte.
#include "cdr/cdr_reader.hpp"
#include "cdr/cdr_writer.hpp"
#include "cdr/ros2_pointcloud.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace brickyard::cdr;

namespace {

// A PointCloud2's CDR written by hand, big-endian (the other byte order from our writer's).
class BigEndianCdr {
 public:
  BigEndianCdr() : out_{0x00, 0x00, 0x00, 0x00} {}
  template <class T>
  void put(T v) {
    while ((out_.size() - 4) % sizeof(T)) out_.push_back(0);
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T); ++i) out_.push_back(b[sizeof(T) - 1 - i]);  // this host is little-endian
  }
  void str(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
  }
  void raw(const std::vector<unsigned char>& b) { out_.insert(out_.end(), b.begin(), b.end()); }
  std::vector<unsigned char> bytes() const { return out_; }

 private:
  std::vector<unsigned char> out_;
};

struct FieldSpec {
  const char* name;
  std::uint32_t offset;
  std::uint8_t datatype;
};

// Two rows of two points, 32 bytes each (x, y, z FLOAT64 at 0, 8, 16; intensity UINT16 at 24;
// t UINT32 ns at 28), rows 72 bytes (8 of slack); the points' bytes big-endian. The last point has
// no return (NaN x).
std::vector<unsigned char> foreign_cloud(const std::vector<FieldSpec>& fields, std::uint32_t point_step = 32, std::size_t cut = 0) {
  BigEndianCdr c;
  c.put<std::int32_t>(12), c.put<std::uint32_t>(500'000'000);
  c.str("os_lidar");
  c.put<std::uint32_t>(2), c.put<std::uint32_t>(2);
  c.put<std::uint32_t>(static_cast<std::uint32_t>(fields.size()));
  for (const auto& f : fields) c.str(f.name), c.put<std::uint32_t>(f.offset), c.put<std::uint8_t>(f.datatype), c.put<std::uint32_t>(1);
  c.put<std::uint8_t>(1);  // is_bigendian
  c.put<std::uint32_t>(point_step), c.put<std::uint32_t>(72);
  std::vector<unsigned char> data(2 * 72, 0xEE);
  auto be = [&](std::size_t at, const void* v, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) data[at + i] = static_cast<const unsigned char*>(v)[n - 1 - i];
  };
  for (int k = 0; k < 4; ++k) {
    const std::size_t at = (k / 2) * 72 + (k % 2) * 32;
    const double x = k == 3 ? std::numeric_limits<double>::quiet_NaN() : 1.5 + k, y = -2.0 * k, z = 0.25 * k;
    const std::uint16_t intensity = static_cast<std::uint16_t>(100 + k);
    const std::uint32_t t_ns = 1000u * static_cast<std::uint32_t>(k);
    be(at, &x, 8), be(at + 8, &y, 8), be(at + 16, &z, 8), be(at + 24, &intensity, 2), be(at + 28, &t_ns, 4);
  }
  data.resize(data.size() - cut);
  c.put<std::uint32_t>(static_cast<std::uint32_t>(data.size()));
  c.raw(data);
  c.put<std::uint8_t>(0);
  return c.bytes();
}

const std::vector<FieldSpec> kForeignFields = {{"x", 0, 8}, {"y", 8, 8}, {"z", 16, 8}, {"intensity", 24, 4}, {"t", 28, 6}};

// Why a cloud is refused, "damaged: " first when its bytes end early (one sample lost, skipped).
std::string refusal(const std::vector<unsigned char>& b) {
  try {
    read_pointcloud2(b.data(), b.size());
  } catch (const DamagedSample& e) {
    return std::string("damaged: ") + e.what();
  } catch (const BadPointCloud2& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(Ros2PointCloud, OurCloudsRoundTripExactly) {
  CloudColumns c;
  c.stamp_ns = -1'250'000'000;  // before the epoch: seconds down, nanoseconds up
  c.frame_id = "lidar_front";
  for (int i = 0; i < 1000; ++i) {
    c.x.push_back(0.1f * i), c.y.push_back(-0.3f * i), c.z.push_back(1e-3f * i);
    c.intensity.push_back(static_cast<float>(i % 256)), c.time_offset.push_back(1e-4f * i);
  }
  const auto bytes = write_pointcloud2(c);
  const CloudColumns back = read_pointcloud2(bytes.data(), bytes.size());
  EXPECT_EQ(back.stamp_ns, c.stamp_ns);
  EXPECT_EQ(back.frame_id, c.frame_id);
  EXPECT_EQ(back.x, c.x);
  EXPECT_EQ(back.y, c.y);
  EXPECT_EQ(back.z, c.z);
  EXPECT_EQ(back.intensity, c.intensity);
  EXPECT_EQ(back.time_offset, c.time_offset);
  c.intensity.clear(), c.time_offset.clear();
  const auto plain = write_pointcloud2(c);
  const CloudColumns bare = read_pointcloud2(plain.data(), plain.size());
  EXPECT_TRUE(bare.intensity.empty() && bare.time_offset.empty());
  EXPECT_EQ(bare.z, c.z);
}

TEST(Ros2PointCloud, AnotherDriversLayoutIsReadByItsFields) {
  const auto b = foreign_cloud(kForeignFields);
  const CloudColumns c = read_pointcloud2(b.data(), b.size());
  EXPECT_EQ(c.stamp_ns, 12'500'000'000);
  EXPECT_EQ(c.frame_id, "os_lidar");
  ASSERT_EQ(c.x.size(), 3u) << "the point with no return left out";
  EXPECT_EQ(c.x, (std::vector<float>{1.5f, 2.5f, 3.5f}));
  EXPECT_EQ(c.y, (std::vector<float>{0.0f, -2.0f, -4.0f}));
  EXPECT_EQ(c.z, (std::vector<float>{0.0f, 0.25f, 0.5f}));
  EXPECT_EQ(c.intensity, (std::vector<float>{100, 101, 102}));
  ASSERT_EQ(c.time_offset.size(), 3u);
  EXPECT_FLOAT_EQ(c.time_offset[2], 2e-6f) << "UINT32 t is nanoseconds";
}

TEST(Ros2PointCloud, WhatDoesNotFitIsRefusedNamed) {
  EXPECT_EQ(refusal(foreign_cloud({{"x", 0, 8}, {"y", 8, 8}, {"intensity", 24, 4}})), "PointCloud2: no field 'z' (fields: x, y, intensity)");
  EXPECT_EQ(refusal(foreign_cloud({{"x", 0, 8}, {"y", 8, 8}, {"z", 16, 8}, {"intensity", 31, 4}})),
            "PointCloud2: field 'intensity' (2 bytes at 31) is past the point step 32");
  EXPECT_EQ(refusal(foreign_cloud({{"x", 0, 5}, {"y", 8, 8}, {"z", 16, 8}})), "PointCloud2: field 'x' is not FLOAT32 or FLOAT64 (datatype 5)");
  EXPECT_EQ(refusal(foreign_cloud({{"x", 0, 9}, {"y", 8, 8}, {"z", 16, 8}})), "PointCloud2: field 'x' has datatype 9, none of 1 to 8");
  EXPECT_EQ(refusal(foreign_cloud(kForeignFields, 40)), "PointCloud2: 2 x 2 points of 40 bytes, rows of 72: a row shorter than its points");
  EXPECT_EQ(refusal(foreign_cloud(kForeignFields, 32, 10)), "damaged: PointCloud2: 2 x 2 points of 32 bytes, rows of 72, in 134 bytes of data");
  auto cut = foreign_cloud(kForeignFields);
  cut.resize(40);
  EXPECT_EQ(refusal(cut).rfind("damaged: ", 0), 0u) << refusal(cut);
  EXPECT_NE(refusal(cut).find("runs past the sample's 40 bytes"), std::string::npos) << refusal(cut);
  EXPECT_EQ(refusal({0x00, 0x01}), "damaged: PointCloud2: 2 bytes, no CDR header");
  // A count of fields the sample cannot hold (found by fuzz_ros2_sensors: 4 billion fields were 200 GB).
  const std::vector<unsigned char> many = {0x00, 0x01, 0x00, 0x00,  // CDR, little-endian
                                           0, 0, 0, 0, 0, 0, 0, 0,  // stamp
                                           1, 0, 0, 0, 0, 0, 0, 0,  // frame_id "" and its padding
                                           1, 0, 0, 0, 1, 0, 0, 0,  // height, width
                                           0xff, 0xff, 0xff, 0xff};  // fields: 4 294 967 295 of them
  EXPECT_EQ(refusal(many), "damaged: PointCloud2: fields' count at byte 32 runs past the sample's 32 bytes");
}

// A cloud of no points however many empty rows it claims is read as empty, at once (found by
// fuzz_ros2_sensors: 4 billion rows of width 0 held the reader for minutes).
TEST(Ros2PointCloud, NoPointsInManyEmptyRowsIsReadAtOnce) {
  std::vector<unsigned char> b;
  CdrWriter w(b);
  w.put_header(0, "lidar");
  w.put<std::uint32_t>(0xFFFFFFFFu);  // height
  w.put<std::uint32_t>(0);            // width
  w.put<std::uint32_t>(3);
  for (std::uint32_t k = 0; k < 3; ++k)  // x, y, z: FLOAT32 (7) at 0, 4, 8
    w.put_string(std::string(1, static_cast<char>('x' + k))), w.put<std::uint32_t>(4 * k), w.put<std::uint8_t>(7), w.put<std::uint32_t>(1);
  w.put<std::uint8_t>(0);   // little-endian
  w.put<std::uint32_t>(12);  // point step
  w.put<std::uint32_t>(0);   // row step
  w.put<std::uint32_t>(0);   // no data
  w.put<std::uint8_t>(1);
  const auto c = read_pointcloud2(b.data(), b.size());
  EXPECT_TRUE(c.x.empty());
  EXPECT_EQ(c.frame_id, "lidar");
}
