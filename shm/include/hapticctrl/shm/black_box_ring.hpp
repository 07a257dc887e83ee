#pragma once
/// @file black_box_ring.hpp
/// The `blackbox` region: the core's last cycles kept in the segment as well as in its own
/// memory, so that a core that is killed or crashes (no fail-safe, no file of its own) leaves
/// them to whoever still maps the segment: the UDP bridge writes them out when it finds the core
/// lost (docs/rt_core.md, J4: before, a killed core left no black box at all).
///
/// One writer (the core's CLOCK thread). A slot is filled, then stamped with its 1-based index
/// in the record sequence (release), then `head` is advanced (release). A reader copies a slot
/// and re-checks its stamp: a slot the writer came round to meanwhile is left out, never torn.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::shm {

/// One cycle as the core's CLOCK saw it (and the state the SERVO committed).
struct CycleRecord {
  std::uint64_t cycle = 0;
  std::int64_t scheduled = 0;           ///< ns, CLOCK_MONOTONIC
  std::int64_t wake_latency = 0;        ///< ns
  std::int64_t servo_start_delay = -1;  ///< ns; -1: the main SERVO did not start
  std::int64_t servo_execution = -1;    ///< ns; -1: no main commit by the check
  std::uint32_t flags = 0;              ///< kRecord* bits
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

/// Slots of the ring: 4.1 s of cycles at 1 ms, 0.41 s at 100 µs (656 KiB of the segment).
inline constexpr std::size_t kBlackBoxSlots = 4096;
inline constexpr std::size_t kRecordWords = sizeof(CycleRecord) / sizeof(std::uint64_t);
static_assert(sizeof(CycleRecord) % sizeof(std::uint64_t) == 0, "a record is whole words");
static_assert(std::is_trivially_copyable_v<CycleRecord>, "copied word by word");

struct BlackBoxSlot {
  std::atomic<std::uint64_t> stamp{0};  ///< 1-based index in the record sequence, set last
  std::array<std::atomic<std::uint64_t>, kRecordWords> words{};
};

struct BlackBoxRing {
  std::atomic<std::uint64_t> head{0};  ///< records written so far
  std::array<BlackBoxSlot, kBlackBoxSlots> slots;
};

/// Appends a record. Real-time contract: wait-free, no syscall; one writer only.
HAPTICCTRL_RT void push_cycle_record(BlackBoxRing& ring, const CycleRecord& record) noexcept;

/// The records still in the ring, oldest first. Not for the cycle (allocates).
[[nodiscard]] std::vector<CycleRecord> read_cycle_records(const BlackBoxRing& ring);

/// Records as CSV text, a header line first (the format of every black box). Not for the cycle.
[[nodiscard]] std::string cycle_records_csv(const std::vector<CycleRecord>& records);

}  // namespace hapticctrl::shm
