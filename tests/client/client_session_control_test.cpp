// The client's control frames (client_session_control.cpp) without a socket: what leaves for
// an object state, a wrench, a joint command and contacts.
#include <gtest/gtest.h>

#include <cmath>

#include "client_session.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "support/client_session_frames.hpp"

namespace hapticctrl::client {
namespace {

using test::answer;
using namespace std::chrono_literals;
using test::at;
using test::open_session;

TEST(ClientSession, ObjectFramesCarryTheEchoOfTheNewestAnswerAndRefuseANonRotation) {
  ClientSession s = open_session();
  const auto before = s.object_frame({0, 0, 0, 0, 0, 0, 1}, {}, at(1ms));
  ASSERT_TRUE(before.has_value());
  EXPECT_FALSE(protocol::unpack_answer_echo(before->body.hcp_body_u.timed.answer_echo).valid)
      << "no answer yet: the echo says so";
  ASSERT_EQ(s.on_frame(answer(1, 4242), at(10ms)), Arrival::kAnswer);
  const auto f = s.object_frame({0.1, 0.2, 0.3, 0, 0, 0, 1}, {0.01, 0, 0, 0, 0, 0}, at(12ms));
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->body.type, HCP_CONTROL_OBJECT_TIMED) << "the controller speaks timing";
  const protocol::AnswerEcho echo =
      protocol::unpack_answer_echo(f->body.hcp_body_u.timed.answer_echo);
  EXPECT_TRUE(echo.valid);
  EXPECT_EQ(echo.cycle_low, 4242U);
  EXPECT_EQ(echo.hold_ns, to_ns(2ms)) << "held from its arrival to this send";
  EXPECT_FLOAT_EQ(f->body.hcp_body_u.timed.position[2], 0.3F);
  EXPECT_FALSE(s.object_frame({0, 0, 0, 0, 0, 0, 2}, {}, at(13ms)).has_value())
      << "a quaternion of norm 2 is not a rotation";
}

TEST(ClientSession, AWrenchOrJointCommandLeavesOnlyWhenTheProtocolTakesIt) {
  ClientSession s = open_session();
  const auto w = s.wrench_frame({1, 2, 3, 0, 0, 0}, at(1ms));
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->body.type, HCP_CONTROL_WRENCH_TIMED) << "the controller speaks local coupling";
  EXPECT_FALSE(s.wrench_frame({std::nan(""), 0, 0, 0, 0, 0}, at(1ms)).has_value()) << "a NaN";
  const auto t = s.joint_torque_frame({0, 0, 0.5, 0, 0, 0}, at(1ms));
  ASSERT_TRUE(t.has_value());
  EXPECT_FLOAT_EQ(t->body.hcp_body_u.joint_torque.torque[2], 0.5F);
  EXPECT_FALSE(s.joint_target_frame({0, std::nan(""), 0, 0, 0, 0}, {}, at(1ms)).has_value())
      << "a NaN set point";
}

}  // namespace
}  // namespace hapticctrl::client
