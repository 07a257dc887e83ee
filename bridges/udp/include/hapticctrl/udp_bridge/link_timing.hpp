#pragma once
/// @file link_timing.hpp
/// How the bridge measures the client link (protocol 1.1, HCP_FEATURE_TIMING): each ANSWER's
/// send time is logged by cycle; a CONTROL_OBJECT_TIMED echoes the newest answer its client had
/// and how long it held it, so round trip = arrival - answer sent - hold, on the bridge's clock
/// alone (no clock offset between hosts). Half of it dates the sample: the core then knows its
/// true age (network + bridge + waiting) and the coupling loop's delay (docs/control.md).
///
/// Real-time contract: noexcept, no allocation, no syscall; safe on the bridge's hot paths.
#include <array>
#include <atomic>
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/protocol/timing.hpp"

namespace hapticctrl::udp_bridge {

/// Send times of the recent answers, by cycle. One writer (the answer thread), any reader.
class AnswerLog {
 public:
  /// Answer side: the answer of `cycle` left at `sent`.
  void record(std::uint64_t cycle, TimePoint sent) noexcept;
  /// The newest cycle recorded (0: none).
  [[nodiscard]] std::uint64_t newest() const noexcept {
    return newest_.load(std::memory_order_acquire);
  }
  /// When the answer of `cycle` left, if it is still in the log (the last kSize cycles).
  [[nodiscard]] bool sent_time(std::uint64_t cycle, TimePoint& sent) const noexcept;

  static constexpr std::size_t kSize = 4096;  ///< 4 s of answers at 1 kHz

 private:
  struct Entry {
    std::atomic<std::uint64_t> cycle{0};
    std::atomic<std::int64_t> sent_ns{0};  ///< to_ns(sent): a plain word for the atomic
  };
  std::array<Entry, kSize> entries_{};
  std::atomic<std::uint64_t> newest_{0};
};

/// What the bridge knows of one control frame's timing.
struct SampleTiming {
  bool measured = false;         ///< an echo of a logged answer: the fields below are set
  std::uint64_t echo_cycle = 0;  ///< the answer's full cycle
  Duration round_trip{};         ///< network only: the client's hold is taken out
  TimePoint sample_time;         ///< arrival less half the round trip
};

/// Smoothed one-way delay, its jitter and the loss rate of the control frames of one session.
class LinkEstimator {
 public:
  /// Times one arriving control frame from its echo.
  [[nodiscard]] static SampleTiming time_sample(const protocol::AnswerEcho& echo,
                                                const AnswerLog& log, TimePoint arrival) noexcept;
  /// Feeds a measured sample into the averages.
  void add(const SampleTiming& sample) noexcept;
  /// Feeds an accepted control frame that came after `lost` missing sequence numbers.
  void add_arrival(std::uint32_t lost) noexcept;
  void reset() noexcept { *this = LinkEstimator{}; }

  [[nodiscard]] Duration delay() const noexcept { return whole_ns(delay_); }
  [[nodiscard]] Duration jitter() const noexcept { return whole_ns(jitter_); }
  [[nodiscard]] std::uint32_t loss_ppm() const noexcept {
    return static_cast<std::uint32_t>(loss_ * 1e6);
  }

 private:
  /// The whole nanoseconds of an average (the fraction dropped, as the wire's count does).
  static Duration whole_ns(double ns) noexcept { return Duration(static_cast<Duration::rep>(ns)); }

  bool have_delay_ = false;
  double delay_ = 0.0;  ///< ns, as jitter_ and last_one_way_
  double jitter_ = 0.0;
  double last_one_way_ = 0.0;
  double loss_ = 0.0;
};

}  // namespace hapticctrl::udp_bridge
