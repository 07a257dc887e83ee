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
        period_ns_(static_cast<std::int64_t>(1e9 / rate_hz)) {
    if (!lcm_->good()) {
      throw std::runtime_error("cannot open LCM on '" + url + "' to publish " + what +
                               " (--no-lcm runs without it)");
    }
  }

  /// Whether a message is due at `now_ns` (monotonic); a true answer books the next slot, a
  /// period later (a period from now after a stall: never a burst to catch up). Cycle-safe.
  [[nodiscard]] bool due(std::int64_t now_ns) noexcept {
    if (now_ns < next_ns_) {
      return false;
    }
    next_ns_ = next_ns_ + period_ns_ > now_ns ? next_ns_ + period_ns_ : now_ns + period_ns_;
    return true;
  }
  /// Publishes one message (one UDP send). Returns false when LCM refused it.
  bool publish(const Message& message) { return lcm_->publish(channel_, &message) == 0; }
  [[nodiscard]] const std::string& channel() const noexcept { return channel_; }

 private:
  std::unique_ptr<lcm::LCM> lcm_;
  std::string channel_;
  std::int64_t period_ns_;
  std::int64_t next_ns_ = 0;
};

}  // namespace hapticctrl::lcmtypes
