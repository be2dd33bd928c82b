#pragma once
// An open-addressing hash map from 64-bit cell keys to small values: the "hash table that holds
// occupied cells only" of the paper's ground filter, reused by the voxel filter and the
// clustering. Linear probing, power-of-two capacity, no deletion; cleared and reused per frame so
// a frame allocates nothing once the table has grown.
#include <cstdint>
#include <vector>

namespace brickyard::perception {

template <class V> class CellMap {
 public:
  // Empties the map and sizes it for at least n keys at most half full.
  void reset(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap <<= 1;
    if (keys_.size() != cap) {
      keys_.assign(cap, kEmpty);
      values_.resize(cap);
    } else {
      std::fill(keys_.begin(), keys_.end(), kEmpty);
    }
    mask_ = cap - 1;
    size_ = 0;
  }
  // The value of key, inserted as `init` when absent; `inserted` tells which.
  V& find_or_insert(std::uint64_t key, const V& init, bool& inserted) {
    std::size_t i = slot(key);
    while (keys_[i] != kEmpty && keys_[i] != key) i = (i + 1) & mask_;
    inserted = keys_[i] == kEmpty;
    if (inserted) {
      keys_[i] = key;
      values_[i] = init;
      ++size_;
    }
    return values_[i];
  }
  // Null when absent.
  V* find_mutable(std::uint64_t key) { return const_cast<V*>(find(key)); }
  const V* find(std::uint64_t key) const {
    std::size_t i = slot(key);
    while (keys_[i] != kEmpty) {
      if (keys_[i] == key) return &values_[i];
      i = (i + 1) & mask_;
    }
    return nullptr;
  }
  std::size_t size() const { return size_; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t slot(std::uint64_t key) const {
    key ^= key >> 33;
    key *= 0xff51afd7ed558ccdull;
    key ^= key >> 33;
    return static_cast<std::size_t>(key) & mask_;
  }
  std::vector<std::uint64_t> keys_;
  std::vector<V> values_;
  std::size_t mask_ = 0, size_ = 0;
};

}  // namespace brickyard::perception
