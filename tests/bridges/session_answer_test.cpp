// The UDP bridge's answer side (session_answer.cpp): answers to the session's client with the
// negotiated features, and the link statistics.
#include <gtest/gtest.h>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/udp_bridge/session.hpp"
#include "support/session_client.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using protocol::Endpoint;
using protocol::FrameBuffer;
using test::SessionTest;

TEST_F(SessionTest, AnswersGoToTheSessionWithTheNegotiatedFeatures) {
  shm::VpPayload vp;
  vp.cycle = 77;
  vp.echo_client_sequence = 3;
  vp.joint_position[0] = 0.5;
  FrameBuffer out{};
  Endpoint to;
  EXPECT_EQ(session.answer(vp, 0, out, to), 0U);  // no session, no answer
  client.hello(protocol::kVersion, HCP_FEATURE_LINK_STATS);
  client.send_object(0.1F);
  const std::size_t n = session.answer(vp, 0, out, to);
  ASSERT_GT(n, 0U);
  EXPECT_EQ(to, client.from);
  hcp_frame a;
  ASSERT_EQ(protocol::decode({out.data(), n}, a), protocol::DecodeStatus::kOk);
  EXPECT_EQ(a.header.token, client.token);
  EXPECT_EQ(a.body.hcp_body_u.answer.cycle, 77U);
  EXPECT_EQ(a.body.hcp_body_u.answer.echo_sequence, 3U);
  EXPECT_EQ(a.body.hcp_body_u.answer.control_received, 1U);
  EXPECT_EQ(a.body.hcp_body_u.answer.joint_position[0], 0.0);  // JOINT_STATE not negotiated
}

TEST_F(SessionTest, StatsReflectTheSessionAndCounters) {
  client.hello();
  client.send_object(0.1F);
  shm::LinkStatsPayload s;
  session.fill_stats(s);
  EXPECT_EQ(s.session_id, 1U);
  EXPECT_EQ(s.peer_port, 40000U);
  EXPECT_EQ(s.peer_ipv4, 0x7F000001U);
  EXPECT_EQ(s.frames_in, 2U);
  EXPECT_EQ(s.control_accepted, 1U);
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
