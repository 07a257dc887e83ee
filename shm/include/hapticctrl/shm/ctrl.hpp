#pragma once
/// @file ctrl.hpp
/// The `ctrl` region: control commands from several writer processes to the core.
///
/// Design (docs/shm.md has the full argument):
///  - The region holds kCtrlSlots independent slots. A writer process claims one slot (a
///    WriterClaim, so a dead writer's slot can be taken over) and is its only writer.
///  - A slot is a single-producer/single-consumer ring of kCtrlRingSize entries plus a
///    monotonically increasing `head` (commands published). An entry is filled first and made
///    visible by one release store of `head`, so a writer that dies mid-write leaves nothing
///    visible and blocks nothing.
///  - The core is the only consumer. It keeps its progress (`consumed`) in the separate
///    `ctrl_ack` region, which only the core writes and writers read, so a writer never
///    overwrites an entry the core has not consumed: no command is lost, and the core consumes a
///    slot strictly in order, so nothing is reordered per writer.
///  - An emergency stop must never be lost, even when the ring is full: the writer then counts it
///    in `estop_overflow_count` and records the ring position it belongs at
///    (`estop_overflow_at`). The core applies it exactly there in the sequence. While such an
///    overflowed stop is pending, the writer refuses other commands, so one position suffices.

#include <array>
#include <atomic>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::shm {

/// Command codes carried by ctrl entries. Unknown codes are rejected (and counted) by the core.
enum class CtrlCode : std::uint32_t {
  kNone = 0,
  kPowerOn = 1,
  kPowerOff = 2,
  kEmergencyStop = 3,
  kEmergencyReset = 4,
  kStop = 5,           ///< orderly stop of the controller
  kInjectOverrun = 6,  ///< fault injection: SERVO overruns for `arg` cycles (if enabled)
};

/// The `arg` of kPowerOn: who asks. 0: an operator (the HMI, and the LCM, DDS and web inputs
/// with their rules); kPowerOnByClient: a client application through the UDP bridge, refused
/// while the core awaits an operator after a restart (state_bits::kAwaitingOperator). Any
/// other value is refused.
inline constexpr std::uint32_t kPowerOnByOperator = 0;
inline constexpr std::uint32_t kPowerOnByClient = 1;

inline constexpr std::size_t kCtrlSlots = 8;
inline constexpr std::size_t kCtrlRingSize = 32;

/// One queued command.
struct CtrlEntry {
  std::atomic<std::uint32_t> code{0};
  std::atomic<std::uint32_t> arg{0};
  std::atomic<std::int64_t> issued_ns{0};  ///< writer's CLOCK_MONOTONIC time
};

/// One writer's queue.
struct alignas(64) CtrlSlot {
  std::atomic<std::uint64_t> head{0};  ///< commands published so far
  std::atomic<std::uint64_t> estop_overflow_count{0};
  std::atomic<std::uint64_t> estop_overflow_at{0};  ///< `head` when the last overflow happened
  std::array<CtrlEntry, kCtrlRingSize> ring;
};

/// The ctrl region (writers -> core).
struct CtrlRegion {
  std::array<CtrlSlot, kCtrlSlots> slots;
};

/// The core's progress on one slot.
struct alignas(64) CtrlSlotAck {
  std::atomic<std::uint64_t> consumed{0};             ///< entries consumed (== next index)
  std::atomic<std::uint64_t> estop_overflow_seen{0};  ///< overflow e-stops applied
  std::atomic<std::uint64_t> rejected{0};             ///< entries refused by validation
  std::atomic<std::uint32_t> last_rejected_code{0};
  std::atomic<std::uint32_t> reserved{0};
};

/// The ctrl_ack region (core -> writers).
struct CtrlAckRegion {
  std::array<CtrlSlotAck, kCtrlSlots> slots;
};

/// A decoded command, as handed to the core's handler.
struct CtrlCommand {
  std::size_t slot = 0;
  std::uint64_t index = 0;  ///< position in the slot's sequence
  CtrlCode code = CtrlCode::kNone;
  std::uint32_t arg = 0;
  std::int64_t issued_ns = 0;
};

/// Result of CtrlWriter::send().
enum class CtrlSendStatus : std::uint8_t {
  kQueued,  ///< published; the core will consume it in order
  kFull,    ///< ring full (or an overflowed e-stop is pending): retry later; never for e-stops
};

/// Writer side of one claimed slot. Constructed by Segment::open_ctrl_writer().
class CtrlWriter {
 public:
  CtrlWriter(CtrlSlot& slot, const CtrlSlotAck& ack, std::size_t index) noexcept
      : slot_(&slot), ack_(&ack), index_(index) {}

  /// Queues a command. Emergency stops always succeed. Returns the command's index in the slot
  /// sequence through `index_out` when queued.
  /// Real-time contract: wait-free, no syscall; safe anywhere.
  CtrlSendStatus send(CtrlCode code, std::uint32_t arg, std::int64_t now_ns,
                      std::uint64_t* index_out = nullptr) noexcept;

  /// True once the core has consumed every command up to and including `index`.
  [[nodiscard]] bool consumed(std::uint64_t index) const noexcept;

  /// Number of this slot's commands the core rejected.
  [[nodiscard]] std::uint64_t rejected() const noexcept;

  [[nodiscard]] std::size_t slot_index() const noexcept { return index_; }

 private:
  [[nodiscard]] bool overflow_estop_pending() const noexcept;

  CtrlSlot* slot_;
  const CtrlSlotAck* ack_;
  std::size_t index_;
};

/// Core side: consumes every slot in order. Only the core may use it.
class CtrlReader {
 public:
  CtrlReader(const CtrlRegion& region, CtrlAckRegion& acks) noexcept
      : region_(&region), acks_(&acks) {}

  /// Calls `handler(const CtrlCommand&) -> bool` for each new command, slot by slot, in order.
  /// The work is bounded by the ring size (at most kCtrlSlots * kCtrlRingSize calls). The
  /// handler returns false to reject a command (counted in the ack). Overflowed e-stops are
  /// delivered at their position in the sequence.
  /// Real-time contract: safe in the cycle if the handler is; no syscall, no allocation.
  template <typename Handler>
  HAPTICCTRL_RT void drain(Handler&& handler) noexcept {
    for (std::size_t s = 0; s < kCtrlSlots; ++s) {
      drain_slot(s, handler);
    }
  }

 private:
  template <typename Handler>
  void drain_slot(std::size_t s, Handler& handler) noexcept {
    const CtrlSlot& slot = region_->slots[s];
    CtrlSlotAck& ack = acks_->slots[s];
    std::uint64_t next = ack.consumed.load(std::memory_order_relaxed);
    const std::uint64_t head = slot.head.load(std::memory_order_acquire);
    if (head - next > kCtrlRingSize) {
      // Misbehaving writer overran the ring: the oldest entries are gone. Skip, count, go on.
      ack.rejected.fetch_add(head - next - kCtrlRingSize, std::memory_order_relaxed);
      next = head - kCtrlRingSize;
    }
    const std::uint64_t overflow_count = slot.estop_overflow_count.load(std::memory_order_acquire);
    const bool overflow_pending =
        overflow_count != ack.estop_overflow_seen.load(std::memory_order_relaxed);
    const std::uint64_t overflow_at = slot.estop_overflow_at.load(std::memory_order_relaxed);
    while (next < head) {
      if (overflow_pending && overflow_at <= next) {
        break;  // the overflowed e-stop comes first
      }
      const CtrlEntry& entry = slot.ring[next % kCtrlRingSize];
      const CtrlCommand command{s, next,
                                static_cast<CtrlCode>(entry.code.load(std::memory_order_relaxed)),
                                entry.arg.load(std::memory_order_relaxed),
                                entry.issued_ns.load(std::memory_order_relaxed)};
      if (!handler(command)) {
        ack.rejected.fetch_add(1, std::memory_order_relaxed);
        ack.last_rejected_code.store(static_cast<std::uint32_t>(command.code),
                                     std::memory_order_relaxed);
      }
      ++next;
      ack.consumed.store(next, std::memory_order_release);
    }
    if (overflow_pending && overflow_at <= next) {
      handler(CtrlCommand{s, next, CtrlCode::kEmergencyStop, 0, 0});
      ack.estop_overflow_seen.store(overflow_count, std::memory_order_release);
    }
  }

  const CtrlRegion* region_;
  CtrlAckRegion* acks_;
};

}  // namespace hapticctrl::shm
