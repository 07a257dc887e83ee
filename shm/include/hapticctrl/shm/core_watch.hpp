#pragma once
/// @file core_watch.hpp
/// How an attached process (the bridges) follows the core's cycles and notices within a few
/// milliseconds that the core is gone: killed, crashed or replaced by a new core.
///
/// Real-time contract: none of this is for the cycle (it blocks, and polls the core's pidfd).
#include <chrono>
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace hapticctrl::shm {

/// Waits for VP publishes; when none comes for `poll`, checks that the core still runs.
class CoreWatch {
 public:
  /// What ended a wait.
  enum class Wake : std::uint8_t {
    kCycle,     ///< the core published VP
    kSilent,    ///< nothing within `poll`, but the core still runs (slow period, stall)
    kCoreGone,  ///< the core's process has ended, or it stopped (the segment is no longer live)
  };

  /// 2 ms: with the 100 µs..10 ms periods of the core, a lost core is noticed within about
  /// 2 ms of its process ending (its pidfd turns readable at once), and a silent core costs a
  /// probe of about 1.4 µs per 2 ms (one poll of the pidfd, 1.37-1.48 µs, 2026-12-02).
  static constexpr std::chrono::milliseconds kDefaultPoll{2};

  explicit CoreWatch(const Segment& segment, std::chrono::nanoseconds poll = kDefaultPoll) noexcept
      : segment_(&segment), poll_(poll) {}

  /// Blocks until the next VP publish or `poll`; on silence, probes the core.
  Wake wait();

  /// How old the core's last heartbeat was when kCoreGone was returned [ns]: the time from the
  /// core's last cycle to this process noticing the loss.
  [[nodiscard]] Duration heartbeat_age_at_loss() const noexcept { return age_at_loss_; }
  /// The core's last heartbeat cycle, as seen when the loss was noticed.
  [[nodiscard]] std::uint64_t last_cycle() const noexcept { return last_cycle_; }
  /// Why the core ended (StopReason), as seen when kCoreGone was returned: the reason it
  /// recorded when it left its cycle in order, or StopReason::kCoreLost when it recorded none
  /// (killed, crashed).
  [[nodiscard]] std::uint32_t stop_reason() const noexcept { return stop_reason_; }

 private:
  const Segment* segment_;
  std::chrono::nanoseconds poll_;
  Duration age_at_loss_{};
  std::uint64_t last_cycle_ = 0;
  std::uint32_t stop_reason_ = 0;
};

}  // namespace hapticctrl::shm
