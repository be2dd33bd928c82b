#pragma once
// A CDR sample read field by field (XCDR1, as ROS 2 and Fast DDS write it): its 4-byte
// encapsulation header first (its byte order), each primitive aligned to its size from after the
// header. For the ROS 2 types read without generated code (ros2_pointcloud.hpp,
// ros2_sensors.hpp). A read past the end throws DamagedSample naming the message, the field and
// the byte ("NavSatFix: latitude at byte 28 runs past the sample's 30 bytes").
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace brickyard::cdr {

inline bool host_little() {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

// A value of `n` (at most 8) bytes at p, in `little` byte order, into host order (or, the same
// swap, host order into that byte order).
inline void load(void* out, const unsigned char* p, std::size_t n, bool little) {
  unsigned char b[8];
  for (std::size_t i = 0; i < n; ++i) b[i] = p[little == host_little() ? i : n - 1 - i];
  std::memcpy(out, b, n);
}

// A sample whose bytes end before its type does (cut short, or no CDR at all): one message lost, not
// a stream of the wrong shape. A player counts it, names the first, and goes on.
class DamagedSample : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class CdrReader {
 public:
  // `message`: the type's name, said in every error.
  CdrReader(const unsigned char* data, std::size_t size, std::string message) : p_(data), size_(size), message_(std::move(message)) {
    if (size < 4) throw DamagedSample(message_ + ": " + std::to_string(size) + " bytes, no CDR header");
    little_ = (data[1] & 1) != 0;
  }
  template <class T>
  T get(const char* what) {
    align(sizeof(T));
    need(sizeof(T), what);
    T v;
    load(&v, p_ + at_, sizeof(T), little_);
    at_ += sizeof(T);
    return v;
  }
  std::string string(const char* what) {
    const auto n = get<std::uint32_t>(what);
    need(n, what);
    std::string s(reinterpret_cast<const char*>(p_ + at_), n ? n - 1 : 0);  // without its NUL
    at_ += n;
    return s;
  }
  // A sequence's length, each element at least `min_bytes` long: one the sample's bytes cannot hold
  // is damage, found before anything is made for it (a count of 4 billion is not 200 GB).
  std::uint32_t count(const char* what, std::size_t min_bytes) {
    const auto n = get<std::uint32_t>(what);
    need(static_cast<std::size_t>(n) * min_bytes, what);
    return n;
  }
  // A byte sequence: where its bytes start and how many.
  std::pair<const unsigned char*, std::size_t> bytes(const char* what) {
    const auto n = get<std::uint32_t>(what);
    need(n, what);
    const unsigned char* start = p_ + at_;
    at_ += n;
    return {start, n};
  }
  // builtin_interfaces/Time (int32 sec, uint32 nanosec) as nanoseconds.
  std::int64_t time_ns(const char* what) {
    const auto sec = get<std::int32_t>(what);
    const auto nanosec = get<std::uint32_t>(what);
    return static_cast<std::int64_t>(sec) * 1'000'000'000 + nanosec;
  }

 private:
  void align(std::size_t n) { at_ += (n - (at_ - 4) % n) % n; }
  void need(std::size_t n, const char* what) const {
    if (at_ > size_ || size_ - at_ < n)
      throw DamagedSample(message_ + ": " + what + " at byte " + std::to_string(at_) + " runs past the sample's " + std::to_string(size_) + " bytes");
  }
  const unsigned char* p_;
  std::size_t size_, at_ = 4;
  std::string message_;
  bool little_ = true;
};

}  // namespace brickyard::cdr
