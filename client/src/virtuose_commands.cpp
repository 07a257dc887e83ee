// The C API's per-cycle commands: the virtual object's state (VIRTMECH) or the wrench
// (IMPEDANCE), sent at once, or after the periodic function when a loop runs.
#include "virtuose_context.hpp"

using hapticctrl::client::CommandType;
using hapticctrl::client::Vector6;
using hapticctrl::client::virtuose::Context;
using hapticctrl::client::virtuose::context_of;
using hapticctrl::client::virtuose::fail;
using hapticctrl::client::virtuose::to_doubles;

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

int virtSetPosition(VirtContext VC, float* pos) {
  Context* vc = context_of(VC, pos, "virtSetPosition: NULL pose");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->command_type != CommandType::kVirtmech) {
    return fail(VC, VIRT_E_WRONG_MODE, "virtSetPosition: needs COMMAND_TYPE_VIRTMECH");
  }
  vc->object_pose = to_doubles<7>(pos);
  vc->pose_pending = true;
  if (!vc->loop_running.load() && !vc->flush_locked()) {
    return fail(VC, VIRT_E_INCORRECT_VALUE,
                "virtSetPosition: pose or speed out of range, or the session is closed");
  }
  return 0;
}

int virtSetSpeed(VirtContext VC, float* speed) {
  Context* vc = context_of(VC, speed, "virtSetSpeed: NULL speed");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  vc->object_speed = to_doubles<6>(speed);
  return 0;
}

int virtSetForce(VirtContext VC, float* force) {
  Context* vc = context_of(VC, force, "virtSetForce: NULL force");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->command_type != CommandType::kImpedance) {
    return fail(VC, VIRT_E_WRONG_MODE, "virtSetForce: needs COMMAND_TYPE_IMPEDANCE");
  }
  vc->wrench = to_doubles<6>(force);
  vc->wrench_pending = true;
  if (!vc->loop_running.load() && !vc->flush_locked()) {
    return fail(VC, VIRT_E_INCORRECT_VALUE,
                "virtSetForce: force out of range, or the session is closed");
  }
  return 0;
}

int virtAddForce(VirtContext VC, float* force) {
  Context* vc = context_of(VC, force, "virtAddForce: NULL force");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->command_type != CommandType::kImpedance) {
    return fail(VC, VIRT_E_WRONG_MODE,
                "virtAddForce: needs COMMAND_TYPE_IMPEDANCE (control frames carry either an "
                "object state or a wrench)");
  }
  const Vector6 f = to_doubles<6>(force);
  for (std::size_t i = 0; i < 6; ++i) {
    vc->added_wrench[i] += f[i];
  }
  vc->wrench_pending = true;
  return 0;
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
