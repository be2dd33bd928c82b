#pragma once
// An open-addressing hash map from 64-bit (or 32-bit) cell keys to small values: the "hash table
// that holds occupied cells only" of the paper's ground filter, reused by the voxel filter and the
// clustering. Linear probing, power-of-two capacity, at most half full (it doubles when an insert
// would pass that), no deletion; cleared and reused per frame so a frame allocates nothing once
// the table has grown. Sized by a hint (the last frame's count), not by the worst case: a table
// sized for every point of a frame when a fifth of them make voxels would be cleared and missed
// in cache for nothing. 32-bit keys (a frame whose cells fit 31 bits, see packed_keys.hpp)
// halve the slots and hash with one multiply.
#include "huge_pages.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace brickyard::perception {

template <class V, class K = std::uint64_t> class CellMap {
  static_assert(std::is_same_v<K, std::uint64_t> || std::is_same_v<K, std::uint32_t>);
  static_assert(std::is_trivially_copyable_v<V>);

 public:
  // Empties the map and sizes it for about n keys at most half full.
  void reset(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap <<= 1;
    if (slots_.size() != cap) {
      slots_.assign(cap, Slot{kEmpty, V{}});
    } else {
      std::memset(slots_.data(), 0xff, cap * sizeof(Slot));  // every key kEmpty; values are unread
    }
    set_capacity(cap);
    size_ = 0;
  }
  // The value of key, inserted as `init` when absent; `inserted` tells which. The reference holds
  // until the next insert.
  V& find_or_insert(K key, const V& init, bool& inserted) {
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
  // Numbers a batch of keys in first-met order, continuing from size(): calls visit(j, number,
  // inserted) for each keys[j] other than `skip`. What find_or_insert does key by key, in one
  // loop that holds the table in locals and prefetches the slots kAhead keys early (the loads
  // that a scattered hash makes of every key overlap instead of queueing): a fifth faster on
  // the voxel filter's 50k points than calling find_or_insert and prefetch.
  template <class Visit> void number(const K* keys, std::size_t n, K skip, Visit&& visit) {
    constexpr std::size_t kAhead = 8;
    Slot* slots = slots_.data();
    std::size_t mask = mask_, size = size_;
    int shift = shift_;
    for (std::size_t j = 0; j < kAhead && j < n; ++j) __builtin_prefetch(&slots[slot(keys[j], mask, shift)]);
    for (std::size_t j = 0; j < n; ++j) {
      if (j + kAhead < n) __builtin_prefetch(&slots[slot(keys[j + kAhead], mask, shift)]);
      const K key = keys[j];
      if (key == skip) continue;
      std::size_t i = slot(key, mask, shift);
      while (slots[i].key != key && slots[i].key != kEmpty) i = (i + 1) & mask;
      const bool inserted = slots[i].key == kEmpty;
      if (inserted) {
        if (2 * (size + 1) > slots_.size()) {
          size_ = size;
          grow();
          slots = slots_.data(), mask = mask_, shift = shift_;
          i = slot(key, mask, shift);
          while (slots[i].key != kEmpty) i = (i + 1) & mask;
        }
        slots[i] = Slot{key, static_cast<V>(size++)};
      }
      visit(j, slots[i].value, inserted);
    }
    size_ = size;
  }
  // Starts loading the slot where `key` would be: called a few keys ahead of find_or_insert, it
  // hides the cache miss that a scattered hash makes of every point.
  void prefetch(K key) const { __builtin_prefetch(&slots_[slot(key)]); }
  // Null when absent.
  const V* find(K key) const {
    std::size_t i = slot(key);
    while (slots_[i].key != kEmpty) {
      if (slots_[i].key == key) return &slots_[i].value;
      i = (i + 1) & mask_;
    }
    return nullptr;
  }
  std::size_t size() const { return size_; }

 private:
  static constexpr K kEmpty = ~K{0};
  void set_capacity(std::size_t cap) {
    mask_ = cap - 1;
    shift_ = 32;
    while (cap > 1) cap >>= 1, --shift_;
  }
  void grow() {
    std::vector<Slot, HugePageAllocator<Slot>> old(std::max<std::size_t>(32, 2 * slots_.size()), Slot{kEmpty, V{}});
    old.swap(slots_);
    set_capacity(slots_.size());
    for (const Slot& s : old) {
      if (s.key == kEmpty) continue;
      std::size_t i = slot(s.key);
      while (slots_[i].key != kEmpty) i = (i + 1) & mask_;
      slots_[i] = s;
    }
  }
  std::size_t slot(K key) const { return slot(key, mask_, shift_); }
  static std::size_t slot(K key, std::size_t mask, int shift) {
    if constexpr (sizeof(K) == 4) {
      return static_cast<std::uint32_t>(key * 0x9e3779b1u) >> shift;  // Fibonacci: the product's top bits
    } else {
      key ^= key >> 33;
      key *= 0xff51afd7ed558ccdull;
      key ^= key >> 33;
      return static_cast<std::size_t>(key) & mask;
    }
  }
  struct Slot {  // key and value side by side: one cache line per probe
    K key;
    V value;
  };
  std::vector<Slot, HugePageAllocator<Slot>> slots_;
  std::size_t mask_ = 0, size_ = 0;
  int shift_ = 32;
};

}  // namespace brickyard::perception
