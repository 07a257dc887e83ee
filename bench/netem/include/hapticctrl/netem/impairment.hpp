#pragma once
/// @file impairment.hpp
/// The network model of `hapticctrl-netem`, the project's user-space network impairment relay
/// (this kernel has no netem qdisc: ../shared/PITFALLS.md). Decides, for each datagram, whether
/// it is lost and when it is delivered: one-way delay, uniform jitter, random loss with optional
/// bursts (a two-state Gilbert model), and blackouts (scheduled windows, or switched by hand).
///
/// Pure and deterministic: it reads no clock (times are arguments, nanoseconds on any monotonic
/// scale) and draws from its own seeded generator, so a scenario is a fast unit test.
/// Not for the controller's cycle: it is a test and benchmark tool.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::netem {

/// One window of total outage, relative to the relay's start.
struct Blackout {
  Duration start{};
  Duration duration{};
};

/// What one direction of the link does to datagrams (the relay applies it to both directions).
struct LinkModel {
  Duration delay{};      ///< one-way delay added to every datagram
  Duration jitter{};     ///< each datagram's delay varies uniformly within ±jitter (never < 0)
  double loss = 0.0;     ///< long-run fraction of datagrams lost, 0..1
  double burst = 1.0;    ///< mean length of a loss burst, in datagrams (1: independent losses)
  bool reorder = false;  ///< let jitter reorder datagrams (false: first in, first out)
  std::vector<Blackout> blackouts;

  /// Throws std::invalid_argument naming the first value out of range or non-finite.
  void validate() const;
  /// Parses "AT:DURATION" in seconds ("2.5:0.3"). Throws std::invalid_argument naming the text.
  static Blackout parse_blackout(const std::string& text);
};

/// Fate of one datagram.
struct Verdict {
  enum class Fate : std::uint8_t { kDeliver, kLost, kBlackout };
  Fate fate = Fate::kDeliver;
  TimePoint deliver_at;  ///< when to send it on (kDeliver)
};

/// One direction of the link: its loss state and the order of its deliveries.
class Impairment {
 public:
  Impairment(const LinkModel& model, std::uint64_t seed);

  /// The fate of a datagram that arrived at `now` (`since_start` after the relay started).
  Verdict on_datagram(TimePoint now, Duration since_start);

  /// Switches a manual blackout on or off (the relay's SIGUSR1).
  void set_manual_blackout(bool on) noexcept { manual_blackout_ = on; }
  [[nodiscard]] bool manual_blackout() const noexcept { return manual_blackout_; }
  [[nodiscard]] bool in_blackout(Duration since_start) const noexcept;

 private:
  bool lose() noexcept;

  LinkModel model_;
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  bool bad_state_ = false;  ///< Gilbert model: in a loss burst
  double enter_burst_ = 0.0;
  double leave_burst_ = 1.0;
  bool manual_blackout_ = false;
  TimePoint last_delivery_;
};

}  // namespace hapticctrl::netem
