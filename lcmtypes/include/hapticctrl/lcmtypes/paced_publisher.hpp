#pragma once
/// @file paced_publisher.hpp
/// Publishes one message type on one LCM channel at most `rate_hz` times a second: the clients'
/// views (the demo's scene_t, hapticctrl-mujoco's world_t) for the web bridge and lcm-spy.
/// Soft real time: called from a client's loop; never blocks on a subscriber (LCM's UDP
/// multicast); setup allocates and throws.
#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::lcmtypes {

template <class Message>
class PacedPublisher {
 public:
  /// Opens LCM on `url`; throws std::runtime_error naming the URL and `what` is published when
  /// LCM cannot start.
  PacedPublisher(const std::string& url, std::string channel, double rate_hz,
                 const std::string& what)
      : lcm_(std::make_unique<lcm::LCM>(url)),
        channel_(std::move(channel)),
        period_(from_seconds(1.0 / rate_hz)) {
    if (!lcm_->good()) {
      throw std::runtime_error("cannot open LCM on '" + url + "' to publish " + what +
                               " (--no-lcm runs without it)");
    }
  }

  /// Whether a message is due at `now`; a true answer books the next slot, a period later (a
  /// period from now after a stall: never a burst to catch up). Cycle-safe.
  [[nodiscard]] bool due(TimePoint now) noexcept {
    if (now < next_) {
      return false;
    }
    next_ = next_ + period_ > now ? next_ + period_ : now + period_;
    return true;
  }
  /// Publishes one message (one UDP send). Returns false when LCM refused it.
  bool publish(const Message& message) { return lcm_->publish(channel_, &message) == 0; }
  [[nodiscard]] const std::string& channel() const noexcept { return channel_; }

 private:
  std::unique_ptr<lcm::LCM> lcm_;
  std::string channel_;
  Duration period_;
  TimePoint next_;
};

}  // namespace hapticctrl::lcmtypes
