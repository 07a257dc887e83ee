#pragma once
/// @file black_box.hpp
/// A preallocated ring of the last cycles' records, written out as CSV on fail-safe, so that
/// the seconds before a fault can be examined afterwards (the flight-recorder of the core).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/rt_core/private_directory.hpp"

namespace hapticctrl::rt_core {

/// One cycle as the CLOCK saw it (and the state the servo committed).
struct CycleRecord {
  std::uint64_t cycle = 0;
  TimeNs scheduled = 0;
  TimeNs wake_latency = 0;
  TimeNs servo_start_delay = -1;  ///< -1: the main SERVO did not start
  TimeNs servo_execution = -1;    ///< -1: no main commit by the check
  std::uint32_t flags = 0;        ///< kRecord* bits
  std::uint32_t state_word = 0;
  std::uint32_t consecutive_misses = 0;
  std::uint32_t skipped = 0;  ///< a stall record (kRecordStall): the slots it skipped; else 0
  std::array<double, 6> joint_position{};
  std::array<double, 6> joint_torque{};
};

inline constexpr std::uint32_t kRecordMiss = 1U << 0;
inline constexpr std::uint32_t kRecordDegraded = 1U << 1;
/// A late wake-up of the CLOCK that skipped slots (a stall): no SERVO ran; `skipped` slots were
/// counted as misses, `wake_latency` is how late it woke, `cycle` the last cycle that ran.
inline constexpr std::uint32_t kRecordStall = 1U << 2;

class BlackBox {
 public:
  /// Allocates room for `capacity` records (setup; the ring never allocates afterwards).
  explicit BlackBox(std::size_t capacity);

  /// Real-time contract: safe in the cycle (copies into the preallocated ring).
  void record(const CycleRecord& r) noexcept;

  [[nodiscard]] std::size_t size() const noexcept {
    return count_ < ring_.size() ? count_ : ring_.size();
  }
  [[nodiscard]] std::size_t capacity() const noexcept { return ring_.size(); }
  /// The i-th oldest record still held (0 = oldest).
  [[nodiscard]] const CycleRecord& at(std::size_t i) const noexcept;

  /// The records oldest first as CSV text. Not for the cycle (allocates).
  [[nodiscard]] std::string csv() const;

 private:
  std::vector<CycleRecord> ring_;
  std::size_t count_ = 0;
};

/// Writes `box` into `directory` as `hapticctrl-blackbox-<instance>.<pid>.csv` (a name already
/// there, a link included, is left alone: `.2`, `.3`, ... is appended), created exclusively with
/// mode 0600, then removes the instance's oldest black boxes there beyond `keep` (at least the
/// new one stays). Returns the new file's path. Not for the cycle; throws std::runtime_error.
std::string store_black_box(const BlackBox& box, const PrivateDirectory& directory,
                            const std::string& instance, int pid, std::size_t keep);

}  // namespace hapticctrl::rt_core
