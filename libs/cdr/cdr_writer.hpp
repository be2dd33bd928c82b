#pragma once
// A CDR sample written field by field (XCDR1, little-endian, as ROS 2 and Fast DDS write it): its
// 4-byte encapsulation header first, each primitive aligned to its size from after the header.
// For the ROS 2 types written without generated code (ros2_pointcloud.hpp, ros2_geometry.hpp).
#include "cdr/cdr_reader.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::cdr {

class CdrWriter {
 public:
  // Writes into `out` from its start (its memory kept: a writer's next sample costs no allocation).
  explicit CdrWriter(std::vector<unsigned char>& out) : out_(out) { out_.assign({0x00, 0x01, 0x00, 0x00}); }  // CDR, little-endian

  template <class T> void put(T v) {
    align(sizeof(T));
    unsigned char b[sizeof(T)];
    load(b, reinterpret_cast<const unsigned char*>(&v), sizeof(T), true);  // host order to little-endian
    out_.insert(out_.end(), b, b + sizeof(T));
  }
  void put_string(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
  }
  // builtin_interfaces/Time (and Duration): whole seconds down, then the nanoseconds past them.
  void put_time(std::int64_t ns) {
    const std::int64_t nanosec = ((ns % 1'000'000'000) + 1'000'000'000) % 1'000'000'000;
    put<std::int32_t>(static_cast<std::int32_t>((ns - nanosec) / 1'000'000'000));
    put<std::uint32_t>(static_cast<std::uint32_t>(nanosec));
  }
  // std_msgs/Header.
  void put_header(std::int64_t stamp_ns, const std::string& frame_id) {
    put_time(stamp_ns);
    put_string(frame_id);
  }
  void align(std::size_t n) {
    while ((out_.size() - 4) % n) out_.push_back(0);
  }
  std::vector<unsigned char>& bytes() { return out_; }

 private:
  std::vector<unsigned char>& out_;
};

}  // namespace brickyard::cdr
