#pragma once
// ROS 2's sensor_msgs/msg/PointCloud2, in its CDR (what a rosbag2 file or a ROS 2 node carries),
// to a cloud's columns and back (issue 45: ROS 2 types at the edges; docs/ros2.md). Points are
// read by the fields the message names: x, y, z (FLOAT32 or FLOAT64) must be there; intensity
// (any numeric type) and t or time (a point's time from the stamp: FLOAT32/FLOAT64 seconds, or
// UINT32 nanoseconds, as Ouster's driver writes it) when they are. Framework-free.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::cdr {

struct CloudColumns {
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  std::vector<float> x, y, z, intensity, time_offset;  // intensity, time_offset: empty when the cloud has none
};

// A cloud whose fields do not make points: std::invalid_argument naming the field ("PointCloud2: no
// field 'z' (fields: x, y, intensity)"; "field 'intensity' (2 bytes at 31) is past the point step
// 32"). Bytes that end before the message does: cdr::DamagedSample (cdr_reader.hpp).
class BadPointCloud2 : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// One PointCloud2 sample's CDR (its 4-byte encapsulation header first, either endianness; the
// points' own byte order by is_bigendian). Data shorter than its rows: DamagedSample. Points whose x, y or z is not finite (a sensor's "no
// return") are left out.
CloudColumns read_pointcloud2(const unsigned char* cdr, std::size_t size);
// The same into `out`, its columns' memory kept (a player's next frame costs no allocation).
void read_pointcloud2(const unsigned char* cdr, std::size_t size, CloudColumns& out);

// The cloud as a PointCloud2 (little-endian CDR, encapsulation header first): fields x, y, z,
// intensity (FLOAT32) and t (FLOAT32, s from the stamp) when the cloud has them; height 1,
// is_dense true.
std::vector<unsigned char> write_pointcloud2(const CloudColumns& cloud);
// The same into `out`, its memory kept.
void write_pointcloud2(const CloudColumns& cloud, std::vector<unsigned char>& out);

}  // namespace brickyard::cdr
