#pragma once
/// Per-session network statistics from the answer stream (internal to the client library).
/// Real-time contract: noexcept, no allocation; not thread-safe (the caller serialises).
#include <cstdint>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

class LinkMonitor {
 public:
  /// The controller's period: the expected answer inter-arrival time.
  void set_period(std::int64_t period_ns) noexcept { period_ns_ = period_ns; }

  /// Accounts one decoded answer. Returns false if it is late (not newer than the last one),
  /// in which case the caller drops it.
  bool on_answer(std::uint32_t answer_sequence, std::int64_t now_ns, std::uint32_t echo_sequence,
                 std::int64_t echo_time_ns, std::uint32_t control_received) noexcept;
  void on_invalid() noexcept { ++stats_.frames_invalid; }

  /// Statistics so far; `control_sent` is kept by the sender and merged in.
  [[nodiscard]] LinkStatistics statistics(std::uint64_t control_sent) const noexcept;

 private:
  LinkStatistics stats_{};
  std::int64_t period_ns_ = 1'000'000;
  bool have_answer_ = false;
  std::uint32_t last_sequence_ = 0;
  std::int64_t last_arrival_ns_ = 0;
  std::uint64_t interarrival_count_ = 0;
  bool have_echo_ = false;
  std::uint32_t last_echo_ = 0;
};

}  // namespace hapticctrl::client
