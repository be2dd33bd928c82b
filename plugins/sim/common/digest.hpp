#pragma once
// FNV-1a over the bytes of published values: a run's fingerprint, reported as a metric so that
// reruns with the same seed can be compared bit for bit.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

namespace brickyard::sim {

class Digest {
 public:
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
  }
  void add(double v) { add(&v, sizeof v); }
  std::string hex() const {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h_));
    return b;
  }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace brickyard::sim
