// An allocator for large arrays that are written in full right after they are made, and read
// by cache line: storage aligned to 64 bytes, elements default-initialised (not zeroed).
// Texture blocks are 64 bytes; malloc's 16-byte alignment would split every block over two
// cache lines, and value-initialising a texture's texels wrote it twice.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace tessera {

template <typename T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};

  CacheLineAllocator() = default;
  template <typename U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}

  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }  // not sized: clang lacks it by default

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
