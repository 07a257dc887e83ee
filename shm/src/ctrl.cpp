// Implements ctrl.hpp: the `ctrl` region: control commands from several writer processes to the
// core.
#include "hapticctrl/shm/ctrl.hpp"

namespace hapticctrl::shm {

bool CtrlWriter::overflow_estop_pending() const noexcept {
  return slot_->estop_overflow_count.load(std::memory_order_relaxed) !=
         ack_->estop_overflow_seen.load(std::memory_order_acquire);
}

CtrlSendStatus CtrlWriter::send(CtrlCode code, std::uint32_t arg, std::int64_t now_ns,
                                std::uint64_t* index_out) noexcept {
  const std::uint64_t head = slot_->head.load(std::memory_order_relaxed);
  const std::uint64_t consumed = ack_->consumed.load(std::memory_order_acquire);
  const bool ring_full = head - consumed >= kCtrlRingSize;
  if (ring_full || overflow_estop_pending()) {
    if (code != CtrlCode::kEmergencyStop) {
      return CtrlSendStatus::kFull;
    }
    // Never lose an e-stop: record where it belongs, then count it (release publishes `at`).
    slot_->estop_overflow_at.store(head, std::memory_order_relaxed);
    slot_->estop_overflow_count.fetch_add(1, std::memory_order_release);
    if (index_out != nullptr) {
      *index_out = head;
    }
    return CtrlSendStatus::kQueued;
  }
  CtrlEntry& entry = slot_->ring[head % kCtrlRingSize];
  entry.code.store(static_cast<std::uint32_t>(code), std::memory_order_relaxed);
  entry.arg.store(arg, std::memory_order_relaxed);
  entry.issued_ns.store(now_ns, std::memory_order_relaxed);
  slot_->head.store(head + 1, std::memory_order_release);
  if (index_out != nullptr) {
    *index_out = head;
  }
  return CtrlSendStatus::kQueued;
}

bool CtrlWriter::consumed(std::uint64_t index) const noexcept {
  return ack_->consumed.load(std::memory_order_acquire) > index;
}

std::uint64_t CtrlWriter::rejected() const noexcept {
  return ack_->rejected.load(std::memory_order_acquire);
}

}  // namespace hapticctrl::shm
