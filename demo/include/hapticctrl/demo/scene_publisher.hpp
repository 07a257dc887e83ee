#pragma once
/// @file scene_publisher.hpp
/// Publishes the demo's scene (scene_t) on LCM so that operator views (the web bridge, lcm-spy)
/// can draw the spheres the controller's handle is coupled to. Soft real time: called from the
/// demo's loop, publishes at most `rate_hz` times a second; never blocks on a subscriber.
#include <cstdint>
#include <memory>
#include <string>

#include "hapticctrl/client/types.hpp"
#include "hapticctrl/demo/demo_input.hpp"
#include "hapticctrl/demo/sphere_scene.hpp"
#include "hapticctrl_lcm/scene_t.hpp"

namespace lcm {
class LCM;
}

namespace hapticctrl::demo {

/// The message for the scene's current state. Pure conversion (no I/O).
[[nodiscard]] hapticctrl_lcm::scene_t to_scene_message(const SphereScene& scene,
                                                       const AppliedWrench& applied,
                                                       const client::LinkStatistics& link,
                                                       std::uint64_t steps, std::int64_t utime);

class ScenePublisher {
 public:
  /// Opens LCM on `url`; throws std::runtime_error naming the URL when LCM cannot start.
  ScenePublisher(const std::string& url, const std::string& instance, double rate_hz);
  ~ScenePublisher();
  ScenePublisher(const ScenePublisher&) = delete;
  ScenePublisher& operator=(const ScenePublisher&) = delete;

  /// Whether a message is due at `now_ns` (monotonic); a true answer books the next slot, a
  /// period later (a period from now after a stall: never a burst to catch up).
  [[nodiscard]] bool due(std::int64_t now_ns) noexcept;
  /// Publishes one message. Returns false when LCM refused it.
  bool publish(const hapticctrl_lcm::scene_t& message);
  [[nodiscard]] const std::string& channel() const noexcept { return channel_; }

 private:
  std::unique_ptr<lcm::LCM> lcm_;
  std::string channel_;
  std::int64_t period_ns_;
  std::int64_t next_ns_ = 0;
};

}  // namespace hapticctrl::demo
