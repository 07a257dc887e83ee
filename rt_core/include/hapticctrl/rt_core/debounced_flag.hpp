#pragma once
/// @file debounced_flag.hpp
/// A flag whose changes are reported only once they have held for a number of cycles; shorter
/// flips are counted as lapses and handed over with the next reported change. The executive
/// uses it for the client's stale/fresh events: a lost sample makes client data stale for a
/// cycle or two, which filled the event log (350 of 352 events in 73 s at 10 % loss,
/// 2026-12-02). Real-time contract: every member is noexcept, allocation-free, O(1).
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::rt_core {

class DebouncedFlag {
 public:
  /// A change is reported after it has held `hold_cycles` cycles (at least 1: at once).
  explicit DebouncedFlag(std::uint64_t hold_cycles) noexcept
      : hold_(hold_cycles == 0 ? 1 : hold_cycles) {}

  /// Feeds the flag's value in `cycle` (cycles increase). Returns true when a change is to be
  /// reported now: reported() is then the new value and lapses() the shorter flips since the
  /// last report.
  HAPTICCTRL_RT bool update(bool value, std::uint64_t cycle) noexcept;

  [[nodiscard]] HAPTICCTRL_RT bool reported() const noexcept { return reported_; }
  [[nodiscard]] HAPTICCTRL_RT std::uint64_t lapses() const noexcept { return lapses_at_report_; }

 private:
  std::uint64_t hold_;
  bool reported_ = false;
  bool changing_ = false;
  std::uint64_t since_ = 0;
  std::uint64_t lapses_ = 0;
  std::uint64_t lapses_at_report_ = 0;
};

}  // namespace hapticctrl::rt_core
