// The bridge's session state machine against real in-memory shm cells: handshake, parameters,
// control frames, the watchdog, and a table of bad inputs that must each be dropped, counted
// under their own reason, and leave the session unharmed. Its parts alone: handshake_test.cpp,
// parameter_channel_test.cpp, control_ingest_test.cpp.
#include "hapticctrl/udp_bridge/session.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/values.hpp"
#include "support/reference_parameters.hpp"
#include "support/session_client.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using protocol::Endpoint;
using protocol::FrameBuffer;
using shm::LinkDrop;

using test::Client;
using test::Controller;
using namespace std::chrono_literals;
using test::SessionTest;

TEST_F(SessionTest, HelloOpensASessionWithTheBridgesTokenAndPublishesIt) {
  client.hello();
  ASSERT_TRUE(client.replied);
  ASSERT_EQ(client.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(client.token, 0x1111U);
  EXPECT_EQ(client.reply.body.hcp_body_u.welcome.watchdog_ms, 100U);
  EXPECT_EQ(client.reply.body.hcp_body_u.welcome.period_ns, 1'000'000);
  EXPECT_EQ(client.reply.body.hcp_body_u.welcome.features, protocol::kAllFeatures);
  EXPECT_EQ(controller.vpr_now().session_id, 1U);
  EXPECT_EQ(controller.vpr_now().watchdog_timeout_us, 100'000U);
}

TEST_F(SessionTest, WelcomeCarriesTheControllersCycleAtSessionStart) {
  // H2: WELCOME.cycle was always 0.
  controller.cycle->store(123'456);
  client.hello();
  ASSERT_EQ(client.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(client.reply.body.hcp_body_u.welcome.cycle, 123'456U);
}

TEST_F(SessionTest, AHelloWithOutOfRangeValuesIsRefusedAsABadRequest) {
  // H2: it got no reply at all, although the .x promises REFUSE BAD_REQUEST.
  client.asked_watchdog_ms = 5;  // below 10 ms
  client.hello();
  ASSERT_TRUE(client.replied);
  ASSERT_EQ(client.reply.body.type, HCP_REFUSE);
  EXPECT_EQ(client.reply.body.hcp_body_u.refuse.code, HCP_REFUSE_BAD_REQUEST);
  EXPECT_EQ(protocol::text_of(client.reply.body.hcp_body_u.refuse.reason),
            "watchdog: 0 (default) or 10 to 60000 ms");
  EXPECT_EQ(dropped(LinkDrop::kRange), 1U) << "counted";
  EXPECT_EQ(controller.vpr_now().session_id, 0U) << "no session";
  client.asked_watchdog_ms = 100;
  client.hello();
  EXPECT_EQ(client.reply.body.type, HCP_WELCOME);
}

TEST_F(SessionTest, HelloWithoutAControllerIsRefused) {
  session.set_controller(nullptr, TimePoint{});
  client.hello();
  ASSERT_EQ(client.reply.body.type, HCP_REFUSE);
  EXPECT_EQ(client.reply.body.hcp_body_u.refuse.code, HCP_REFUSE_NO_CONTROLLER);
}

TEST_F(SessionTest, ASecondClientIsBusyUntilTheFirstFallsSilent) {
  client.hello();
  Client other{&session};
  other.from = Endpoint::resolve("127.0.0.1", 40001);
  other.now = client.now + 30ms;
  other.hello();
  ASSERT_EQ(other.reply.body.type, HCP_REFUSE);
  EXPECT_EQ(other.reply.body.hcp_body_u.refuse.code, HCP_REFUSE_BUSY);
  EXPECT_EQ(other.reply.body.hcp_body_u.refuse.retry_after_ms, 70U);
  EXPECT_EQ(session.counters().refused_busy.load(), 1U);
  EXPECT_TRUE(session.check_watchdog(client.now + 101ms));
  other.now = client.now + 102ms;
  other.hello();
  EXPECT_EQ(other.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(controller.vpr_now().session_id, 2U);
}

TEST_F(SessionTest, ALostWelcomeIsRepeatedToTheSameClient) {
  client.hello();
  const std::uint64_t token = client.token;
  client.hello();
  ASSERT_EQ(client.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(client.reply.header.token, token);
  EXPECT_EQ(session.counters().sessions_opened.load(), 1U);
}

TEST_F(SessionTest, AnotherMajorVersionIsRefusedWithBothVersions) {
  client.hello(protocol::make_version(2, 1));
  ASSERT_EQ(client.reply.body.type, HCP_REFUSE);
  EXPECT_EQ(client.reply.body.hcp_body_u.refuse.code, HCP_REFUSE_VERSION);
  EXPECT_EQ(client.reply.body.hcp_body_u.refuse.peer_version, protocol::make_version(2, 1));
  EXPECT_EQ(std::string(protocol::text_of(client.reply.body.hcp_body_u.refuse.reason)),
            "protocol version mismatch: client 2.1 (oldest 2.1), controller 1.4");
  EXPECT_EQ(session.counters().refused_version.load(), 1U);
}

TEST_F(SessionTest, ANewerClientThatStillSpeaksOursIsAcceptedWithTheCommonFeatures) {
  client.hello(protocol::make_version(2, 0), 0xFF, protocol::make_version(1, 0));
  ASSERT_EQ(client.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(client.reply.header.protocol, protocol::kVersion);
  EXPECT_EQ(client.reply.body.hcp_body_u.welcome.features, protocol::kAllFeatures);
  Client older{&session};
  older.from = Endpoint::resolve("127.0.0.1", 40002);
  FrameBuffer notice{};
  Endpoint to;
  ASSERT_GT(session.close(TimePoint{}, "test", notice, to), 0U);
  older.hello(protocol::make_version(1, 0), HCP_FEATURE_JOINT_STATE);
  EXPECT_EQ(older.reply.body.hcp_body_u.welcome.features, HCP_FEATURE_JOINT_STATE);
}

TEST_F(SessionTest, ControlFramesReachVprAndKeepalivesOnlyFeedTheWatchdog) {
  client.hello();
  client.send_object(0.25F);
  shm::VprPayload v = controller.vpr_now();
  EXPECT_DOUBLE_EQ(v.object_pose[0], 0.25);
  EXPECT_EQ(v.client_sequence, 1U);
  hcp_frame w = protocol::make_frame(HCP_CONTROL_WRENCH, client.token, ++client.control_seq, 5);
  w.body.hcp_body_u.wrench.wrench[2] = -3.0F;
  client.feed(client.bytes(w));
  v = controller.vpr_now();
  EXPECT_DOUBLE_EQ(v.impedance_wrench[2], -3.0);
  EXPECT_EQ(v.client_time_ns, 5);
  const std::uint64_t publishes = controller.vpr_publishes();
  client.now += 90ms;
  client.feed(client.bytes(
      protocol::make_frame(HCP_KEEPALIVE, client.token, ++client.control_seq, to_ns(client.now))));
  EXPECT_EQ(controller.vpr_publishes(), publishes);  // the core keeps judging data freshness
  EXPECT_FALSE(session.check_watchdog(client.now + 90ms));
  EXPECT_EQ(session.counters().control_accepted.load(), 2U);
}

TEST_F(SessionTest, BadInputsAreDroppedCountedAndLeaveTheSessionUnharmed) {
  client.hello();
  client.send_object(0.1F);
  struct Case {
    std::string name;
    std::vector<std::uint8_t> bytes;
    LinkDrop reason;
  };
  const auto good = client.bytes(client.object(0.2F));  // sequence 2, never delivered
  std::vector<Case> cases;
  cases.push_back({"empty", {}, LinkDrop::kSize});
  cases.push_back({"truncated", {good.begin(), good.begin() + 20}, LinkDrop::kSize});
  cases.push_back({"odd length", {good.begin(), good.end() - 1}, LinkDrop::kSize});
  auto crc = good;
  crc[40] ^= 1;
  cases.push_back({"bad crc", crc, LinkDrop::kCrc});
  auto magic = good;
  magic[1] = 'X';
  cases.push_back({"bad magic", magic, LinkDrop::kMagic});
  hcp_frame v2 = client.object(0.2F);
  v2.header.protocol = protocol::make_version(2, 0);
  cases.push_back({"wrong version", client.bytes(v2), LinkDrop::kVersion});
  hcp_frame forged = client.object(0.2F);
  forged.header.token ^= 0x5A5A;
  cases.push_back({"wrong token", client.bytes(forged), LinkDrop::kToken});
  for (const float bad : {std::nanf(""), std::numeric_limits<float>::infinity()}) {
    hcp_frame f = client.object(0.2F);
    f.body.hcp_body_u.object.twist[1] = bad;
    cases.push_back({"non-finite", client.bytes(f), LinkDrop::kRange});
  }
  hcp_frame replay = client.object(0.2F);
  replay.header.sequence = 1;  // already accepted
  cases.push_back({"replayed", client.bytes(replay), LinkDrop::kSequence});
  cases.push_back({"unexpected type",
                   client.bytes(protocol::make_frame(HCP_ANSWER, client.token, 9, 0)),
                   LinkDrop::kUnexpected});

  const std::uint64_t publishes = controller.vpr_publishes();
  for (const Case& c : cases) {
    const std::uint64_t before = dropped(c.reason);
    client.feed(c.bytes);
    EXPECT_FALSE(client.replied) << c.name;
    EXPECT_EQ(dropped(c.reason), before + 1) << c.name;
  }
  Client stranger{&session};  // the right token from another address
  stranger.from = Endpoint::resolve("127.0.0.1", 40009);
  const std::uint64_t token_drops = dropped(LinkDrop::kToken);
  stranger.feed(good);
  EXPECT_EQ(dropped(LinkDrop::kToken), token_drops + 1);
  session.on_oversized();
  EXPECT_EQ(controller.vpr_publishes(), publishes);  // nothing bad reached the controller

  client.now += 50ms;
  client.control_seq = 5;
  client.send_object(0.3F);  // the session still works
  EXPECT_FLOAT_EQ(static_cast<float>(controller.vpr_now().object_pose[0]), 0.3F);
  client.control_seq = 4;
  client.send_object(0.9F);  // reordered: older than the last accepted
  EXPECT_FLOAT_EQ(static_cast<float>(controller.vpr_now().object_pose[0]), 0.3F);
  EXPECT_EQ(dropped(LinkDrop::kSequence), 2U);
}

TEST_F(SessionTest, TheWatchdogClosesASilentSessionAndTheCoreSeesNoSession) {
  client.hello();
  client.send_object(0.1F);
  EXPECT_FALSE(session.check_watchdog(client.now + 100ms));
  EXPECT_TRUE(session.check_watchdog(client.now + 101ms));
  EXPECT_EQ(controller.vpr_now().session_id, 0U);
  EXPECT_EQ(session.counters().watchdog_expiries.load(), 1U);
  client.send_object(0.2F);  // the old token is worthless now
  EXPECT_EQ(dropped(LinkDrop::kToken), 1U);
}

TEST_F(SessionTest, ByeIsAcknowledgedAndEndsTheSession) {
  client.hello();
  hcp_frame bye =
      protocol::make_frame(HCP_BYE, client.token, ++client.param_seq, to_ns(client.now));
  client.feed(client.bytes(bye));
  ASSERT_EQ(client.reply.body.type, HCP_ACK);
  EXPECT_EQ(client.reply.header.token, client.token);
  EXPECT_EQ(controller.vpr_now().session_id, 0U);
  EXPECT_EQ(session.counters().sessions_closed.load(), 1U);
}

TEST_F(SessionTest, ALocalCouplingSessionGetsAnswersCoupledAndSendsTimedWrenchesAndContacts) {
  client.hello();  // every feature: local coupling (1.3)
  EXPECT_NE(controller.vpr_now().flags & shm::vpr_flags::kLocalCoupling, 0U);
  FrameBuffer out{};
  Endpoint to;
  shm::VpPayload vp;
  vp.cycle = 700;
  vp.contact_normal = {-1.0, 0.0, 0.0};
  vp.normal_gains = {900.0, 10.0};
  vp.limits = {35.0, 3.0};
  vp.max_contact_stiffness = 2000.0;
  vp.contacts = 1;
  const std::size_t n = session.answer(vp, client.now, out, to);
  hcp_frame a;
  ASSERT_EQ(protocol::decode({out.data(), n}, a), protocol::DecodeStatus::kOk);
  ASSERT_EQ(a.body.type, HCP_ANSWER_COUPLED);
  const hcp_local_coupling& l = a.body.hcp_body_u.answer_coupled.local;
  EXPECT_EQ(l.contact_normal[0], -1.0);
  EXPECT_EQ(l.normal_gains[0], 900.0);
  EXPECT_EQ(l.limits[1], 3.0);
  EXPECT_EQ(l.max_contact_stiffness, 2000.0);
  EXPECT_EQ(l.contacts, 1U);

  // An IMPEDANCE wrench with its echo and energy: a new sample, dated like an object state.
  client.now += 4ms;
  hcp_frame w = protocol::make_frame(HCP_CONTROL_WRENCH_TIMED, client.token, ++client.control_seq,
                                     to_ns(client.now));
  w.body.hcp_body_u.wrench_timed.wrench[0] = -8.0F;
  w.body.hcp_body_u.wrench_timed.answer_echo = protocol::pack_answer_echo(700, to_ns(1ms), true);
  w.body.hcp_body_u.wrench_timed.energy_in = 1000U;
  client.feed(client.bytes(w));
  const shm::VprPayload after_wrench = controller.vpr_now();
  EXPECT_EQ(after_wrench.impedance_wrench[0], -8.0);
  EXPECT_EQ(after_wrench.echo_cycle, 700U);
  EXPECT_EQ(after_wrench.sample_time_ns, to_ns(client.now - 1500us));

  // A contact: its slot and the count, the object's pose with it; the sample stays the same.
  hcp_frame c = protocol::make_frame(HCP_CONTROL_CONTACT, client.token, ++client.control_seq,
                                     to_ns(client.now));
  c.body.hcp_body_u.contact.slots = protocol::pack_contact_slots(1, 2);
  hcp_contact& k = c.body.hcp_body_u.contact.contact;
  k.point[0] = 0.6F;
  k.normal[0] = -1.0F;
  k.distance = -0.001F;
  k.stiffness = 1500.0F;
  k.friction[0] = 0.3F;
  k.friction[1] = 0.2F;
  client.feed(client.bytes(c));
  const shm::VprPayload after_contact = controller.vpr_now();
  EXPECT_EQ(after_contact.client_sequence, after_wrench.client_sequence)
      << "a contact is no new sample";
  EXPECT_EQ(after_contact.contact_count, 2U);
  EXPECT_EQ(after_contact.contact_frames, after_wrench.contact_frames + 1);
  EXPECT_EQ(after_contact.contacts[1].stiffness, 1500.0);
  EXPECT_NEAR(after_contact.contacts[1].distance, -0.001, 1e-9);
  EXPECT_EQ(after_contact.contacts[1].received_time_ns, to_ns(client.now));
  EXPECT_EQ(after_contact.contacts[0].stiffness, 0.0) << "slot 0 not sent yet";
  // Count 0 clears every slot.
  hcp_frame clear = protocol::make_frame(HCP_CONTROL_CONTACT, client.token, ++client.control_seq,
                                         to_ns(client.now));
  clear.body.hcp_body_u.contact.slots = protocol::pack_contact_slots(0, 0);
  client.feed(client.bytes(clear));
  EXPECT_EQ(controller.vpr_now().contact_count, 0U);
  EXPECT_EQ(controller.vpr_now().contacts[1].stiffness, 0.0);
}

TEST_F(SessionTest, TimedWrenchesAndContactsFromASessionWithoutLocalCouplingAreDropped) {
  client.hello(protocol::kVersion, HCP_FEATURE_TIMING);
  hcp_frame w = protocol::make_frame(HCP_CONTROL_WRENCH_TIMED, client.token, ++client.control_seq,
                                     to_ns(client.now));
  client.feed(client.bytes(w));
  hcp_frame c = protocol::make_frame(HCP_CONTROL_CONTACT, client.token, ++client.control_seq,
                                     to_ns(client.now));
  client.feed(client.bytes(c));
  EXPECT_EQ(session.counters().dropped_for(LinkDrop::kToken), 2U);
  EXPECT_EQ(controller.vpr_now().flags & shm::vpr_flags::kLocalCoupling, 0U);
}

TEST_F(SessionTest, JointFramesAndModesFromASessionWithoutJointControlAreRefused) {
  client.hello(protocol::kVersion, HCP_FEATURE_TIMING);
  hcp_frame f = client.param(HCP_P_COMMAND_TYPE);
  f.body.hcp_body_u.param.hcp_param_u.command_type = HCP_COMMAND_ARTICULAR_IMPEDANCE;
  client.feed(client.bytes(f));
  EXPECT_EQ(client.reply.body.hcp_body_u.ack.status, HCP_ACK_REJECTED);
  EXPECT_NE(std::string(protocol::text_of(client.reply.body.hcp_body_u.ack.reason)).find("1.4"),
            std::string::npos);
  client.feed(client.bytes(
      protocol::make_frame(HCP_CONTROL_JOINT_TORQUE, client.token, ++client.control_seq, 1)));
  EXPECT_EQ(dropped(LinkDrop::kToken), 1U);
  EXPECT_EQ(controller.vpr_now().command_type, 0U);
}

TEST_F(SessionTest, LocalCouplingWithoutTimingIsNotGranted) {
  client.hello(protocol::kVersion, HCP_FEATURE_LOCAL_COUPLING);
  ASSERT_EQ(client.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(client.reply.body.hcp_body_u.welcome.features, 0U);
}

TEST_F(SessionTest, TimedObjectsFromASessionWithoutTimingAreDropped) {
  client.hello(protocol::kVersion, HCP_FEATURE_LINK_STATS);
  client.feed(client.bytes(client.timed_object(1, 0ns, 0)));
  EXPECT_EQ(session.counters().dropped_for(LinkDrop::kToken), 1U);
  EXPECT_EQ(session.counters().control_accepted.load(), 0U);
}

TEST_F(SessionTest, ClosingTellsTheClientWhyWithItsToken) {
  FrameBuffer notice{};
  Endpoint to;
  EXPECT_EQ(session.close(TimePoint{}, "the controller stopped", notice, to), 0U);  // no session
  client.hello();
  const std::size_t n = session.close(client.now, "the controller stopped", notice, to);
  ASSERT_GT(n, 0U);
  EXPECT_EQ(to, client.from);
  hcp_frame f;
  ASSERT_EQ(protocol::decode({notice.data(), n}, f), protocol::DecodeStatus::kOk);
  EXPECT_EQ(f.body.type, HCP_REFUSE);
  EXPECT_EQ(f.header.token, client.token);
  EXPECT_EQ(f.body.hcp_body_u.refuse.code, HCP_REFUSE_NO_CONTROLLER);
  EXPECT_EQ(protocol::text_of(f.body.hcp_body_u.refuse.reason), "the controller stopped");
  EXPECT_EQ(controller.vpr_now().session_id, 0U);
}

TEST(SessionSecurity, ASourceOffTheAllowListIsDroppedUndecodedAndCounted) {
  test::InMemoryController controller;
  Session session({100, kMaxWatchdogMs, ClientAllowList({Ipv4Network::parse("127.0.0.2")}), {}},
                  [] { return std::uint64_t{7}; });
  session.set_controller(&controller.ports, TimePoint{});
  Client stranger{&session};  // 127.0.0.1
  stranger.hello();
  EXPECT_FALSE(stranger.replied);
  stranger.feed({1, 2, 3});  // not even a frame: still "not allowed", not "size"
  EXPECT_EQ(session.counters().dropped_for(LinkDrop::kNotAllowed), 2U);
  Client friendly{&session, Endpoint::resolve("127.0.0.2", 40000)};
  friendly.hello();
  ASSERT_TRUE(friendly.replied);
  EXPECT_EQ(friendly.reply.body.type, HCP_WELCOME);
}

TEST(SessionSecurity, AHandshakeFloodIsAnsweredOnlyAtItsRate) {
  test::InMemoryController controller;
  Session session({100, kMaxWatchdogMs, {}, {10.0, 4.0}}, [] { return std::uint64_t{7}; });
  session.set_controller(&controller.ports, TimePoint{});
  Client flood{&session};
  int answered = 0;
  for (int i = 0; i < 100; ++i) {
    flood.hello();
    answered += flood.replied ? 1 : 0;
  }
  EXPECT_EQ(answered, 2) << "kFirstHellos for a new source, then nothing within the same instant";
  EXPECT_EQ(session.counters().dropped_for(LinkDrop::kRateLimited), 98U);
}

TEST(SessionSecurity, AClientCannotHoldAnIdleSessionBeyondTheDefaultNorAskForMoreThanTheCap) {
  // H3: one HELLO asking for a 60 s watchdog held the session for 60 s.
  test::InMemoryController controller;
  Session session({100, 500, {}, {}}, [] { return std::uint64_t{7}; });
  session.set_controller(&controller.ports, TimePoint{});
  Client greedy{&session};
  greedy.asked_watchdog_ms = 60'000;
  greedy.hello();
  ASSERT_EQ(greedy.reply.body.type, HCP_WELCOME);
  EXPECT_EQ(greedy.reply.body.hcp_body_u.welcome.watchdog_ms, 500U) << "capped";
  EXPECT_FALSE(session.check_watchdog(greedy.now + 100ms));
  EXPECT_TRUE(session.check_watchdog(greedy.now + 101ms)) << "idle: the default holds";
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
