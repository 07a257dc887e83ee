// The UDP bridge's parameter frames (session_parameters.cpp): applied once, acknowledged, a
// rejection with its reason, a full ctrl queue answered with a retry.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/udp_bridge/session.hpp"
#include "support/reference_parameters.hpp"
#include "support/session_client.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using protocol::FrameBuffer;
using namespace std::chrono_literals;
using test::SessionTest;

TEST_F(SessionTest, EveryParameterReachesVprOrCtrl) {
  client.hello();
  const auto apply = [&](hcp_frame f) {
    client.feed(client.bytes(f));
    ASSERT_TRUE(client.replied);
    ASSERT_EQ(client.reply.body.type, HCP_ACK);
    EXPECT_EQ(client.reply.body.hcp_body_u.ack.acked_sequence, f.header.sequence);
    EXPECT_EQ(client.reply.body.hcp_body_u.ack.status, HCP_ACK_OK);
  };
  hcp_frame f = client.param(HCP_P_TIME_STEP);
  f.body.hcp_body_u.param.hcp_param_u.time_step = 0.002;
  apply(f);
  f = client.param(HCP_P_FORCE_FACTOR);
  f.body.hcp_body_u.param.hcp_param_u.force_factor = 0.5;
  apply(f);
  f = client.param(HCP_P_SPEED_FACTOR);
  f.body.hcp_body_u.param.hcp_param_u.speed_factor = 2.0;
  apply(f);
  f = client.param(HCP_P_BASE_FRAME);
  f.body.hcp_body_u.param.hcp_param_u.base_frame[2] = 0.1;
  f.body.hcp_body_u.param.hcp_param_u.base_frame[6] = 1.0;
  apply(f);
  f = client.param(HCP_P_OBSERVATION_FRAME);
  f.body.hcp_body_u.param.hcp_param_u.observation_frame[0] = -0.1;
  f.body.hcp_body_u.param.hcp_param_u.observation_frame[6] = 1.0;
  apply(f);
  f = client.param(HCP_P_INDEXING_MODE);
  f.body.hcp_body_u.param.hcp_param_u.indexing_mode = 1;
  apply(f);
  f = client.param(HCP_P_COMMAND_TYPE);
  f.body.hcp_body_u.param.hcp_param_u.command_type = 2;
  apply(f);
  f = client.param(HCP_P_OBJECT);
  f.body.hcp_body_u.param.hcp_param_u.object = {1, 0.3, {0.001, 0.002, 0.003}};
  apply(f);
  f = client.param(HCP_P_GAINS);
  f.body.hcp_body_u.param.hcp_param_u.gains[0] = 800.0;
  apply(f);
  f = client.param(HCP_P_FORCE_LIMITS);
  f.body.hcp_body_u.param.hcp_param_u.force_limits[0] = 10.0;
  apply(f);
  f = client.param(HCP_P_WATCHDOG);
  f.body.hcp_body_u.param.hcp_param_u.watchdog_ms = 300;
  apply(f);
  test::expect_reference_parameters(controller.vpr_now());
  EXPECT_FALSE(session.check_watchdog(client.now + 250ms));
  // 1.2: the frames in single precision land in the same fields.
  f = client.param(HCP_P_BASE_FRAME_SP);
  f.body.hcp_body_u.param.hcp_param_u.base_frame_sp[0] = 0.25F;
  f.body.hcp_body_u.param.hcp_param_u.base_frame_sp[6] = 1.0F;
  apply(f);
  f = client.param(HCP_P_OBSERVATION_FRAME_SP);
  f.body.hcp_body_u.param.hcp_param_u.observation_frame_sp[1] = -0.5F;
  f.body.hcp_body_u.param.hcp_param_u.observation_frame_sp[6] = 1.0F;
  apply(f);
  EXPECT_EQ(controller.vpr_now().base_frame[0], 0.25);
  EXPECT_EQ(controller.vpr_now().observation_frame[1], -0.5);

  f = client.param(HCP_P_POWER);
  f.body.hcp_body_u.param.hcp_param_u.power_on = 1;
  apply(f);
  apply(client.param(HCP_P_EMERGENCY_STOP));
  apply(client.param(HCP_P_EMERGENCY_RESET));
  f = client.param(HCP_P_POWER);
  apply(f);
  EXPECT_EQ(controller.drain(),
            (std::vector<shm::CtrlCode>{shm::CtrlCode::kPowerOn, shm::CtrlCode::kEmergencyStop,
                                        shm::CtrlCode::kEmergencyReset, shm::CtrlCode::kPowerOff}));
  EXPECT_EQ(session.counters().params_applied.load(), 17U);
}

TEST_F(SessionTest, ARetransmittedParameterIsAcknowledgedAgainButAppliedOnce) {
  client.hello();
  hcp_frame on = client.param(HCP_P_POWER);
  on.body.hcp_body_u.param.hcp_param_u.power_on = 1;
  const auto bytes = client.bytes(on);
  client.feed(bytes);
  client.feed(bytes);
  ASSERT_EQ(client.reply.body.type, HCP_ACK);
  EXPECT_EQ(client.reply.body.hcp_body_u.ack.acked_sequence, on.header.sequence);
  EXPECT_EQ(controller.drain().size(), 1U);
  EXPECT_EQ(session.counters().param_duplicates.load(), 1U);
  hcp_frame older = on;
  older.header.sequence = 0;
  client.feed(client.bytes(older));
  EXPECT_FALSE(client.replied);
}

TEST_F(SessionTest, AnOutOfRangeParameterIsRejectedWithTheReason) {
  client.hello();
  hcp_frame f = client.param(HCP_P_FORCE_FACTOR);
  f.body.hcp_body_u.param.hcp_param_u.force_factor = -2.0;
  client.feed(client.bytes(f));
  ASSERT_EQ(client.reply.body.type, HCP_ACK);
  EXPECT_EQ(client.reply.body.hcp_body_u.ack.status, HCP_ACK_REJECTED);
  EXPECT_EQ(protocol::text_of(client.reply.body.hcp_body_u.ack.reason),
            "force factor: between 0.001 and 1000");
  EXPECT_DOUBLE_EQ(controller.vpr_now().force_factor, 1.0);
  EXPECT_EQ(session.counters().params_rejected.load(), 1U);
}

TEST_F(SessionTest, AFullCtrlQueueAsksForARetryAndTheRetryApplies) {
  client.hello();
  for (std::size_t i = 0; i < shm::kCtrlRingSize; ++i) {
    ASSERT_EQ(controller.writer.send(shm::CtrlCode::kPowerOff, 0, 0), shm::CtrlSendStatus::kQueued);
  }
  hcp_frame on = client.param(HCP_P_POWER);
  on.body.hcp_body_u.param.hcp_param_u.power_on = 1;
  client.feed(client.bytes(on));
  EXPECT_EQ(client.reply.body.hcp_body_u.ack.status, HCP_ACK_RETRY);
  controller.drain();
  client.feed(client.bytes(on));
  EXPECT_EQ(client.reply.body.hcp_body_u.ack.status, HCP_ACK_OK);
  EXPECT_EQ(controller.drain(), std::vector<shm::CtrlCode>{shm::CtrlCode::kPowerOn});
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
