// Implements core_watch.hpp: how an attached process (the bridges) follows the core's cycles and
// notices within a few milliseconds that the core is gone: killed, crashed or replaced by a new
// core.
#include "hapticctrl/shm/core_watch.hpp"

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::shm {

CoreWatch::Wake CoreWatch::wait() {
  const auto& vp = segment_->region<RegionId::kVp>();
  if (vp.wait_for_publish(vp.sequence_word(), poll_) == WaitStatus::kPublished) {
    return Wake::kCycle;
  }
  if (segment_->still_current()) {  // the core still runs, and its segment is live
    return Wake::kSilent;
  }
  const SegmentHeader& header = segment_->header();
  last_cycle_ = header.heartbeat_cycle.load(std::memory_order_acquire);
  age_at_loss_ = MonotonicClock::now() -
                 time_point_from_ns(header.heartbeat_ns.load(std::memory_order_acquire));
  stop_reason_ = header.stop_reason.load(std::memory_order_acquire);
  if (stop_reason_ == static_cast<std::uint32_t>(StopReason::kNone)) {
    stop_reason_ = static_cast<std::uint32_t>(StopReason::kCoreLost);
  }
  return Wake::kCoreGone;
}

}  // namespace hapticctrl::shm
