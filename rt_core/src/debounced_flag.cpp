// Implements debounced_flag.hpp: a flag whose changes are reported only once they have held for a
// number of cycles; shorter flips are counted as lapses and handed over with the next reported
// change.
#include "hapticctrl/rt_core/debounced_flag.hpp"

namespace hapticctrl::rt_core {

bool DebouncedFlag::update(bool value, std::uint64_t cycle) noexcept {
  if (value == reported_) {
    if (changing_) {  // back before the change held: a lapse
      ++lapses_;
      changing_ = false;
    }
    return false;
  }
  if (!changing_) {
    changing_ = true;
    since_ = cycle;
  }
  if (cycle - since_ + 1 < hold_) {
    return false;
  }
  reported_ = value;
  changing_ = false;
  lapses_at_report_ = lapses_;
  lapses_ = 0;
  return true;
}

}  // namespace hapticctrl::rt_core
