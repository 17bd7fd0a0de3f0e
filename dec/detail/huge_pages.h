// dec/detail/huge_pages.h — asks the kernel to back a large, not yet touched buffer with transparent
// huge pages (Linux madvise MADV_HUGEPAGE; a no-op elsewhere and for buffers under 2 MB).
// First-touch page faults dominate the assembly of large meshes on virtual machines: measured
// here, one 4 KB fault costs ~13 us, so filling 32 MB takes ~100 ms with 4 KB pages and ~10 ms
// with 2 MB pages (docs/benchmarks.md). Call it right after allocating, before writing. The
// environment variable POLYDEC_NO_HUGE_PAGES (any value) turns it off, to measure its effect.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace polydec {

inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
  static const bool disabled = std::getenv("POLYDEC_NO_HUGE_PAGES") != nullptr;  // read once
  if (bytes < kHuge || disabled) return;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

// v set to n copies of `value` in fresh storage advised as above before its first write (v's
// previous storage is released first).
template <class T>
void assign_on_huge_pages(std::vector<T>& v, std::size_t n, const T& value = T()) {
  std::vector<T>().swap(v);
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  v.assign(n, value);
}

// An array of n default-initialized T (trivial T: not written, so no zeroing pass) advised as
// above, for scratch that the caller fills completely before reading it.
template <class T>
std::unique_ptr<T[]> uninitialized_on_huge_pages(std::size_t n) {
  std::unique_ptr<T[]> a(new T[n]);
  advise_huge_pages(a.get(), n * sizeof(T));
  return a;
}

}  // namespace polydec
