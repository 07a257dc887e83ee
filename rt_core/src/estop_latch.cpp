// Implements estop_latch.hpp: the latched emergency stop as a file that outlives the core.
#include "hapticctrl/rt_core/estop_latch.hpp"

#include "state_note.hpp"

namespace hapticctrl::rt_core {

EstopLatchFile::EstopLatchFile(const PrivateDirectory& directory, const std::string& instance)
    : directory_(&directory), name_("hapticctrl-estop." + instance) {
  // Whatever is there counts as latched, a link or an unreadable file included: the safe side.
  on_file_ = directory_->contains(name_);
  left_latched_ = on_file_;
  if (left_latched_) {
    left_note_ = read_state_note(*directory_, name_);
  }
}

void EstopLatchFile::follow(bool latched) {
  if (latched == on_file_) {
    return;
  }
  if (latched) {
    // A file already there (made meanwhile by hand, say) is the same latch: keep it.
    directory_->create_file(name_, state_note("latched at"));
  } else {
    directory_->remove(name_);
  }
  on_file_ = latched;
}

}  // namespace hapticctrl::rt_core
