// Implements restart_marker.hpp: whether the core before this one stopped in order.
#include "hapticctrl/rt_core/restart_marker.hpp"

#include <stdexcept>

#include "state_note.hpp"

namespace hapticctrl::rt_core {

RestartMarker::RestartMarker(const PrivateDirectory& directory, const std::string& instance)
    : directory_(&directory), name_("hapticctrl-running." + instance) {
  left_ = directory_->contains(name_);
  if (left_) {
    left_note_ = read_state_note(*directory_, name_);
    directory_->remove(name_);
  }
  if (!directory_->create_file(name_, state_note("running since"))) {
    throw std::runtime_error("the restart marker " + name_ + " reappeared while it was replaced");
  }
}

void RestartMarker::stopped_in_order() {
  directory_->remove(name_);
}

}  // namespace hapticctrl::rt_core
