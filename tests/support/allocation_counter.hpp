#pragma once
/// A counting global operator new for allocation-free proofs. It replaces the program's
/// allocator (shared libraries included), so include this header in exactly one source file of
/// a test executable; arm it around the code under test:
///   test::allocations = 0; test::counting = true; ...; test::counting = false;
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace hapticctrl::test {
inline std::atomic<bool> counting{false};
inline std::atomic<std::uint64_t> allocations{0};
#if defined(HAPTICCTRL_TSAN)
/// clang's ThreadSanitizer runtime, linked statically, defines the global operator new itself,
/// so a replacement cannot link there: the allocation proofs run in the plain and ASan builds.
inline constexpr bool kCountsAllocations = false;
#else
inline constexpr bool kCountsAllocations = true;
#endif
}  // namespace hapticctrl::test

#if !defined(HAPTICCTRL_TSAN)

// GCC pairs our malloc-backed new with free() and warns; the pairing is exactly what we want.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

// NOLINTBEGIN(misc-definitions-in-headers): the replacement must be defined once per program.
void* operator new(std::size_t size) {
  if (hapticctrl::test::counting.load(std::memory_order_relaxed)) {
    hapticctrl::test::allocations.fetch_add(1, std::memory_order_relaxed);
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t /*size*/) noexcept {
  std::free(p);
}
// NOLINTEND(misc-definitions-in-headers)
#endif
