#pragma once
/// @file events.hpp
/// The `events` region: a ring of the core's state transitions and faults, so that monitors
/// (the LCM bridge) see every event even if they read only every few cycles.
///
/// One writer (the core's CLOCK thread). An entry is filled, then stamped with its 1-based index
/// in the event sequence (release), then `head` is advanced (release). A reader keeps its own
/// position; entries it did not read before the writer came round again are reported as lost,
/// never as wrong: a reader re-checks an entry's stamp after copying it.
#include <array>
#include <atomic>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::shm {

/// What an event says. `code` and `value` depend on the kind.
enum class EventKind : std::uint32_t {
  kNone = 0,
  kCoreState = 1,      ///< code: CoreState entered, value: StopReason (0 while running)
  kPower = 2,          ///< code: 1 powered, 0 unpowered
  kEmergencyStop = 3,  ///< code: 1 latched, 0 reset
  kDegraded = 4,       ///< code: 1 the degraded SERVO ran this cycle, 0 the main one is back
  kClientSession = 5,  ///< value: the new session id (0: no session)
  kClientStale = 6,    ///< code: 1 client data stale (extrapolating/fading), 0 fresh again;
                       ///< debounced: reported once the state has held 20 ms, value: how
                       ///< many shorter lapses (a lost sample or two) came since the last
  kCoupling = 7,       ///< code: 1 coupling active, 0 inactive
};

/// Stable short names of EventKind values, for telemetry and logs.
[[nodiscard]] const char* event_kind_name(EventKind kind) noexcept;

inline constexpr std::size_t kEventRingSize = 256;

struct EventEntry {
  std::atomic<std::uint64_t> stamp{0};  ///< 1-based index in the event sequence, set last
  std::atomic<std::uint64_t> cycle{0};
  std::atomic<std::int64_t> time_ns{0};  ///< CLOCK_MONOTONIC
  std::atomic<std::uint32_t> kind{0};
  std::atomic<std::uint32_t> code{0};
  std::atomic<std::uint64_t> value{0};
};

struct EventRing {
  std::atomic<std::uint64_t> head{0};  ///< events written so far
  std::array<EventEntry, kEventRingSize> entries;
};

/// A plain copy of one event.
struct Event {
  std::uint64_t index = 0;  ///< 1-based position in the core's event sequence
  std::uint64_t cycle = 0;
  std::int64_t time_ns = 0;
  EventKind kind = EventKind::kNone;
  std::uint32_t code = 0;
  std::uint64_t value = 0;
};

/// Appends an event. Real-time contract: wait-free, no syscall; one writer only.
HAPTICCTRL_RT void push_event(EventRing& ring, std::uint64_t cycle, std::int64_t time_ns,
                              EventKind kind, std::uint32_t code, std::uint64_t value) noexcept;

/// A reader's position in the ring.
class EventReader {
 public:
  /// Starts after the events already in the ring (`from_start`: with the oldest still there).
  explicit EventReader(const EventRing& ring, bool from_start = false) noexcept;

  /// Calls `sink(const Event&)` for each new event in order. Returns how many were delivered.
  /// Real-time contract: wait-free, no syscall.
  template <typename Sink>
  std::uint64_t poll(Sink&& sink) noexcept {
    std::uint64_t delivered = 0;
    Event e;
    while (next(e)) {
      sink(e);
      ++delivered;
    }
    return delivered;
  }

  /// Events overwritten before this reader got to them.
  [[nodiscard]] std::uint64_t lost() const noexcept { return lost_; }

 private:
  bool next(Event& out) noexcept;

  const EventRing* ring_;
  std::uint64_t position_ = 0;  ///< events consumed (or skipped as lost)
  std::uint64_t lost_ = 0;
};

}  // namespace hapticctrl::shm
