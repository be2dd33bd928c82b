#pragma once
// An open-addressing hash map from 64-bit cell keys to small values: the "hash table that holds
// occupied cells only" of the paper's ground filter, reused by the voxel filter and the
// clustering. Linear probing, power-of-two capacity, at most half full (it doubles when an insert
// would pass that), no deletion; cleared and reused per frame so a frame allocates nothing once
// the table has grown. Sized by a hint (the last frame's count), not by the worst case: a table
// sized for every point of a frame when a fifth of them make voxels would be cleared and missed
// in cache for nothing.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace brickyard::perception {

template <class V> class CellMap {
 public:
  // Empties the map and sizes it for about n keys at most half full.
  void reset(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap <<= 1;
    if (slots_.size() != cap) {
      slots_.assign(cap, Slot{kEmpty, V{}});
    } else {
      for (auto& s : slots_) s.key = kEmpty;
    }
    mask_ = cap - 1;
    size_ = 0;
  }
  // The value of key, inserted as `init` when absent; `inserted` tells which. The reference holds
  // until the next insert.
  V& find_or_insert(std::uint64_t key, const V& init, bool& inserted) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    std::size_t i = slot(key);
    while (slots_[i].key != kEmpty && slots_[i].key != key) i = (i + 1) & mask_;
    inserted = slots_[i].key == kEmpty;
    if (inserted) {
      slots_[i] = Slot{key, init};
      ++size_;
    }
    return slots_[i].value;
  }
  // Starts loading the slot where `key` would be: called a few keys ahead of find_or_insert, it
  // hides the cache miss that a scattered hash makes of every point.
  void prefetch(std::uint64_t key) const { __builtin_prefetch(&slots_[slot(key)]); }
  // Null when absent.
  const V* find(std::uint64_t key) const {
    std::size_t i = slot(key);
    while (slots_[i].key != kEmpty) {
      if (slots_[i].key == key) return &slots_[i].value;
      i = (i + 1) & mask_;
    }
    return nullptr;
  }
  std::size_t size() const { return size_; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  void grow() {
    std::vector<Slot> old(std::max<std::size_t>(32, 2 * slots_.size()), Slot{kEmpty, V{}});
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.key == kEmpty) continue;
      std::size_t i = slot(s.key);
      while (slots_[i].key != kEmpty) i = (i + 1) & mask_;
      slots_[i] = s;
    }
  }
  std::size_t slot(std::uint64_t key) const {
    key ^= key >> 33;
    key *= 0xff51afd7ed558ccdull;
    key ^= key >> 33;
    return static_cast<std::size_t>(key) & mask_;
  }
  struct Slot {  // key and value side by side: one cache line per probe
    std::uint64_t key;
    V value;
  };
  std::vector<Slot> slots_;
  std::size_t mask_ = 0, size_ = 0;
};

}  // namespace brickyard::perception
