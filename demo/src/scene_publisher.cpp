// Implements scene_publisher.hpp: publishes the demo's scene (scene_t) on LCM so that operator
// views (the web bridge, lcm-spy) can draw the spheres the controller's handle is coupled to.
#include "hapticctrl/demo/scene_publisher.hpp"

#include <algorithm>

namespace hapticctrl::demo {

hapticctrl_lcm::scene_t to_scene_message(const SphereScene& scene, const AppliedWrench& applied,
                                         const client::LinkStatistics& link, std::uint64_t steps,
                                         std::int64_t utime) {
  hapticctrl_lcm::scene_t m{};
  m.utime = utime;
  m.steps = static_cast<std::int64_t>(steps);
  const SceneConfig& c = scene.config();
  for (int i = 0; i < 3; ++i) {
    m.fixed_center[i] = c.fixed_center(i);
  }
  m.fixed_radius = c.fixed_radius;
  const client::Pose7 pose = scene.pose();
  std::copy(pose.begin(), pose.end(), m.mobile_pose);
  m.mobile_radius = c.mobile_radius;
  const Eigen::Vector3d contact = scene.contact_force();
  for (int i = 0; i < 3; ++i) {
    m.contact_force[i] = contact(i);
  }
  m.penetration = scene.penetration();
  std::copy(applied.wrench.begin(), applied.wrench.end(), m.applied_wrench);
  m.rtt_last_us = link.rtt_last_us;
  m.rtt_mean_us = link.rtt_mean_us;
  m.rtt_max_us = link.rtt_max_us;
  m.answers_received = static_cast<std::int64_t>(link.answers_received);
  m.answers_lost = static_cast<std::int64_t>(link.answers_lost);
  return m;
}

}  // namespace hapticctrl::demo
