// Implements estop_latch.hpp: the latched emergency stop as a file that outlives the core.
#include "hapticctrl/rt_core/estop_latch.hpp"

#include <unistd.h>

#include <array>
#include <ctime>

namespace hapticctrl::rt_core {
namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%d %H:%M:%S UTC", &utc);
  return text.data();
}

}  // namespace

EstopLatchFile::EstopLatchFile(const PrivateDirectory& directory, const std::string& instance)
    : directory_(&directory), name_("hapticctrl-estop." + instance) {
  // Whatever is there counts as latched, a link or an unreadable file included: the safe side.
  on_file_ = directory_->contains(name_);
  left_latched_ = on_file_;
  if (left_latched_) {
    left_note_ = directory_->read_file(name_);
    while (!left_note_.empty() && (left_note_.back() == '\n' || left_note_.back() == '\r')) {
      left_note_.pop_back();
    }
  }
}

void EstopLatchFile::follow(bool latched) {
  if (latched == on_file_) {
    return;
  }
  if (latched) {
    // A file already there (made meanwhile by hand, say) is the same latch: keep it.
    directory_->create_file(
        name_, "latched at " + utc_now() + " (core pid " + std::to_string(getpid()) + ")\n");
  } else {
    directory_->remove(name_);
  }
  on_file_ = latched;
}

}  // namespace hapticctrl::rt_core
