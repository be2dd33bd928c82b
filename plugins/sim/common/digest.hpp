#pragma once
// A run's fingerprint over the bytes of published values, reported as a metric so that reruns
// with the same seed can be compared bit for bit. FNV-1a style, but eight bytes per step with a
// xor-shift after each multiply, in four independent lanes: byte by byte it cost 14% of a LiDAR
// frame (272 KB per frame), one multiply chain 4%.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

namespace brickyard::sim {

class Digest {
 public:
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    // The lanes in locals: kept in the member array, every step went through memory (a store and
    // a reload on each lane's chain), which made the digest 4 % of a simulator run.
    std::uint64_t a = h_[0], b = h_[1], c = h_[2], d = h_[3];
    for (; i + 32 <= n; i += 32) {
      mix(a, word(p + i));
      mix(b, word(p + i + 8));
      mix(c, word(p + i + 16));
      mix(d, word(p + i + 24));
    }
    h_[0] = a; h_[1] = b; h_[2] = c; h_[3] = d;
    for (; i + 8 <= n; i += 8) mix(h_[0], word(p + i));
    for (; i < n; ++i) mix(h_[0], p[i]);
  }
  void add(double v) { add(&v, sizeof v); }
  std::string hex() const {
    std::uint64_t h = h_[0];
    for (int l = 1; l < 4; ++l) mix(h, h_[l]);
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
    return b;
  }

 private:
  static std::uint64_t word(const unsigned char* p) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    return w;
  }
  static void mix(std::uint64_t& h, std::uint64_t w) {
    h = (h ^ w) * 0x9E3779B97F4A7C15ull;
    h ^= h >> 29;
  }
  std::uint64_t h_[4] = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull, 0x9ce484222325cbf2ull, 0x2325cbf29ce48422ull};
};

}  // namespace brickyard::sim
