// An allocator for large arrays that are written in full right after they are made, and read
// by cache line: storage aligned to 64 bytes, elements default-initialised (not zeroed).
// Texture blocks are 64 bytes; malloc's 16-byte alignment would split every block over two
// cache lines, and value-initialising a texture's texels wrote it twice.
// An array of 2 MiB or more starts on a 2 MiB boundary and asks the kernel for transparent
// huge pages (which it gives, where configured as `madvise` or `always`, to the whole 2 MiB
// pages inside it): a texture is read at random, and with 4 KiB pages its lookups also missed
// the TLB (DamagedHelmet, whose four 2048x2048 maps are 64 MiB, renders 1-2% faster; where
// fresh huge pages are slow to touch, as on this project's virtual machine, converting the
// maps takes up to as much longer, a cost that does not grow with the render:
// docs/performance.md).
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include <sys/mman.h>

namespace tessera {

template <typename T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;  // x86-64's
  static constexpr std::align_val_t kHugeAlignment{kHugePage};

  CacheLineAllocator() = default;
  template <typename U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes, kAlignment));
    void* p = ::operator new(bytes, kHugeAlignment);
    madvise(p, bytes, MADV_HUGEPAGE);  // advice: nothing to do if refused
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {  // not sized: clang lacks it by default
    if (n * sizeof(T) < kHugePage) ::operator delete(p, kAlignment);
    else ::operator delete(p, kHugeAlignment);
  }

  // resize(n) default-initialises: a trivial type is left as it is, to be written next.
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <typename U>
  bool operator==(const CacheLineAllocator<U>&) const { return true; }
  template <typename U>
  bool operator!=(const CacheLineAllocator<U>&) const { return false; }
};

}  // namespace tessera
