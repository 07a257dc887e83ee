// Tests of parameter_channel.hpp alone: the order of a session's PARAM frames (applied once,
// replayed, stale) and what each parameter does to VPr, the watchdog or the controller.
#include "hapticctrl/udp_bridge/parameter_channel.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace hapticctrl::udp_bridge {
namespace {

using Step = ParameterChannel::Step;

TEST(ParameterChannel, EachParameterIsAppliedOnceAndItsAckReplayed) {
  ParameterChannel channel;
  EXPECT_EQ(channel.step_for(7), Step::kApply) << "the first of a session, whatever its number";
  ParamAck ack{7, HCP_ACK_REJECTED};
  std::strcpy(ack.reason, "why");
  channel.record(ack);
  EXPECT_EQ(channel.step_for(7), Step::kReplay);
  EXPECT_STREQ(channel.last().reason, "why") << "the same ACK again, reason and all";
  EXPECT_EQ(channel.step_for(6), Step::kStale);
  EXPECT_EQ(channel.step_for(8), Step::kApply);
  channel.record({8, HCP_ACK_RETRY});
  EXPECT_EQ(channel.step_for(8), Step::kApply) << "a RETRY is not recorded: its retransmission";
  EXPECT_EQ(channel.last().sequence, 7U);
  channel.record({0x00000002U, HCP_ACK_OK});
  EXPECT_EQ(channel.step_for(0xFFFFFFFEU), Step::kStale) << "before the wrap";
  channel.reset();
  EXPECT_EQ(channel.step_for(1), Step::kApply) << "a new session";
}

hcp_param param(hcp_param_id id) {
  hcp_param p{};
  p.id = id;
  return p;
}

TEST(ApplyParam, EachParameterLandsInVprOrAsACommand) {
  shm::VprPayload vpr;
  std::uint32_t watchdog_ms = 100;
  hcp_param p = param(HCP_P_FORCE_FACTOR);
  p.hcp_param_u.force_factor = 0.5;
  EXPECT_EQ(apply_param(p, 1000, vpr, watchdog_ms).ctrl, shm::CtrlCode::kNone);
  EXPECT_EQ(vpr.force_factor, 0.5);
  p = param(HCP_P_OBJECT);
  p.hcp_param_u.object = {1, 0.3, {0.001, 0.002, 0.003}};
  (void)apply_param(p, 1000, vpr, watchdog_ms);
  EXPECT_NE(vpr.flags & shm::vpr_flags::kObjectAttached, 0U);
  EXPECT_EQ(vpr.object_mass, 0.3);
  EXPECT_EQ(vpr.object_inertia[2], 0.003);
  p = param(HCP_P_WATCHDOG);
  p.hcp_param_u.watchdog_ms = 60'000;
  (void)apply_param(p, 1000, vpr, watchdog_ms);
  EXPECT_EQ(watchdog_ms, 1000U) << "capped";
  EXPECT_EQ(vpr.watchdog_timeout_us, 1'000'000U);
  p = param(HCP_P_POWER);
  p.hcp_param_u.power_on = 1;
  const ParamEffect on = apply_param(p, 1000, vpr, watchdog_ms);
  EXPECT_EQ(on.ctrl, shm::CtrlCode::kPowerOn);
  EXPECT_EQ(on.ctrl_arg, shm::kPowerOnByClient) << "the core refuses it after a fault (J8)";
  EXPECT_EQ(apply_param(param(HCP_P_EMERGENCY_STOP), 1000, vpr, watchdog_ms).ctrl,
            shm::CtrlCode::kEmergencyStop);
}

TEST(ApplyParam, ANewCommandTypeClearsTheJointCommandOfTheOneBefore) {
  shm::VprPayload vpr;
  std::uint32_t watchdog_ms = 100;
  vpr.command_type = HCP_COMMAND_ARTICULAR;
  vpr.flags = shm::vpr_flags::kJointCommand | shm::vpr_flags::kObjectAttached;
  vpr.joint_target[1] = 0.4;
  hcp_param p = param(HCP_P_COMMAND_TYPE);
  p.hcp_param_u.command_type = HCP_COMMAND_ARTICULAR;
  (void)apply_param(p, 1000, vpr, watchdog_ms);
  EXPECT_EQ(vpr.joint_target[1], 0.4) << "the same type again changes nothing";
  p.hcp_param_u.command_type = HCP_COMMAND_ARTICULAR_IMPEDANCE;
  (void)apply_param(p, 1000, vpr, watchdog_ms);
  EXPECT_EQ(vpr.command_type, HCP_COMMAND_ARTICULAR_IMPEDANCE);
  EXPECT_EQ(vpr.joint_target[1], 0.0);
  EXPECT_EQ(vpr.flags, shm::vpr_flags::kObjectAttached);
}

TEST(ApplyParam, JointModesNeedJointControl) {
  hcp_param p = param(HCP_P_COMMAND_TYPE);
  p.hcp_param_u.command_type = HCP_COMMAND_ARTICULAR_IMPEDANCE;
  EXPECT_NE(missing_feature(p, HCP_FEATURE_TIMING), nullptr);
  EXPECT_EQ(missing_feature(p, HCP_FEATURE_JOINT_CONTROL), nullptr);
  p.hcp_param_u.command_type = HCP_COMMAND_VIRTMECH;
  EXPECT_EQ(missing_feature(p, 0), nullptr);
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
