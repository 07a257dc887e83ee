// The C API's view of the arm: the latest controller answer, through the indexing.
#include <algorithm>
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "virtuose_context.hpp"

using hapticctrl::client::Pose7;
using hapticctrl::client::StateSnapshot;
using hapticctrl::client::Vector6;
using hapticctrl::client::virtuose::Context;
using hapticctrl::client::virtuose::context_of;
using hapticctrl::client::virtuose::fail;
using hapticctrl::client::virtuose::to_floats;

namespace {

namespace state_bits = hapticctrl::client::state_bits;

/// VirtuoseAPI's bound bit of each answer bound bit (joint j lower, upper; then J2 + J3):
/// lower is LEFT or INF, upper RIGHT or SUP.
constexpr std::uint32_t kBoundBits[] = {  // NOLINT(*-avoid-c-arrays)
    VIRT_BOUND_LEFT_AXE_1,  VIRT_BOUND_RIGHT_AXE_1, VIRT_BOUND_INF_AXE_2,  VIRT_BOUND_SUP_AXE_2,
    VIRT_BOUND_INF_AXE_3,   VIRT_BOUND_SUP_AXE_3,   VIRT_BOUND_LEFT_AXE_4, VIRT_BOUND_RIGHT_AXE_4,
    VIRT_BOUND_INF_AXE_5,   VIRT_BOUND_SUP_AXE_5,   VIRT_BOUND_LEFT_AXE_6, VIRT_BOUND_RIGHT_AXE_6,
    VIRT_BOUND_INF_AXE_2_3, VIRT_BOUND_SUP_AXE_2_3};

/// Reads the latest answer and the indexing together, for one getter. Without a session (the
/// controller lost, the library connecting to the next one) the last answer is read and the
/// call fails with VIRT_E_COMMUNICATION_FAILURE: the arm is not where it was reported.
template <typename Read>
int read_state(VirtContext vc, const void* out, const char* what, Read&& read) noexcept {
  Context* c = context_of(vc, out, what);
  if (c == nullptr) {
    return -1;
  }
  const std::shared_ptr<hapticctrl::client::Connection> link = c->link();
  const StateSnapshot s = link->snapshot();
  const bool open = link->is_open();
  const std::lock_guard lock(c->mutex);
  read(*c, s);
  return open ? 0 : c->fail_without_session(s);
}

}  // namespace

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

int virtGetPosition(VirtContext VC, float* pos) {
  return read_state(VC, pos, "virtGetPosition: NULL output",
                    [&](const Context& c, const StateSnapshot& s) {
                      to_floats(c.indexing.avatar(s.handle_pose), pos);
                    });
}

int virtGetAvatarPosition(VirtContext VC, float* pos) {
  return virtGetPosition(VC, pos);
}

int virtGetSpeed(VirtContext VC, float* speed) {
  return read_state(VC, speed, "virtGetSpeed: NULL output",
                    [&](const Context& c, const StateSnapshot& s) {
                      to_floats(c.indexing.avatar_twist(s.handle_pose, s.handle_twist), speed);
                    });
}

int virtGetPhysicalPosition(VirtContext VC, float* pos) {
  return read_state(VC, pos, "virtGetPhysicalPosition: NULL output",
                    [&](const Context&, const StateSnapshot& s) { to_floats(s.handle_pose, pos); });
}

int virtGetPhysicalSpeed(VirtContext VC, float* speed) {
  return read_state(
      VC, speed, "virtGetPhysicalSpeed: NULL output",
      [&](const Context&, const StateSnapshot& s) { to_floats(s.handle_twist, speed); });
}

int virtGetForce(VirtContext VC, float* force) {
  return read_state(VC, force, "virtGetForce: NULL output",
                    [&](const Context& c, const StateSnapshot& s) {
                      to_floats(c.indexing.to_avatar(s.handle_pose, s.coupling_wrench), force);
                    });
}

int virtGetArticularPosition(VirtContext VC, float* pos) {
  return read_state(
      VC, pos, "virtGetArticularPosition: NULL output",
      [&](const Context&, const StateSnapshot& s) { to_floats(s.joint_position, pos); });
}

int virtGetArticularSpeed(VirtContext VC, float* speed) {
  return read_state(
      VC, speed, "virtGetArticularSpeed: NULL output",
      [&](const Context&, const StateSnapshot& s) { to_floats(s.joint_velocity, speed); });
}

int virtGetPowerOn(VirtContext VC, int* power) {
  return read_state(VC, power, "virtGetPowerOn: NULL output",
                    [&](const Context&, const StateSnapshot& s) { *power = s.powered() ? 1 : 0; });
}

int virtGetEmergencyStop(VirtContext VC, int* emergency_stop) {
  // Haption's meaning: 1 while the arm is operational (the emergency stop is not latched and a
  // controller answers), 0 otherwise.
  return read_state(VC, emergency_stop, "virtGetEmergencyStop: NULL output",
                    [&](const Context& c, const StateSnapshot& s) {
                      *emergency_stop =
                          s.valid && !s.emergency_stop() && c.link()->is_open() ? 1 : 0;
                    });
}

int virtGetTimeLastUpdate(VirtContext VC, unsigned int* time) {
  Context* vc = context_of(VC, time, "virtGetTimeLastUpdate: NULL output");
  if (vc == nullptr) {
    return -1;
  }
  const StateSnapshot s = vc->link()->snapshot();
  if (!s.valid) {
    return fail(VC, VIRT_E_TIME_OUT, "virtGetTimeLastUpdate: no answer from the controller yet");
  }
  const std::int64_t us =
      (hapticctrl::to_ns(hapticctrl::MonotonicClock::now()) - s.received_ns) / 1000;
  *time = static_cast<unsigned int>(std::clamp<std::int64_t>(us, 0, 0xFFFFFFFF));
  return 0;
}

int virtGetAlarm(VirtContext VC, unsigned int* alarm) {
  return read_state(VC, alarm, "virtGetAlarm: NULL output",
                    [&](Context& c, const StateSnapshot& s) {
                      *alarm = c.alarms | ((s.state_word & state_bits::kSaturated) != 0U
                                               ? static_cast<unsigned>(VIRT_ALARM_SATURATE)
                                               : 0U);
                      c.alarms = 0;  // raised since the last read
                    });
}

int virtIsInBounds(VirtContext VC, unsigned int* bounds) {
  return read_state(VC, bounds, "virtIsInBounds: NULL output",
                    [&](const Context&, const StateSnapshot& s) {
                      unsigned int bits = 0;
                      for (unsigned i = 0; i < std::size(kBoundBits); ++i) {
                        if ((s.state_word & (1U << (state_bits::kJointBoundsShift + i))) != 0U) {
                          bits |= kBoundBits[i];
                        }
                      }
                      *bounds = bits;
                    });
}

int virtIsInShiftPosition(VirtContext VC, int* decalage) {
  return read_state(
      VC, decalage, "virtIsInShiftPosition: NULL output",
      [&](const Context& c, const StateSnapshot&) { *decalage = c.indexing.shifted() ? 1 : 0; });
}

int virtForceShiftButton(VirtContext VC, int forceShiftButton) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  const Pose7 physical = vc->link()->snapshot().handle_pose;
  const std::lock_guard lock(vc->mutex);
  if (forceShiftButton != 0) {
    vc->indexing.press(physical);
  } else {
    vc->indexing.release(physical);
  }
  return 0;
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
