// Implements world_message.hpp: the scene's geoms and the held body's contacts as world_t.
#include "hapticctrl/mujoco/world_message.hpp"

#include <algorithm>
#include <array>
#include <iterator>

namespace hapticctrl::mujoco {

hapticctrl_lcm::world_t to_world_message(const World& world, const Grasp& grasp,
                                         std::span<const client::Contact> contacts,
                                         const WorldRun& run) noexcept {
  hapticctrl_lcm::world_t m{};
  m.utime = run.utime;
  m.steps = static_cast<std::int64_t>(run.steps);
  m.steps_per_second = run.steps_per_second;
  m.model_steps_per_second = 1.0 / world.timestep();
  constexpr std::size_t kRoom = std::size(m.geoms);
  std::array<GeomView, kRoom> geoms{};
  const std::size_t n = world.geoms(geoms);
  m.geom_count = static_cast<std::int32_t>(n);
  m.geoms_total = static_cast<std::int32_t>(world.visible_geoms());
  for (std::size_t i = 0; i < n; ++i) {
    const GeomView& g = geoms[i];
    hapticctrl_lcm::world_geom_t& out = m.geoms[i];
    out.type = static_cast<std::int8_t>(g.type);
    std::copy(g.size.begin(), g.size.end(), out.size);
    // The scene's axes are the arm's (grasp.hpp): a geom's place moves, its orientation does not.
    const std::array<double, 3> at = grasp.point_to_client({g.pose[0], g.pose[1], g.pose[2]});
    std::copy(at.begin(), at.end(), out.pose);
    std::copy(g.pose.begin() + 3, g.pose.end(), out.pose + 3);
    std::copy(g.rgba.begin(), g.rgba.end(), out.rgba);
    out.coupled = g.coupled;
  }
  constexpr std::size_t kContactRoom = std::size(m.contacts);
  m.contact_count = static_cast<std::int32_t>(std::min(contacts.size(), kContactRoom));
  for (std::size_t i = 0; i < static_cast<std::size_t>(m.contact_count); ++i) {
    const client::Contact& c = contacts[i];
    hapticctrl_lcm::world_contact_t& out = m.contacts[i];
    std::copy(c.point.begin(), c.point.end(), out.point);
    std::copy(c.normal.begin(), c.normal.end(), out.normal);
    out.distance = c.distance;
    out.stiffness = c.stiffness;
  }
  const std::array<double, 3> f = world.contact_force();
  std::copy(f.begin(), f.end(), m.contact_force);
  return m;
}

}  // namespace hapticctrl::mujoco
