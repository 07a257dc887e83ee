#pragma once
/// @file model_json.hpp
/// The arm's kinematics for the page: each joint's origin (in the previous link frame at
/// q = 0) and axis (in its own frame), its limits, the handle point in the last frame, and the
/// workspace box. The page chains them exactly as rt_core's ArmDynamics::forward_kinematics
/// does, and checks its handle against the controller's. Setup code (allocates).
#include <string>

#include "hapticctrl/arm_model/arm_model.hpp"

namespace hapticctrl::web_bridge {

/// {"name":...,"joints":[{"origin":[x,y,z],"axis":[x,y,z],"limits":[lo,hi]},...],
///  "handle":[x,y,z],"workspace":{"center":[...],"half_size":[...]}}
[[nodiscard]] std::string model_json(const arm_model::ArmModel& model);

}  // namespace hapticctrl::web_bridge
