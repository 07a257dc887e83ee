#pragma once
/// @file world_message.hpp
/// The scene as the web view draws it (world_t on hapticctrl.<instance>.world): every visible
/// geom of the model with its pose, and the held body's contacts as they were reported, in the
/// client's frame (the controller's base frame: hapticctrl-mujoco sets them equal).
#include <cstdint>
#include <span>

#include "hapticctrl/client/types.hpp"
#include "hapticctrl/mujoco/grasp.hpp"
#include "hapticctrl/mujoco/world.hpp"
#include "hapticctrl_lcm/world_t.hpp"

namespace hapticctrl::mujoco {

/// What the message says besides the world's own state.
struct WorldRun {
  std::uint64_t steps = 0;
  double steps_per_second = 0.0;
  std::int64_t utime = 0;
};

/// The message for the world's state after its last step, placed by `grasp` as the controller
/// sees it, with the contacts last reported (client frame). Pure conversion (no I/O, no
/// allocation); a model with more geoms than the message holds sends the first ones
/// (geoms_total says how many there are).
[[nodiscard]] hapticctrl_lcm::world_t to_world_message(const World& world, const Grasp& grasp,
                                                       std::span<const client::Contact> contacts,
                                                       const WorldRun& run) noexcept;

}  // namespace hapticctrl::mujoco
