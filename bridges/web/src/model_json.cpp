// Implements model_json.hpp: the arm's kinematics for the page: each joint's origin (in the
// previous link frame at q = 0) and axis (in its own frame), its limits, the handle point in the
// last frame, and the workspace box.
#include "hapticctrl/web_bridge/model_json.hpp"

#include <nlohmann/json.hpp>

namespace hapticctrl::web_bridge {
namespace {

nlohmann::json vector_json(const arm_model::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

}  // namespace

std::string model_json(const arm_model::ArmModel& model) {
  nlohmann::json joints = nlohmann::json::array();
  for (const arm_model::JointModel& j : model.joints) {
    joints.push_back({{"origin", vector_json(j.origin)},
                      {"axis", vector_json(j.axis)},
                      {"limits", nlohmann::json::array({j.q_min, j.q_max})}});
  }
  const nlohmann::json model_json{{"type", "model"},
                                  {"name", model.name},
                                  {"joints", std::move(joints)},
                                  {"handle", vector_json(model.handle)},
                                  {"workspace",
                                   {{"center", vector_json(model.limits.workspace_center)},
                                    {"half_size", vector_json(model.limits.workspace_half_size)}}}};
  return model_json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace hapticctrl::web_bridge
