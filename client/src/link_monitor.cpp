// Implements link_monitor.hpp: per-session network statistics from the answer stream (internal to
// the client library).
#include "link_monitor.hpp"

#include <algorithm>
#include <cmath>

#include "hapticctrl/protocol/codec.hpp"

namespace hapticctrl::client {

bool LinkMonitor::on_answer(std::uint32_t answer_sequence, TimePoint now,
                            std::uint32_t echo_sequence, TimePoint echo_sent,
                            std::uint32_t control_received) noexcept {
  if (have_answer_ && !protocol::sequence_newer(answer_sequence, last_sequence_)) {
    ++stats_.answers_late;
    return false;
  }
  if (have_answer_) {
    stats_.answers_lost += static_cast<std::uint32_t>(answer_sequence - last_sequence_) - 1U;
    const double gap_us = to_seconds(now - last_arrival_) * 1e6;
    ++interarrival_count_;
    stats_.interarrival_mean_us +=
        (gap_us - stats_.interarrival_mean_us) / static_cast<double>(interarrival_count_);
    stats_.interarrival_max_us = std::max(stats_.interarrival_max_us, gap_us);
    // RFC 3550 section 6.4.1: J += (|D| - J) / 16, D the deviation from the expected spacing.
    const double deviation = std::abs(gap_us - to_seconds(period_) * 1e6);
    stats_.jitter_us += (deviation - stats_.jitter_us) / 16.0;
  }
  have_answer_ = true;
  last_sequence_ = answer_sequence;
  last_arrival_ = now;
  ++stats_.answers_received;
  stats_.control_received_by_controller = control_received;

  // Round trip: the first answer that echoes a new control frame (later ones echo it again).
  if (echo_sent != TimePoint{} && (!have_echo_ || echo_sequence != last_echo_)) {
    have_echo_ = true;
    last_echo_ = echo_sequence;
    const double rtt_us = to_seconds(now - echo_sent) * 1e6;
    if (rtt_us >= 0.0) {
      ++stats_.rtt_samples;
      stats_.rtt_last_us = rtt_us;
      stats_.rtt_mean_us += (rtt_us - stats_.rtt_mean_us) / static_cast<double>(stats_.rtt_samples);
      stats_.rtt_max_us = std::max(stats_.rtt_max_us, rtt_us);
    }
  }
  return true;
}

LinkStatistics LinkMonitor::statistics(std::uint64_t control_sent) const noexcept {
  LinkStatistics s = stats_;
  s.control_sent = control_sent;
  return s;
}

}  // namespace hapticctrl::client
