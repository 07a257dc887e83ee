// The C API's per-cycle commands against the real controller and bridge.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/virtuose_api.h"
#include "support/controller_stack.hpp"
#include "virtuose_session.hpp"

namespace hapticctrl {
namespace {

using test::ControllerStack;
using test::VirtuoseSession;

TEST(VirtuoseCommands, EachCommandNeedsItsModeAndReachesTheController) {
  ControllerStack stack("capicommands");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  std::array<float, 7> pose{};
  ASSERT_EQ(virtGetPosition(vc.get(), pose.data()), 0);
  std::array<float, 6> speed{0.01F, 0, 0, 0, 0, 0};
  std::array<float, 6> force{1, 0, 0, 0, 0, 0};
  EXPECT_EQ(virtSetPosition(vc.get(), pose.data()), -1) << "COMMAND_TYPE_NONE";
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);
  EXPECT_EQ(virtSetForce(vc.get(), force.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);

  ASSERT_EQ(virtSetCommandType(vc.get(), COMMAND_TYPE_VIRTMECH), 0);
  ASSERT_EQ(virtSetSpeed(vc.get(), speed.data()), 0);
  pose[0] += 0.001F;
  ASSERT_EQ(virtSetPosition(vc.get(), pose.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] {
    const shm::VprPayload v = stack.vpr();
    return std::abs(v.object_pose[0] - static_cast<double>(pose[0])) < 1e-6 &&
           std::abs(v.object_twist[0] - 0.01) < 1e-6;
  })) << "the pose with the speed set before it";
  EXPECT_EQ(virtSetForce(vc.get(), force.data()), -1);
  EXPECT_EQ(virtAddForce(vc.get(), force.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);
  pose[6] = 3.0F;  // not a unit quaternion: the library refuses to send it
  EXPECT_EQ(virtSetPosition(vc.get(), pose.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_INCORRECT_VALUE);

  ASSERT_EQ(virtSetCommandType(vc.get(), COMMAND_TYPE_IMPEDANCE), 0);
  ASSERT_EQ(virtAddForce(vc.get(), force.data()), 0);  // with the next virtSetForce
  ASSERT_EQ(virtSetForce(vc.get(), force.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] { return stack.vpr().impedance_wrench[0] == 2.0; }));
  EXPECT_EQ(virtSetForce(vc.get(), nullptr), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_INCORRECT_VALUE);
  EXPECT_EQ(virtSetSpeed(nullptr, speed.data()), -1);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INVALID_CONTEXT);
}

TEST(VirtuoseCommands, JointSpaceTakesTheJointsToTheApplicationsPositionsAndCarriesItsTorques) {
  // J6: COMMAND_TYPE_ARTICULAR and ARTICULAR_IMPEDANCE through the real core and bridge.
  ControllerStack stack("capijoints");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  std::array<float, 6> q{};
  std::array<float, 6> none{};
  EXPECT_EQ(virtSetArticularPosition(vc.get(), q.data()), -1) << "COMMAND_TYPE_NONE";
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);
  ASSERT_EQ(virtGetArticularPosition(vc.get(), q.data()), 0);
  ASSERT_EQ(virtSetCommandType(vc.get(), COMMAND_TYPE_ARTICULAR), 0) << vc.detail();
  std::array<float, 6> target = q;
  // From the ready pose to where servo_law_closed_loop_test.cpp takes it: a handle inside the
  // workspace box, whose wall would hold the arm back.
  const std::array<float, 6> move{0.2F, 0.1F, -0.1F, 0.5F, 0.2F, 0.6F};
  for (std::size_t i = 0; i < 6; ++i) {
    target.at(i) += move.at(i);
  }
  ASSERT_EQ(virtSetArticularSpeed(vc.get(), none.data()), 0);
  ASSERT_EQ(virtSetPowerOn(vc.get(), 1), 0) << vc.detail();
  float worst = 1.0F;
  const bool reached = ControllerStack::eventually(
      [&] {
        virtSetArticularPosition(vc.get(), target.data());  // as an application's loop does
        virtGetArticularPosition(vc.get(), q.data());
        worst = 0.0F;
        for (std::size_t i = 0; i < 6; ++i) {
          worst = std::max(worst, std::abs(q.at(i) - target.at(i)));
        }
        return worst < 0.02F;
      },
      std::chrono::seconds(5));
  EXPECT_TRUE(reached) << "the farthest joint " << worst << " rad from its target; joints " << q[0]
                       << " " << q[1] << " " << q[2] << " " << q[3] << " " << q[4] << " " << q[5]
                       << ", targets " << target[0] << " " << target[1] << " " << target[2] << " "
                       << target[3] << " " << target[4] << " " << target[5];
  EXPECT_EQ(stack.vp().command_type, static_cast<std::uint32_t>(shm::CommandType::kArticular));

  ASSERT_EQ(virtSetCommandType(vc.get(), COMMAND_TYPE_ARTICULAR_IMPEDANCE), 0) << vc.detail();
  EXPECT_EQ(virtSetArticularPosition(vc.get(), target.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);
  std::array<float, 6> torque{0.3F, 0, 0, 0, 0, -0.05F};
  ASSERT_EQ(virtSetArticularForce(vc.get(), torque.data()), 0) << vc.detail();
  EXPECT_TRUE(ControllerStack::eventually([&] {
    const shm::VprPayload v = stack.vpr();
    return (v.flags & shm::vpr_flags::kJointCommand) != 0 &&
           std::abs(v.joint_torque[0] - 0.3) < 1e-6 && std::abs(v.joint_torque[5] + 0.05) < 1e-6;
  })) << "the torques, and the flag that they are the command of the mode in force";
  torque[0] = std::nanf("");
  EXPECT_EQ(virtSetArticularForce(vc.get(), torque.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_INCORRECT_VALUE);
  unsigned int bounds = 0;
  EXPECT_EQ(virtIsInBounds(vc.get(), &bounds), 0);
}

TEST(VirtuoseCommands, ContactsReachTheControllerWithTheObjectAndBadOnesAreRefused) {
  // J2's VirtuoseAPI extension: virtSetContacts (hapticctrl's, not Haption's).
  ControllerStack stack("capicontacts");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  std::array<float, 7> pose{};
  ASSERT_EQ(virtGetPosition(vc.get(), pose.data()), 0);
  std::array<float, VIRT_CONTACT_FLOATS> wall{pose[0] + 0.03F, pose[1], pose[2], -1,   0,   0,
                                              0.002F,          2000,    5,       0.5F, 0.4F};
  EXPECT_EQ(virtSetContacts(vc.get(), 1, wall.data()), -1) << "COMMAND_TYPE_NONE";
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);
  ASSERT_EQ(virtSetCommandType(vc.get(), COMMAND_TYPE_VIRTMECH), 0);
  ASSERT_EQ(virtSetContacts(vc.get(), 1, wall.data()), 0) << virtGetErrorDetail(vc.get());
  ASSERT_EQ(virtSetPosition(vc.get(), pose.data()), 0);  // the contact goes with it
  EXPECT_TRUE(ControllerStack::eventually([&] {
    const shm::VprPayload v = stack.vpr();
    return v.contact_count == 1 && v.contacts[0].stiffness == 2000.0 &&
           std::abs(v.contacts[0].point[0] - static_cast<double>(wall[0])) < 1e-6 &&
           std::abs(v.contacts[0].friction[1] - 0.4) < 1e-6;
  })) << "the controller has the wall";

  std::array<float, VIRT_CONTACT_FLOATS> bad = wall;
  bad[3] = 2;  // not a unit normal
  EXPECT_EQ(virtSetContacts(vc.get(), 1, bad.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_INCORRECT_VALUE);
  bad = wall;
  bad[7] = 1e7F;  // stiffer than the controller renders
  EXPECT_EQ(virtSetContacts(vc.get(), 1, bad.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_INCORRECT_VALUE);
  EXPECT_EQ(virtSetContacts(vc.get(), 9, wall.data()), -1);
  EXPECT_EQ(virtSetContacts(vc.get(), 1, nullptr), -1);

  ASSERT_EQ(virtSetContacts(vc.get(), 0, nullptr), 0) << "count 0 clears them";
  ASSERT_EQ(virtSetPosition(vc.get(), pose.data()), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] { return stack.vpr().contact_count == 0; }));
}

}  // namespace
}  // namespace hapticctrl
