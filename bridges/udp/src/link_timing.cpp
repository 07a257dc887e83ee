// Implements link_timing.hpp: how the bridge measures the client link (protocol 1.1,
// HCP_FEATURE_TIMING): each ANSWER's send time is logged by cycle.
#include "hapticctrl/udp_bridge/link_timing.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::udp_bridge {
namespace {

/// Averaging gains: the delay and jitter over about 16 frames (16 ms at 1 kHz), the loss rate
/// over about 256 frames (enough to tell 10 % from 1 % within a quarter second).
constexpr double kDelayGain = 1.0 / 16.0;
constexpr double kLossGain = 1.0 / 256.0;

}  // namespace

void AnswerLog::record(std::uint64_t cycle, TimePoint sent) noexcept {
  // Without fences (ThreadSanitizer does not model them): the entry's cycle is cleared before
  // the time changes and set after it, all release; a reader that saw the new time sees the
  // cleared or the new cycle on its second look, never the old one.
  Entry& e = entries_[cycle % kSize];
  e.cycle.store(0, std::memory_order_release);
  e.sent_ns.store(to_ns(sent), std::memory_order_release);
  e.cycle.store(cycle, std::memory_order_release);
  newest_.store(cycle, std::memory_order_release);
}

bool AnswerLog::sent_time(std::uint64_t cycle, TimePoint& sent) const noexcept {
  if (cycle == 0) {
    return false;
  }
  const Entry& e = entries_[cycle % kSize];
  if (e.cycle.load(std::memory_order_acquire) != cycle) {
    return false;
  }
  const std::int64_t t = e.sent_ns.load(std::memory_order_acquire);
  if (e.cycle.load(std::memory_order_acquire) != cycle) {
    return false;  // overwritten while read
  }
  sent = time_point_from_ns(t);
  return true;
}

SampleTiming LinkEstimator::time_sample(const protocol::AnswerEcho& echo, const AnswerLog& log,
                                        TimePoint arrival) noexcept {
  SampleTiming s;
  if (!echo.valid) {
    return s;
  }
  const std::uint64_t cycle = protocol::expand_cycle(echo.cycle_low, log.newest());
  TimePoint sent;
  if (!log.sent_time(cycle, sent) || arrival < sent) {
    return s;
  }
  s.measured = true;
  s.echo_cycle = cycle;
  // A client that claims a longer hold than the whole round trip lies or rounds: never below 0.
  s.round_trip = std::max(Duration::zero(), arrival - sent - Duration(echo.hold_ns));
  s.sample_time = arrival - s.round_trip / 2;
  return s;
}

void LinkEstimator::add(const SampleTiming& sample) noexcept {
  if (!sample.measured) {
    return;
  }
  const double one_way = static_cast<double>(to_ns(sample.round_trip)) / 2.0;
  if (!have_delay_) {
    have_delay_ = true;
    delay_ = one_way;
  } else {
    delay_ += (one_way - delay_) * kDelayGain;
    jitter_ += (std::abs(one_way - last_one_way_) - jitter_) * kDelayGain;
  }
  last_one_way_ = one_way;
}

void LinkEstimator::add_arrival(std::uint32_t lost) noexcept {
  // Each missing sequence number is one lost frame (n steps of the average towards 1 leave
  // (1 - gain)^n of the distance), this arrival one delivered frame.
  const double lost_steps = static_cast<double>(std::min<std::uint32_t>(lost, 1000));
  loss_ = 1.0 - (1.0 - loss_) * std::pow(1.0 - kLossGain, lost_steps);
  loss_ -= loss_ * kLossGain;
}

}  // namespace hapticctrl::udp_bridge
