// The C API's per-cycle commands: the virtual object's state (VIRTMECH), the wrench
// (IMPEDANCE), the joint set points (ARTICULAR) or torques (ARTICULAR_IMPEDANCE), sent at once,
// or after the periodic function when a loop runs.
#include <algorithm>
#include <array>
#include <span>

#include "virtuose_context.hpp"

using hapticctrl::client::CommandType;
using hapticctrl::client::Contact;
using hapticctrl::client::ContactResult;
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
  return vc->loop_running.load() ? 0
                                 : vc->flush_locked("virtSetPosition: pose or speed out of range");
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
  return vc->loop_running.load() ? 0 : vc->flush_locked("virtSetForce: force out of range");
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

int virtSetArticularPosition(VirtContext VC, float* pos) {
  Context* vc = context_of(VC, pos, "virtSetArticularPosition: NULL positions");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->command_type != CommandType::kArticular) {
    return fail(VC, VIRT_E_WRONG_MODE, "virtSetArticularPosition: needs COMMAND_TYPE_ARTICULAR");
  }
  vc->joint_position = to_doubles<6>(pos);
  vc->joints_pending = true;
  return vc->loop_running.load()
             ? 0
             : vc->flush_locked("virtSetArticularPosition: a position or speed out of range");
}

int virtSetArticularSpeed(VirtContext VC, float* speed) {
  Context* vc = context_of(VC, speed, "virtSetArticularSpeed: NULL speeds");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  vc->joint_speed = to_doubles<6>(speed);  // goes with the next positions, as virtSetSpeed's
  return 0;
}

int virtSetArticularForce(VirtContext VC, float* force) {
  Context* vc = context_of(VC, force, "virtSetArticularForce: NULL torques");
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->command_type != CommandType::kArticularImpedance) {
    return fail(VC, VIRT_E_WRONG_MODE,
                "virtSetArticularForce: needs COMMAND_TYPE_ARTICULAR_IMPEDANCE");
  }
  vc->joint_torque = to_doubles<6>(force);
  vc->joints_pending = true;
  return vc->loop_running.load() ? 0
                                 : vc->flush_locked("virtSetArticularForce: a torque out of range");
}

int virtSetContacts(VirtContext VC, int count, float* contacts) {
  Context* vc = context_of(VC, count == 0 ? static_cast<const void*>(&count) : contacts,
                           "virtSetContacts: NULL contacts");
  if (vc == nullptr) {
    return -1;
  }
  if (count < 0 || count > VIRT_MAX_CONTACTS) {
    return fail(VC, VIRT_E_INCORRECT_VALUE, "virtSetContacts: count outside 0-8");
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->command_type != CommandType::kVirtmech && vc->command_type != CommandType::kImpedance) {
    return fail(VC, VIRT_E_WRONG_MODE, "virtSetContacts: needs COMMAND_TYPE_VIRTMECH or IMPEDANCE");
  }
  // Points as the application's object poses go (through indexing's offset: linear quantities
  // do not rotate with it, so the normals stay as given).
  const std::shared_ptr<hapticctrl::client::Connection> link = vc->link();
  const hapticctrl::client::Pose7 handle = link->snapshot().handle_pose;
  std::array<Contact, VIRT_MAX_CONTACTS> taken{};
  const auto n = static_cast<std::size_t>(count);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, VIRT_CONTACT_FLOATS> f{};
    std::copy_n(contacts + i * VIRT_CONTACT_FLOATS, VIRT_CONTACT_FLOATS, f.begin());
    const hapticctrl::client::Pose7 point =
        vc->indexing.to_physical(handle, hapticctrl::client::Pose7{f[0], f[1], f[2], 0, 0, 0, 1});
    Contact& c = taken.at(i);
    c.point = {point[0], point[1], point[2]};
    c.normal = {f[3], f[4], f[5]};
    c.distance = f[6];
    c.stiffness = f[7];
    c.damping = f[8];
    c.friction_static = f[9];
    c.friction_dynamic = f[10];
  }
  switch (link->set_contacts(std::span<const Contact>(taken.data(), n))) {
    case ContactResult::kAccepted:
      vc->settings.contacts = taken;  // for the next session, should the controller be lost
      vc->settings.contact_count = n;
      return 0;
    case ContactResult::kUnsupported:
      return fail(VC, VIRT_E_INCOMPATIBLE_VERSION,
                  "virtSetContacts: the controller takes no contacts (protocol 1.3)");
    case ContactResult::kTooStiff:
      return fail(VC, VIRT_E_INCORRECT_VALUE,
                  "virtSetContacts: stiffer than the controller renders");
    case ContactResult::kTooMany:
    case ContactResult::kInvalid:
      break;
  }
  return fail(VC, VIRT_E_INCORRECT_VALUE,
              "virtSetContacts: a value out of range (non-finite, a normal that is not a unit "
              "vector, a stiffness outside 1 to 1e6 N/m, a negative damping, or dynamic friction "
              "above the static)");
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
