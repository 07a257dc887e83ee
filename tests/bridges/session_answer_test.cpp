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
using namespace std::chrono_literals;

TEST_F(SessionTest, AnswersGoToTheSessionWithTheNegotiatedFeatures) {
  shm::VpPayload vp;
  vp.cycle = 77;
  vp.echo_client_sequence = 3;
  vp.joint_position[0] = 0.5;
  FrameBuffer out{};
  Endpoint to;
  EXPECT_EQ(session.answer(vp, TimePoint{}, out, to), 0U);  // no session, no answer
  client.hello(protocol::kVersion, HCP_FEATURE_LINK_STATS);
  client.send_object(0.1F);
  const std::size_t n = session.answer(vp, TimePoint{}, out, to);
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

TEST_F(SessionTest, AnswersAndLinkStatsCarryTheLinkAsTheBridgeMeasuresIt) {
  // The link figures come from the bridge's own estimator, not round through the core's VP
  // (which no longer carries them, J7): a 3 ms round trip is a 1.5 ms one-way delay.
  client.hello(protocol::kVersion, HCP_FEATURE_LINK_STATS | HCP_FEATURE_TIMING);
  shm::VpPayload vp;
  vp.cycle = 500;
  FrameBuffer out{};
  Endpoint to;
  ASSERT_GT(session.answer(vp, client.now, out, to), 0U);  // answer 500 leaves at `now`
  client.now += 4ms;  // the state computed from it; the client held it 1 ms
  client.feed(client.bytes(client.timed_object(500, 1ms, 0)));
  const shm::VprPayload vpr = controller.vpr_now();
  ASSERT_GT(vpr.link_delay_ns, 0);

  vp.cycle = 501;
  const std::size_t n = session.answer(vp, client.now, out, to);
  ASSERT_GT(n, 0U);
  hcp_frame a;
  ASSERT_EQ(protocol::decode({out.data(), n}, a), protocol::DecodeStatus::kOk);
  ASSERT_EQ(a.body.type, HCP_ANSWER_TIMED);
  const hcp_coupling_report& report = a.body.hcp_body_u.answer_timed.coupling;
  EXPECT_DOUBLE_EQ(report.link_delay_s, static_cast<double>(vpr.link_delay_ns) * 1e-9);
  EXPECT_NEAR(report.link_delay_s, 1.5e-3, 1e-6);
  EXPECT_DOUBLE_EQ(report.link_jitter_s, static_cast<double>(vpr.link_jitter_ns) * 1e-9);

  shm::LinkStatsPayload stats;
  session.fill_stats(stats);
  EXPECT_EQ(stats.link_delay_ns, vpr.link_delay_ns);
  EXPECT_EQ(stats.link_jitter_ns, vpr.link_jitter_ns);
  EXPECT_EQ(stats.link_loss_ppm, vpr.link_loss_ppm);

  // A new session starts from no link figures.
  client.feed(client.bytes(
      protocol::make_frame(HCP_BYE, client.token, ++client.param_seq, to_ns(client.now))));
  client.hello(protocol::kVersion, HCP_FEATURE_LINK_STATS | HCP_FEATURE_TIMING);
  session.fill_stats(stats);
  EXPECT_EQ(stats.link_delay_ns, 0);
  const std::size_t fresh = session.answer(vp, client.now, out, to);
  ASSERT_GT(fresh, 0U);
  ASSERT_EQ(protocol::decode({out.data(), fresh}, a), protocol::DecodeStatus::kOk);
  EXPECT_EQ(a.body.hcp_body_u.answer_timed.coupling.link_delay_s, 0.0);
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
