// Tests of handshake.hpp alone: what a HELLO gets, what a session is granted, which frames a
// session may send.
#include "hapticctrl/udp_bridge/handshake.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using namespace std::chrono_literals;

using Kind = HelloVerdict::Kind;
using testing::HasSubstr;

hcp_frame hello(std::uint32_t version = protocol::kVersion,
                std::uint32_t oldest = protocol::kVersion) {
  hcp_frame f = protocol::make_frame(HCP_HELLO, 0, 1, 0);
  f.header.protocol = version;
  f.body.hcp_body_u.hello.min_version = oldest;
  return f;
}

const protocol::Endpoint kFirst = protocol::Endpoint::resolve("127.0.0.1", 40000);
const protocol::Endpoint kSecond = protocol::Endpoint::resolve("127.0.0.1", 40001);

TEST(Handshake, AHelloOpensASessionOnlyWithAControllerAndNoOtherSession) {
  const SessionView none;
  EXPECT_EQ(judge_hello(hello(), kFirst, {none, true}).kind, Kind::kOpen);
  const HelloVerdict alone = judge_hello(hello(), kFirst, {none, false});
  EXPECT_EQ(alone.kind, Kind::kRefuse);
  EXPECT_EQ(alone.code, HCP_REFUSE_NO_CONTROLLER);
  EXPECT_THAT(alone.reason, HasSubstr("hapticctrl-core is not running"));
}

TEST(Handshake, ASecondClientRetriesWhenTheSessionsWatchdogWouldExpire) {
  const SessionView busy{42, kFirst, 0, 0};
  const HelloVerdict v = judge_hello(hello(), kSecond, {busy, true, 700ms, 3000});
  EXPECT_EQ(v.kind, Kind::kRefuse);
  EXPECT_EQ(v.code, HCP_REFUSE_BUSY);
  EXPECT_EQ(v.retry_ms, 2300U);
  EXPECT_EQ(judge_hello(hello(), kSecond, {busy, true, 5s, 3000}).retry_ms, 1U) << "at least 1 ms";
  EXPECT_EQ(judge_hello(hello(), kFirst, {busy, true}).kind, Kind::kWelcomeAgain)
      << "the session's own client: its WELCOME was lost";
}

TEST(Handshake, AnotherMajorVersionIsRefusedSayingBoth) {
  const SessionView none;
  const std::uint32_t next_major = protocol::kVersion + (1U << 16U);
  const HelloVerdict v = judge_hello(hello(next_major, next_major), kFirst, {none, true});
  EXPECT_EQ(v.kind, Kind::kRefuse);
  EXPECT_EQ(v.code, HCP_REFUSE_VERSION);
  const std::string minor = std::to_string(protocol::version_minor(protocol::kVersion));
  EXPECT_THAT(v.reason, HasSubstr("protocol version mismatch: client 2." + minor + " (oldest 2." +
                                  minor + "), controller 1." + minor));
  EXPECT_EQ(judge_hello(hello(next_major, protocol::kVersion), kFirst, {none, true}).kind,
            Kind::kOpen)
      << "a newer client that still speaks ours";
}

TEST(Handshake, ASessionIsGrantedWhatItAsksWithinTheBridgesLimits) {
  EXPECT_EQ(granted_features(HCP_FEATURE_LOCAL_COUPLING), 0U) << "local coupling needs timing";
  EXPECT_EQ(granted_features(HCP_FEATURE_TIMING | HCP_FEATURE_LOCAL_COUPLING | 0x80000000U),
            HCP_FEATURE_TIMING | HCP_FEATURE_LOCAL_COUPLING)
      << "an unknown feature is not granted";
  EXPECT_EQ(granted_watchdog_ms(0, 3000, 10000), 3000U);
  EXPECT_EQ(granted_watchdog_ms(500, 3000, 10000), 500U);
  EXPECT_EQ(granted_watchdog_ms(60000, 3000, 10000), 10000U);
}

TEST(Handshake, OnlyTheSessionsClientMaySendAndOnlyWhatItNegotiated) {
  const SessionView session{42, kFirst, HCP_FEATURE_TIMING, 0};
  hcp_frame f = protocol::make_frame(HCP_CONTROL_OBJECT_TIMED, 42, 1, 0);
  EXPECT_TRUE(from_session(f, kFirst, session));
  EXPECT_FALSE(from_session(f, kSecond, session)) << "another address";
  f.header.token = 43;
  EXPECT_FALSE(from_session(f, kFirst, session)) << "another token";
  EXPECT_FALSE(from_session(f, kFirst, SessionView{})) << "no session";
  EXPECT_TRUE(negotiated(HCP_CONTROL_OBJECT_TIMED, HCP_FEATURE_TIMING));
  EXPECT_FALSE(negotiated(HCP_CONTROL_OBJECT_TIMED, 0));
  EXPECT_FALSE(negotiated(HCP_CONTROL_CONTACT, HCP_FEATURE_TIMING));
  EXPECT_TRUE(negotiated(HCP_CONTROL_CONTACT, HCP_FEATURE_LOCAL_COUPLING));
  EXPECT_FALSE(negotiated(HCP_CONTROL_JOINT_TORQUE, HCP_FEATURE_TIMING));
  EXPECT_TRUE(negotiated(HCP_CONTROL_OBJECT, 0));
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
