// The client's protocol state machine (client_session.cpp) without a socket: frames in with
// their arrival time, frames out.
#include "client_session.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hapticctrl/protocol/timing.hpp"
#include "support/client_session_frames.hpp"

namespace hapticctrl::client {
namespace {

using namespace std::chrono_literals;

using test::answer;
using test::at;
using test::kToken;
using test::open_session;
using test::options;
using test::welcome;

hcp_frame refusal(hcp_refuse_code code, std::uint32_t retry_ms, const char* reason) {
  hcp_frame r = protocol::make_frame(HCP_REFUSE, 0, 1, 0);
  r.header.protocol = protocol::make_version(2, 0);
  r.body.hcp_body_u.refuse.code = code;
  r.body.hcp_body_u.refuse.retry_after_ms = retry_ms;
  protocol::set_text(r.body.hcp_body_u.refuse.reason, reason);
  return r;
}

hcp_frame ack(std::uint32_t sequence, hcp_ack_status status, const char* reason = "") {
  hcp_frame f = protocol::make_frame(HCP_ACK, kToken, 9, 0);
  f.body.hcp_body_u.ack.acked_sequence = sequence;
  f.body.hcp_body_u.ack.status = status;
  protocol::set_text(f.body.hcp_body_u.ack.reason, reason);
  return f;
}

hcp_param watchdog_param(std::uint32_t ms) {
  hcp_param p{};
  p.id = HCP_P_WATCHDOG;
  p.hcp_param_u.watchdog_ms = ms;
  return p;
}

TEST(ClientSession, HelloIsDueAtOnceThenEveryTwoRetransmitPeriods) {
  ClientSession s(options(), "127.0.0.1:5125");
  const auto first = s.hello_due(at(0ms));
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->body.type, HCP_HELLO);
  EXPECT_EQ(first->header.protocol, protocol::kVersion);
  EXPECT_EQ(first->body.hcp_body_u.hello.features, protocol::kAllFeatures);
  EXPECT_FALSE(s.hello_due(at(39ms)).has_value());
  const auto second = s.hello_due(at(40ms));
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->header.sequence, first->header.sequence + 1);
}

TEST(ClientSession, AWelcomeOpensTheSessionOnTheControllersTerms) {
  ClientSession s(options(), "127.0.0.1:5125");
  (void)s.hello_due(at(0ms));
  const HandshakeStep step = s.on_handshake_frame(welcome(), at(5ms));
  EXPECT_TRUE(step.welcomed);
  EXPECT_FALSE(step.reply.has_value());
  EXPECT_FALSE(step.fail.has_value());
  EXPECT_TRUE(s.is_open());
  EXPECT_EQ(s.features(), protocol::kAllFeatures);
  EXPECT_EQ(s.watchdog_ms(), 400U);
  EXPECT_EQ(s.controller_period(), 1ms);
  EXPECT_EQ(s.controller_version(), protocol::kVersion);
  EXPECT_FALSE(s.hello_due(at(100ms)).has_value()) << "no HELLO once open";
}

TEST(ClientSession, ABusyControllerIsAskedAgainAfterItsRetryTimeAndTheTimeoutSaysWhy) {
  ClientSession s(options(), "127.0.0.1:5125");
  (void)s.hello_due(at(0ms));
  const HandshakeStep step =
      s.on_handshake_frame(refusal(HCP_REFUSE_BUSY, 100, "another client holds the arm"), at(1ms));
  EXPECT_FALSE(step.welcomed);
  EXPECT_FALSE(step.fail.has_value()) << "busy is worth asking again";
  EXPECT_FALSE(s.hello_due(at(100ms)).has_value());
  EXPECT_TRUE(s.hello_due(at(101ms)).has_value());
  const ClientError e = s.handshake_timeout();
  EXPECT_EQ(e.code(), ErrorCode::kBusy);
  EXPECT_THAT(e.what(), testing::HasSubstr("another client holds the arm"));
}

TEST(ClientSession, AVersionRefusalFailsAtOnceNamingBothVersions) {
  ClientSession s(options(), "127.0.0.1:5125");
  (void)s.hello_due(at(0ms));
  const HandshakeStep step =
      s.on_handshake_frame(refusal(HCP_REFUSE_VERSION, 0, "too old"), at(1ms));
  ASSERT_TRUE(step.fail.has_value());
  EXPECT_EQ(step.fail->code(), ErrorCode::kVersion);
  const std::string what = step.fail->what();
  EXPECT_NE(what.find("too old"), std::string::npos) << what;
  EXPECT_NE(what.find("the controller 2.0"), std::string::npos) << what;
}

TEST(ClientSession, AWelcomeOfAnotherMajorVersionIsRefusedBack) {
  ClientSession s(options(), "127.0.0.1:5125");
  (void)s.hello_due(at(0ms));
  const HandshakeStep step = s.on_handshake_frame(welcome(protocol::make_version(9, 0)), at(1ms));
  EXPECT_FALSE(step.welcomed);
  ASSERT_TRUE(step.reply.has_value()) << "the controller is told why";
  EXPECT_EQ(step.reply->body.type, HCP_REFUSE);
  EXPECT_EQ(step.reply->body.hcp_body_u.refuse.code, HCP_REFUSE_VERSION);
  ASSERT_TRUE(step.fail.has_value());
  EXPECT_EQ(step.fail->code(), ErrorCode::kVersion);
  EXPECT_FALSE(s.is_open());
}

TEST(ClientSession, SilenceDuringTheHandshakeAsksWhetherTheBridgeRuns) {
  const ClientSession s(options(), "lab-pc:5125");
  const ClientError e = s.handshake_timeout();
  EXPECT_EQ(e.code(), ErrorCode::kTimeout);
  EXPECT_THAT(e.what(), testing::HasSubstr("lab-pc:5125 within 500 ms: is hapticctrl-udp running"))
      << e.what();
}

TEST(ClientSession, AnswersBecomeTheLatestStateAndOlderOnesAreIgnored) {
  ClientSession s = open_session();
  EXPECT_EQ(s.on_frame(answer(1, 100), at(2ms)), Arrival::kAnswer);
  EXPECT_EQ(s.on_frame(answer(2, 101), at(3ms)), Arrival::kAnswer);
  EXPECT_EQ(s.on_frame(answer(1, 100), at(4ms)), Arrival::kIgnored) << "late: not newer";
  const StateSnapshot& latest = s.latest();
  EXPECT_TRUE(latest.valid);
  EXPECT_EQ(latest.cycle, 101U);
  EXPECT_EQ(latest.received_ns, to_ns(3ms));
  EXPECT_DOUBLE_EQ(latest.handle_pose[6], 1.0);
  EXPECT_EQ(s.statistics().answers_late, 1U);
}

TEST(ClientSession, AFrameOfAnotherSessionIsCountedAndChangesNothing) {
  ClientSession s = open_session();
  hcp_frame stranger = answer(1, 100);
  stranger.header.token = kToken + 1;
  EXPECT_EQ(s.on_frame(stranger, at(1ms)), Arrival::kInvalid);
  s.on_invalid();  // and a datagram that did not decode
  EXPECT_FALSE(s.latest().valid);
  EXPECT_EQ(s.statistics().frames_invalid, 2U);
}

TEST(ClientSession, TheBridgesRefusalClosesTheSessionAndEveryCallSaysWhy) {
  ClientSession s = open_session();
  hcp_frame end = refusal(HCP_REFUSE_NO_CONTROLLER, 0, "the controller stopped");
  end.header.token = kToken;
  EXPECT_EQ(s.on_frame(end, at(1ms)), Arrival::kClosed);
  EXPECT_FALSE(s.is_open());
  try {
    (void)s.param_frame(watchdog_param(100), "set_watchdog");
    FAIL() << "a closed session sent a parameter";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kClosed);
    EXPECT_STREQ(e.what(), "set_watchdog: the session is closed (the controller stopped)");
  }
  EXPECT_FALSE(s.object_frame({0, 0, 0, 0, 0, 0, 1}, {}, at(2ms)).has_value());
  EXPECT_FALSE(s.wrench_frame({}, at(2ms)).has_value());
  EXPECT_FALSE(s.keepalive_due(at(1000ms)).has_value());
}

TEST(ClientSession, ABridgeSilentForTheAnswerTimeoutEndsTheSession) {
  ClientSession s = open_session();
  EXPECT_EQ(s.on_frame(answer(1, 1), at(100ms)), Arrival::kAnswer);
  EXPECT_FALSE(s.close_if_silent(at(400ms))) << "300 ms since the last frame: not yet";
  EXPECT_TRUE(s.close_if_silent(at(401ms)));
  EXPECT_EQ(s.closed_reason(), "no answer from the bridge for 300 ms");
  EXPECT_FALSE(s.close_if_silent(at(900ms))) << "closed once";
}

TEST(ClientSession, AKeepaliveIsDueAfterAQuarterOfTheWatchdogWithoutSending) {
  ClientSession s = open_session();  // watchdog 400 ms
  EXPECT_FALSE(s.keepalive_due(at(100ms)).has_value());
  const auto keepalive = s.keepalive_due(at(101ms));
  ASSERT_TRUE(keepalive.has_value());
  EXPECT_EQ(keepalive->body.type, HCP_KEEPALIVE);
  EXPECT_EQ(keepalive->header.token, kToken);
  s.on_sent(at(101ms));
  EXPECT_FALSE(s.keepalive_due(at(150ms)).has_value()) << "the quiet time counts from a send";
}

TEST(ClientSession, AnAppliedWatchdogSetsTheKeepaliveInterval) {
  ClientSession s = open_session();
  const hcp_frame f = s.param_frame(watchdog_param(100), "set_watchdog");
  EXPECT_EQ(f.body.type, HCP_PARAM);
  EXPECT_EQ(f.header.token, kToken);
  EXPECT_EQ(s.watchdog_ms(), 400U) << "not before the controller acknowledged it";
  s.on_param_applied(f.body.hcp_body_u.param);
  EXPECT_EQ(s.watchdog_ms(), 100U);
  EXPECT_TRUE(s.keepalive_due(at(26ms)).has_value());
}

TEST(ClientSession, AcknowledgementsAreMatchedToTheirFrameAndTakenOnce) {
  ClientSession s = open_session();
  const hcp_frame first = s.param_frame(watchdog_param(100), "set_watchdog");
  const hcp_frame second = s.param_frame(watchdog_param(200), "set_watchdog");
  EXPECT_EQ(second.header.sequence, first.header.sequence + 1);
  EXPECT_EQ(s.on_frame(ack(second.header.sequence, HCP_ACK_REJECTED, "out of range"), at(1ms)),
            Arrival::kAck);
  EXPECT_FALSE(s.take_ack(first.header.sequence).has_value()) << "not this frame's";
  const auto outcome = s.take_ack(second.header.sequence);
  ASSERT_TRUE(outcome.has_value());
  EXPECT_EQ(outcome->status, HCP_ACK_REJECTED);
  EXPECT_EQ(outcome->reason, "out of range");
  EXPECT_FALSE(s.take_ack(second.header.sequence).has_value()) << "taken once";
}

TEST(ClientSession, AValueTheProtocolRefusesNeverLeaves) {
  ClientSession s = open_session();
  hcp_param nan{};
  nan.id = HCP_P_TIME_STEP;
  nan.hcp_param_u.time_step = std::nan("");
  try {
    (void)s.param_frame(nan, "set_time_step");
    FAIL() << "a NaN time step was framed";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(std::string(e.what()).rfind("set_time_step: ", 0), 0U) << e.what();
  }
}

}  // namespace
}  // namespace hapticctrl::client
