#pragma once
// FNV-1a, 64 bit: a fast, stable digest of bytes — for identifying what a file was built from
// and for comparing runs bit for bit. Not a cryptographic hash. Framework-free, header-only.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace brickyard::math {

class Fnv1a {
 public:
  static constexpr std::uint64_t offset_basis = 1469598103934665603ull;
  static constexpr std::uint64_t prime = 1099511628211ull;

  void add(const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * prime;
  }
  void add(std::string_view s) { add(s.data(), s.size()); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = offset_basis;
};

inline std::uint64_t fnv1a(std::string_view s) {
  Fnv1a h;
  h.add(s);
  return h.value();
}

}  // namespace brickyard::math
