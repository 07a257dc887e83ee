// The C API's view of the arm against the real controller and bridge: avatar and physical
// poses through a shift (the operator moving the handle), the joints in their walls, the saturation
// alarm.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <thread>
#include <utility>

#include "hapticctrl/shm/segment.hpp"
#include "hapticctrl/virtuose_api.h"
#include "support/controller_stack.hpp"
#include "support/machine_retries.hpp"
#include "virtuose_session.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;
using test::retry_what_the_machine_disturbed;
using test::VirtuoseSession;

using Pose = std::array<float, 7>;

Pose avatar(VirtContext vc) {
  Pose p{};
  EXPECT_EQ(virtGetAvatarPosition(vc, p.data()), 0);
  return p;
}

Pose physical(VirtContext vc) {
  Pose p{};
  EXPECT_EQ(virtGetPhysicalPosition(vc, p.data()), 0);
  return p;
}

double distance(const Pose& a, const Pose& b) {
  return static_cast<double>(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
}

/// The operator pushes the handle with `wrench` (the simulated hand, through the force region)
/// for `duration`, lets go, and the handle comes to rest.
void operator_push(const ControllerStack& stack, VirtContext vc, const shm::Vector6& wrench,
                   std::chrono::milliseconds duration) {
  shm::Segment hand = shm::Segment::attach(stack.instance(), {.write = {shm::RegionId::kForce}});
  hand.writable<shm::RegionId::kForce>().publish({.wrench = wrench}, 1);
  std::this_thread::sleep_for(duration);
  hand.writable<shm::RegionId::kForce>().publish({}, 2);
  std::array<float, 6> speed{};
  EXPECT_TRUE(ControllerStack::eventually([&] {
    return virtGetPhysicalSpeed(vc, speed.data()) == 0 &&
           std::hypot(speed[0], speed[1], speed[2]) < 1e-3F;
  })) << "the handle comes to rest";
}

/// An open session set to IMPEDANCE and powered on; false (with the failure said) otherwise.
bool powered_in_impedance(const VirtuoseSession& vc) {
  const bool impedance = virtSetCommandType(vc.get(), COMMAND_TYPE_IMPEDANCE) == 0;
  EXPECT_TRUE(impedance) << vc.detail();
  const bool powered = impedance && virtSetPowerOn(vc.get(), 1) == 0;
  EXPECT_TRUE(powered) << vc.detail();
  return powered;
}

class VirtuoseState : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(stack_.ready()) << stack_.diagnostics();
    ASSERT_TRUE(vc_.open()) << virtGetErrorDetail(nullptr);
    ASSERT_TRUE(powered_in_impedance(vc_));
  }
  ControllerStack stack_{"capistate"};
  VirtuoseSession vc_{stack_};
};

/// The shift: the avatar held while the operator moves the handle, the offset kept after.
void expect_a_shift_holds_the_avatar(const ControllerStack& stack, VirtContext vc) {
  EXPECT_LT(distance(avatar(vc), physical(vc)), 1e-6) << "no offset before any shift";
  const Pose held = avatar(vc);
  ASSERT_EQ(virtForceShiftButton(vc, 1), 0);
  int shifted = 0;
  ASSERT_EQ(virtIsInShiftPosition(vc, &shifted), 0);
  EXPECT_EQ(shifted, 1);
  operator_push(stack, vc, {0, 4, 0, 0, 0, 0}, 300ms);
  const Pose moved = physical(vc);
  ASSERT_GT(distance(moved, held), 0.01) << "the push moved the handle";
  EXPECT_LT(distance(avatar(vc), held), 1e-4) << "the avatar kept still";
  std::array<float, 6> speed{};
  ASSERT_EQ(virtGetSpeed(vc, speed.data()), 0);
  EXPECT_EQ(speed[1], 0.0F) << "and has no speed while shifted";
  ASSERT_EQ(virtForceShiftButton(vc, 0), 0);
  ASSERT_EQ(virtIsInShiftPosition(vc, &shifted), 0);
  EXPECT_EQ(shifted, 0);
  // Released: the avatar follows the handle again, from where it was held.
  operator_push(stack, vc, {0, -4, 0, 0, 0, 0}, 150ms);
  const Pose p = physical(vc);
  const Pose a = avatar(vc);
  ASSERT_GT(distance(p, moved), 0.005);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(a[i] - p[i], held[i] - moved[i], 1e-3) << "the offset kept, axis " << i;
  }
  EXPECT_EQ(virtIsInShiftPosition(vc, nullptr), -1);
}

TEST(VirtuoseShift, HoldsTheAvatarWhileTheHandleMovesAndKeepsTheOffsetAfter) {
  // The handle must come to rest after each push: a core the machine failed safe meanwhile (or
  // a stall under the push) spoils that, not the shift (once beside stress-ng, 2026-12-03).
  retry_what_the_machine_disturbed("shift", 3, [](int attempt) {
    ControllerStack stack("capishift" + std::to_string(attempt));
    VirtuoseSession vc(stack);
    if (!stack.ready() || !vc.open()) {
      ADD_FAILURE() << stack.diagnostics() << virtGetErrorDetail(nullptr);
      return true;
    }
    if (powered_in_impedance(vc)) {
      expect_a_shift_holds_the_avatar(stack, vc.get());
    }
    return true;
  });
}

TEST_F(VirtuoseState, AnInhibitingIndexingModeRendersNoForceWhileShifted) {
  VirtContext vc = vc_.get();
  ASSERT_EQ(virtSetIndexingMode(vc, INDEXING_ALL_FORCE_FEEDBACK_INHIBITION), 0);
  std::array<float, 6> force{1.5F, 0, 0, 0, 0, 0};
  ASSERT_EQ(virtSetForce(vc, force.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] { return stack_.vpr().impedance_wrench[0] == 1.5; }));
  ASSERT_EQ(virtForceShiftButton(vc, 1), 0);
  ASSERT_EQ(virtSetForce(vc, force.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] { return stack_.vpr().impedance_wrench[0] == 0.0; }));
  ASSERT_EQ(virtForceShiftButton(vc, 0), 0);
  ASSERT_EQ(virtSetForce(vc, force.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] { return stack_.vpr().impedance_wrench[0] == 1.5; }));
  std::array<float, 6> none{};
  ASSERT_EQ(virtSetForce(vc, none.data()), 0);
}

TEST_F(VirtuoseState, TheSaturationAlarmFollowsTheClippedWrench) {
  VirtContext vc = vc_.get();
  ASSERT_EQ(virtSaturateTorque(vc, 1.0F, 0.2F), 0);
  unsigned int alarm = 0xFFFFFFFF;
  ASSERT_EQ(virtGetAlarm(vc, &alarm), 0);
  EXPECT_EQ(alarm & VIRT_ALARM_SATURATE, 0U);
  std::array<float, 6> over{1.5F, 0, 0, 0, 0, 0};
  ASSERT_EQ(virtSetForce(vc, over.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] {
    return virtGetAlarm(vc, &alarm) == 0 && (alarm & VIRT_ALARM_SATURATE) != 0;
  })) << "1.5 N over the 1 N asked";
  std::array<float, 6> within{0.5F, 0, 0, 0, 0, 0};
  ASSERT_EQ(virtSetForce(vc, within.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return virtGetAlarm(vc, &alarm) == 0 && (alarm & VIRT_ALARM_SATURATE) == 0; }));
  std::array<float, 6> none{};
  ASSERT_EQ(virtSetForce(vc, none.data()), 0);
}

TEST_F(VirtuoseState, IsInBoundsNamesTheJointsTheControllerHoldsInTheirWalls) {
  VirtContext vc = vc_.get();
  unsigned int bounds = 0xFFFF;
  ASSERT_EQ(virtIsInBounds(vc, &bounds), 0);
  EXPECT_EQ(bounds, 0U) << "the rest pose is clear of every wall";
  // A steady torque turns the wrist until a joint meets its wall.
  std::array<float, 6> twist{0, 0, 0, 0.3F, 0, 0.3F};
  EXPECT_TRUE(ControllerStack::eventually(
      [&] {
        virtSetForce(vc, twist.data());
        return virtIsInBounds(vc, &bounds) == 0 && bounds != 0;
      },
      5s));
  std::array<float, 6> q{};
  ASSERT_EQ(virtGetArticularPosition(vc, q.data()), 0);
  // The shipped model's limits (arm_model/models/virtuose6d_class.arm) and the wall's 0.05 rad.
  constexpr std::array<std::pair<float, float>, 7> kLimits{{{-2.4F, 2.4F},
                                                            {-1.6F, 0.6F},
                                                            {0.2F, 2.6F},
                                                            {-2.6F, 2.6F},
                                                            {-1.4F, 1.4F},
                                                            {-2.6F, 2.6F},
                                                            {-0.6F, 2.2F}}};
  constexpr std::array<unsigned, 14> kBits{
      VIRT_BOUND_LEFT_AXE_1,  VIRT_BOUND_RIGHT_AXE_1, VIRT_BOUND_INF_AXE_2,  VIRT_BOUND_SUP_AXE_2,
      VIRT_BOUND_INF_AXE_3,   VIRT_BOUND_SUP_AXE_3,   VIRT_BOUND_LEFT_AXE_4, VIRT_BOUND_RIGHT_AXE_4,
      VIRT_BOUND_INF_AXE_5,   VIRT_BOUND_SUP_AXE_5,   VIRT_BOUND_LEFT_AXE_6, VIRT_BOUND_RIGHT_AXE_6,
      VIRT_BOUND_INF_AXE_2_3, VIRT_BOUND_SUP_AXE_2_3};
  constexpr float kNear = 0.05F + 0.02F;  // the wall, and the motion between the two reads
  for (std::size_t i = 0; i < kBits.size(); ++i) {
    if ((bounds & kBits[i]) == 0U) {
      continue;
    }
    const std::size_t j = i / 2;
    const float value = j < 6 ? q[j] : q[1] + q[2];
    const float limit = i % 2 == 0 ? kLimits[j].first : kLimits[j].second;
    EXPECT_LT(std::abs(value - limit), kNear) << "bit " << i << ": joint at " << value;
  }
  std::array<float, 6> none{};
  ASSERT_EQ(virtSetForce(vc, none.data()), 0);
}

}  // namespace
}  // namespace hapticctrl
