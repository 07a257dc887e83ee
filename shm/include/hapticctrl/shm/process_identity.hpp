#pragma once
/// @file process_identity.hpp
/// A process identity that survives pid reuse: pid plus the process start time.

#include <sys/types.h>

#include <cstdint>
#include <optional>

namespace hapticctrl::shm {

/// pid plus start time (clock ticks since boot, /proc/<pid>/stat field 22).
struct ProcessIdentity {
  pid_t pid = 0;
  std::uint64_t start_ticks = 0;

  /// The calling process. Reads /proc once; not for the cycle.
  static ProcessIdentity self();

  /// Start time of `pid`, or nullopt when no such process exists.
  static std::optional<std::uint64_t> start_ticks_of(pid_t pid);

  /// True while this exact process (same pid, same start time) is alive.
  [[nodiscard]] bool alive() const;

  friend bool operator==(const ProcessIdentity&, const ProcessIdentity&) = default;
};

/// Packs an identity into one 64-bit word for an atomic claim: pid in the low 22 bits (Linux
/// pid_max is at most 2^22) and the low 42 bits of the start time above. 0 means "nobody".
[[nodiscard]] std::uint64_t pack_identity(const ProcessIdentity& id) noexcept;
[[nodiscard]] ProcessIdentity unpack_identity(std::uint64_t word) noexcept;
/// Liveness of a packed identity (compares the 42 stored bits of the start time).
[[nodiscard]] bool packed_identity_alive(std::uint64_t word);

}  // namespace hapticctrl::shm
