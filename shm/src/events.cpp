// Implements events.hpp: the `events` region: a ring of the core's state transitions and faults, so
// that monitors (the LCM bridge) see every event even if they read only every few cycles.
#include "hapticctrl/shm/events.hpp"

namespace hapticctrl::shm {

const char* event_kind_name(EventKind kind) noexcept {
  switch (kind) {
    case EventKind::kCoreState:
      return "core_state";
    case EventKind::kPower:
      return "power";
    case EventKind::kEmergencyStop:
      return "emergency_stop";
    case EventKind::kDegraded:
      return "degraded";
    case EventKind::kClientSession:
      return "client_session";
    case EventKind::kClientStale:
      return "client_stale";
    case EventKind::kCoupling:
      return "coupling";
    case EventKind::kNone:
      break;
  }
  return "none";
}

void push_event(EventRing& ring, std::uint64_t cycle, std::int64_t time_ns, EventKind kind,
                std::uint32_t code, std::uint64_t value) noexcept {
  const std::uint64_t index = ring.head.load(std::memory_order_relaxed);
  EventEntry& e = ring.entries[index % kEventRingSize];
  // As in SeqlockCell, no fences (TSan does not model them): the fields are stored with release,
  // so a reader that sees any new field value also sees the stamp cleared before it.
  e.stamp.store(0, std::memory_order_relaxed);  // readers treat 0 as "being rewritten"
  e.cycle.store(cycle, std::memory_order_release);
  e.time_ns.store(time_ns, std::memory_order_release);
  e.kind.store(static_cast<std::uint32_t>(kind), std::memory_order_release);
  e.code.store(code, std::memory_order_release);
  e.value.store(value, std::memory_order_release);
  e.stamp.store(index + 1, std::memory_order_release);
  ring.head.store(index + 1, std::memory_order_release);
}

EventReader::EventReader(const EventRing& ring, bool from_start) noexcept : ring_(&ring) {
  const std::uint64_t head = ring.head.load(std::memory_order_acquire);
  position_ = from_start ? (head > kEventRingSize ? head - kEventRingSize : 0) : head;
}

bool EventReader::next(Event& out) noexcept {
  for (;;) {
    const std::uint64_t head = ring_->head.load(std::memory_order_acquire);
    if (position_ >= head) {
      return false;
    }
    if (head - position_ > kEventRingSize) {  // the writer came round: skip what is gone
      lost_ += head - kEventRingSize - position_;
      position_ = head - kEventRingSize;
    }
    const EventEntry& e = ring_->entries[position_ % kEventRingSize];
    const std::uint64_t want = position_ + 1;
    if (e.stamp.load(std::memory_order_acquire) != want) {
      ++lost_;  // overwritten between our head read and now
      ++position_;
      continue;
    }
    out.index = want;
    out.cycle = e.cycle.load(std::memory_order_acquire);
    out.time_ns = e.time_ns.load(std::memory_order_acquire);
    out.kind = static_cast<EventKind>(e.kind.load(std::memory_order_acquire));
    out.code = e.code.load(std::memory_order_acquire);
    out.value = e.value.load(std::memory_order_acquire);
    ++position_;
    if (e.stamp.load(std::memory_order_relaxed) != want) {
      ++lost_;  // rewritten while we copied: the copy is not trusted
      continue;
    }
    return true;
  }
}

}  // namespace hapticctrl::shm
