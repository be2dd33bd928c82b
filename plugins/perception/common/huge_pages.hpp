#pragma once
// An allocator for big tables read at random (a track map's voxel hash, its voxels): blocks of
// 2 MiB or more are 2 MiB-aligned and offered to the kernel's transparent huge pages
// (madvise MADV_HUGEPAGE; a hint, ignored where THP is off). Why: a lookup in a table of tens of
// MiB is a TLB miss on 4 KiB pages, and under a hypervisor a TLB miss walks two page tables; a
// prefetch does not hide it. Smaller blocks come from operator new as usual.
#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>

namespace brickyard::perception {

template <class T> struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHuge = std::size_t{2} << 20;

  HugePageAllocator() = default;
  template <class U> HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHuge) return static_cast<T*>(::operator new(bytes, std::align_val_t{alignof(T)}));
    const std::size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
    void* p = std::aligned_alloc(kHuge, rounded);
    if (!p) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // before the first touch: the pages fault in huge
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kHuge) ::operator delete(p, std::align_val_t{alignof(T)});
    else std::free(p);
  }
  template <class U> bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <class U> bool operator!=(const HugePageAllocator<U>&) const { return false; }
};

}  // namespace brickyard::perception
