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
}  // namespace hapticctrl::test

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
