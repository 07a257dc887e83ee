// Tests of control_ingest.hpp alone (no session, no shm): the order of control frames, the link
// they measure, the client's energy and what each frame writes into VPr.
#include "hapticctrl/udp_bridge/control_ingest.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "support/protocol_frames.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using namespace std::chrono_literals;

struct ControlIngestTest : testing::Test {
  std::unique_ptr<AnswerLog> answers = std::make_unique<AnswerLog>();  // 64 KiB: on the heap
  ControlIngest ingest{*answers};
  shm::VprPayload vpr;

  static hcp_frame timed_object(std::uint32_t sequence, std::uint64_t answer_cycle, Duration hold,
                                std::uint32_t energy_uj) {
    hcp_frame f =
        protocol::test::timed_object_frame(1, sequence, 0, answer_cycle, to_ns(hold), energy_uj);
    f.body.hcp_body_u.timed.position[1] = -0.2F;
    return f;
  }
};

TEST_F(ControlIngestTest, OnlyNewerFramesAreAdmittedAndTheSequenceGrowsPast32Bits) {
  EXPECT_TRUE(ingest.admit(0xFFFFFFF0U));
  EXPECT_FALSE(ingest.admit(0xFFFFFFF0U)) << "replayed";
  EXPECT_FALSE(ingest.admit(0xFFFFFFE0U)) << "reordered";
  EXPECT_TRUE(ingest.admit(0x00000010U)) << "wrapped: 32 later";
  hcp_frame f = protocol::make_frame(HCP_CONTROL_OBJECT, 1, 0x10, 77);
  ingest.take(f, TimePoint{}, vpr);
  EXPECT_EQ(vpr.client_sequence, 0x100000010U);
  EXPECT_EQ(vpr.client_time_ns, 77);
  EXPECT_EQ(vpr.link_loss_ppm, ingest.link().loss_ppm);
  EXPECT_GT(ingest.link().loss_ppm, 0U) << "31 sequence numbers skipped";
  ingest.reset();
  EXPECT_TRUE(ingest.admit(5U)) << "a new session starts from any number";
  EXPECT_EQ(ingest.link().loss_ppm, 0U);
}

TEST_F(ControlIngestTest, ATimedObjectIsDatedFromTheAnswerItEchoesAndCarriesTheEnergy) {
  answers->record(500, TimePoint{10ms});
  ASSERT_TRUE(ingest.admit(1));
  ingest.take(timed_object(1, 500, 1ms, 0xFFFFFF00U), TimePoint{14ms}, vpr);
  EXPECT_EQ(vpr.echo_cycle, 500U);
  EXPECT_EQ(vpr.sample_time_ns, to_ns(TimePoint{14ms - 1500us}))
      << "half of the 3 ms network round trip";
  EXPECT_FLOAT_EQ(static_cast<float>(vpr.object_pose[1]), -0.2F);
  EXPECT_NEAR(vpr.object_pose[6], 1.0, 1e-6);
  EXPECT_EQ(ingest.link().delay, 1500us);
  EXPECT_EQ(vpr.link_delay_ns, to_ns(1500us));
  EXPECT_EQ(vpr.client_energy_in, 0.0) << "the first report is the reference";
  ASSERT_TRUE(ingest.admit(2));
  ingest.take(timed_object(2, 500, 1ms, 0x00000100U), TimePoint{14ms}, vpr);  // wraps: +512 uJ
  EXPECT_NEAR(vpr.client_energy_in, 512e-6, 1e-12);
  ASSERT_TRUE(ingest.admit(3));
  ingest.take(timed_object(3, 500, 1ms, 0x80000000U), TimePoint{14ms}, vpr);  // +2147 J
  EXPECT_NEAR(vpr.client_energy_in, 512e-6, 1e-12) << "not physical: ignored";
  ASSERT_TRUE(ingest.admit(4));
  ingest.take(timed_object(4, 99, 0ms, 0x80000000U), TimePoint{15ms}, vpr);
  EXPECT_EQ(vpr.sample_time_ns, 0) << "an answer the log does not hold: the sample is undated";
  EXPECT_EQ(vpr.echo_cycle, 0U);
}

TEST_F(ControlIngestTest, JointFramesCountAsTheCommandOfTheirModeOnly) {
  vpr.command_type = static_cast<std::uint32_t>(shm::CommandType::kArticular);
  hcp_frame torque = protocol::make_frame(HCP_CONTROL_JOINT_TORQUE, 1, 1, 0);
  torque.body.hcp_body_u.joint_torque.torque[2] = 0.5F;
  ingest.take(torque, TimePoint{}, vpr);
  EXPECT_DOUBLE_EQ(vpr.joint_torque[2], 0.5);
  EXPECT_EQ(vpr.flags & shm::vpr_flags::kJointCommand, 0U) << "a torque is not ARTICULAR's";
  hcp_frame target = protocol::make_frame(HCP_CONTROL_JOINT_TARGET, 1, 2, 0);
  target.body.hcp_body_u.joint_target.position[1] = -0.5F;
  target.body.hcp_body_u.joint_target.speed[5] = 0.25F;
  ingest.take(target, TimePoint{}, vpr);
  EXPECT_DOUBLE_EQ(vpr.joint_target[1], -0.5);
  EXPECT_DOUBLE_EQ(vpr.joint_speed[5], 0.25);
  EXPECT_NE(vpr.flags & shm::vpr_flags::kJointCommand, 0U);
}

TEST_F(ControlIngestTest, AContactFillsItsSlotEmptiesThoseAboveAndIsNotANewSample) {
  vpr.command_type = static_cast<std::uint32_t>(shm::CommandType::kVirtmech);
  vpr.object_pose = {0.1, 0, 0, 0, 0, 0, 1};
  vpr.contacts[3].stiffness = 900;  // left from before
  vpr.client_sequence = 41;
  hcp_frame f = protocol::make_frame(HCP_CONTROL_CONTACT, 1, 7, 0);
  hcp_control_contact& c = f.body.hcp_body_u.contact;
  c.slots = protocol::pack_contact_slots(1, 2);
  c.contact.normal[2] = 1.0F;
  c.contact.distance = -0.002F;
  c.contact.stiffness = 3000.0F;
  ingest.take(f, TimePoint{5ms}, vpr);
  EXPECT_EQ(vpr.contact_count, 2U);
  EXPECT_EQ(vpr.contact_frames, 1U);
  EXPECT_DOUBLE_EQ(vpr.contacts[1].stiffness, 3000.0);
  EXPECT_FLOAT_EQ(static_cast<float>(vpr.contacts[1].distance), -0.002F);
  EXPECT_EQ(vpr.contacts[1].object_pose[0], 0.1) << "the object's pose when it came";
  EXPECT_EQ(vpr.contacts[1].received_time_ns, to_ns(5ms));
  EXPECT_EQ(vpr.contacts[3].stiffness, 0.0) << "at and above the count: empty";
  EXPECT_EQ(vpr.client_sequence, 41U) << "a contact is not an object sample";
  vpr.command_type = static_cast<std::uint32_t>(shm::CommandType::kImpedance);
  ingest.take(f, TimePoint{6ms}, vpr);
  EXPECT_EQ(vpr.contacts[1].object_pose[0], 0.0) << "IMPEDANCE: no object, the identity";
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
