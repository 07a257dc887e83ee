#pragma once
/// @file scene_publisher.hpp
/// Publishes the demo's scene (scene_t) on LCM so that operator views (the web bridge, lcm-spy)
/// can draw the spheres the controller's handle is coupled to. Soft real time: called from the
/// demo's loop, publishes at most `rate_hz` times a second; never blocks on a subscriber.
#include <cstdint>
#include <string>

#include "hapticctrl/client/types.hpp"
#include "hapticctrl/demo/demo_input.hpp"
#include "hapticctrl/demo/sphere_scene.hpp"
#include "hapticctrl/lcmtypes/channels.hpp"
#include "hapticctrl/lcmtypes/paced_publisher.hpp"
#include "hapticctrl_lcm/scene_t.hpp"

namespace hapticctrl::demo {

/// The message for the scene's current state. Pure conversion (no I/O).
[[nodiscard]] hapticctrl_lcm::scene_t to_scene_message(const SphereScene& scene,
                                                       const AppliedWrench& applied,
                                                       const client::LinkStatistics& link,
                                                       std::uint64_t steps, std::int64_t utime);

/// The scene on its instance's channel (hapticctrl.<instance>.scene).
class ScenePublisher : public lcmtypes::PacedPublisher<hapticctrl_lcm::scene_t> {
 public:
  /// Opens LCM on `url`; throws std::runtime_error naming the URL when LCM cannot start.
  ScenePublisher(const std::string& url, const std::string& instance, double rate_hz)
      : PacedPublisher(url, lcmtypes::Channels::of(instance).scene, rate_hz, "the scene") {}
};

}  // namespace hapticctrl::demo
