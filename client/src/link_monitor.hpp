#pragma once
/// Per-session network statistics from the answer stream (internal to the client library).
/// Real-time contract: noexcept, no allocation; not thread-safe (the caller serialises).
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

class LinkMonitor {
 public:
  /// The controller's period: the expected answer inter-arrival time.
  void set_period(Duration period) noexcept { period_ = period; }

  /// Accounts one decoded answer arriving at `now` that echoes the control frame sent at
  /// `echo_sent` (the epoch: none). Returns false if it is late (not newer than the last one),
  /// in which case the caller drops it.
  bool on_answer(std::uint32_t answer_sequence, TimePoint now, std::uint32_t echo_sequence,
                 TimePoint echo_sent, std::uint32_t control_received) noexcept;
  void on_invalid() noexcept { ++stats_.frames_invalid; }

  /// Statistics so far; `control_sent` is kept by the sender and merged in.
  [[nodiscard]] LinkStatistics statistics(std::uint64_t control_sent) const noexcept;

 private:
  LinkStatistics stats_{};
  Duration period_ = std::chrono::milliseconds(1);
  bool have_answer_ = false;
  std::uint32_t last_sequence_ = 0;
  TimePoint last_arrival_;
  std::uint64_t interarrival_count_ = 0;
  bool have_echo_ = false;
  std::uint32_t last_echo_ = 0;
};

}  // namespace hapticctrl::client
