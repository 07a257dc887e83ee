#pragma once
/// @file real_time_steps.hpp
/// When the engine steps: in real time at the model's time step, from the wall clock it is
/// given (it reads none). After a stall, the steps missed are run at once up to a bound; beyond
/// it the world's time is dropped (the world pauses, counted) rather than integrated blind or
/// chased in a spiral. While the controller is silent the world pauses too (counted apart): the
/// body is not left to fall out of the hand for a link that may come back.
#include <cstdint>

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::mujoco {

class RealTimeSteps {
 public:
  /// `step` > 0; `max_catch_up`: the most world time run at once after a stall.
  RealTimeSteps(Duration step, Duration max_catch_up) noexcept;

  /// The world's time starts now.
  void start(TimePoint now) noexcept;
  /// How many steps to run now (0 if none is due yet); the steps beyond the catch-up bound are
  /// dropped and counted. Counts the returned steps as run.
  [[nodiscard]] std::uint64_t due(TimePoint now) noexcept;
  /// The link is silent: the time since the last step is not the world's (counted as paused).
  void pause(TimePoint now) noexcept;
  /// When the next step is due.
  [[nodiscard]] TimePoint next_due() const noexcept;

  [[nodiscard]] std::uint64_t run() const noexcept { return run_; }
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_; }
  [[nodiscard]] std::uint64_t paused() const noexcept { return paused_; }
  /// Times more than one step was due at once (a late wake-up or a stall).
  [[nodiscard]] std::uint64_t catch_ups() const noexcept { return catch_ups_; }

 private:
  /// Steps the wall clock has made due since the start, counted run, dropped or paused.
  [[nodiscard]] std::uint64_t owed(TimePoint now) const noexcept;

  Duration step_;
  std::uint64_t max_catch_up_;
  TimePoint origin_;
  std::uint64_t accounted_ = 0;  ///< run + dropped + paused
  std::uint64_t run_ = 0;
  std::uint64_t dropped_ = 0;
  std::uint64_t paused_ = 0;
  std::uint64_t catch_ups_ = 0;
};

}  // namespace hapticctrl::mujoco
