// The client library against the real hapticctrl-core and hapticctrl-udp on loopback.
#include "hapticctrl/client/connection.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "support/controller_stack.hpp"
#include "support/reference_parameters.hpp"

namespace hapticctrl::client {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

Address address_of(const ControllerStack& stack) {
  return {"127.0.0.1", stack.port()};
}

/// Streams `send` once per answer for `duration`; returns the last snapshot.
template <typename Send>
StateSnapshot stream(Connection& c, std::chrono::milliseconds duration, Send send) {
  StateSnapshot s = c.snapshot();
  const auto end = std::chrono::steady_clock::now() + duration;
  while (std::chrono::steady_clock::now() < end) {
    if (c.wait_for_answer(s.cycle, 100ms, s)) {
      send(s);
    }
  }
  return s;
}

TEST(Connection, HandshakeNegotiatesAndTheAnswerStreamFlows) {
  ControllerStack stack("handshake");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  EXPECT_EQ(c.features(), 31U)
      << "joint state, link statistics, timing, local coupling, joint control";
  EXPECT_EQ(c.controller_period_ns(), stack.period_us() * 1000);
  EXPECT_EQ(c.watchdog_ms(), 3000U);
  EXPECT_EQ(c.controller_version(), 0x00010004U);
  StateSnapshot s;
  ASSERT_TRUE(c.wait_for_answer(0, 2s, s));
  EXPECT_TRUE(s.valid);
  EXPECT_EQ(s.core_state, 1U);
  EXPECT_FALSE(s.powered());
  EXPECT_NEAR(std::hypot(std::hypot(s.handle_pose[3], s.handle_pose[4]),
                         std::hypot(s.handle_pose[5], s.handle_pose[6])),
              1.0, 1e-6);
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().sessions_opened == 1U; }, 1s));
}

TEST(Connection, ImpedanceWrenchMovesTheHandle) {
  ControllerStack stack("impedance");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  c.set_command_type(CommandType::kImpedance);
  c.set_power(true);
  ASSERT_TRUE(ControllerStack::eventually([&] { return c.snapshot().powered(); }));
  const double x0 = c.snapshot().handle_pose[0];
  const StateSnapshot s = stream(c, 600ms, [&](const StateSnapshot&) {
    c.send_wrench({4.0, 0, 0, 0, 0, 0});  // 4 N along +x of the client frame
  });
  EXPECT_GT(s.handle_pose[0] - x0, 0.005) << "the handle follows the rendered force";
}

TEST(Connection, VirtmechCouplesTheObjectAndTheHandleBothWays) {
  ControllerStack stack("virtmech");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  c.set_command_type(CommandType::kVirtmech);
  c.attach_object(0.5, {0.001, 0.001, 0.001});
  c.set_power(true);
  ASSERT_TRUE(ControllerStack::eventually([&] { return c.snapshot().powered(); }));
  Pose7 object = c.snapshot().handle_pose;
  const double x0 = object[0];
  object[0] += 0.03;  // the object held 3 cm away along +x
  double min_force_on_object = 0.0;
  const StateSnapshot s = stream(c, 600ms, [&](const StateSnapshot& now) {
    min_force_on_object = std::min(min_force_on_object, now.coupling_wrench[0]);
    c.send_object_state(object, {});
  });
  EXPECT_LT(min_force_on_object, -0.5) << "the object is pulled back towards the handle";
  EXPECT_GT(s.handle_pose[0] - x0, 0.005) << "the handle is pulled towards the object";
  const LinkStatistics st = c.statistics();
  const auto cycles = static_cast<std::uint64_t>(600'000 / stack.period_us());
  EXPECT_GT(st.rtt_samples, cycles / 3);
  EXPECT_GT(st.control_received_by_controller, cycles / 3);
  EXPECT_GT(st.answers_received, cycles / 2);
}

TEST(Connection, CallbackLoopIsPacedByTheController) {
  ControllerStack stack("loop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  std::atomic<int> calls{0};
  std::atomic<std::uint64_t> last_cycle{0};
  c.start_loop([&](const StateSnapshot& s) {
    ++calls;
    last_cycle = s.cycle;
    c.send_wrench({});
  });
  std::this_thread::sleep_for(500ms);
  c.stop_loop();
  const int seen = calls.load();
  const int cycles = 500'000 / stack.period_us();  // one call per controller cycle
  EXPECT_GT(seen, cycles / 2);
  EXPECT_LT(seen, cycles * 3 / 2 + 5);
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(calls.load(), seen);
}

TEST(Connection, ASecondClientIsRefusedAsBusy) {
  ControllerStack stack("busy");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection first(address_of(stack));
  ConnectOptions quick;
  quick.connect_timeout = 300ms;
  try {
    Connection second(address_of(stack), quick);
    FAIL() << "a second client must be refused";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kBusy);
    EXPECT_THAT(e.what(), testing::HasSubstr("another client session is active")) << e.what();
  }
  EXPECT_TRUE(first.is_open());
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().refused_busy >= 1U; }, 1s));
}

TEST(Connection, VersionMismatchIsExplainedWithBothVersions) {
  ControllerStack stack("version");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  ConnectOptions newer;
  newer.advertised_version = 0x00020003;
  try {
    Connection c(address_of(stack), newer);
    FAIL() << "a client of another major version must be refused";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kVersion);
    const std::string what = e.what();
    EXPECT_NE(what.find("client 2.3"), std::string::npos) << what;
    EXPECT_NE(what.find("controller 1.4"), std::string::npos) << what;
  }
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().refused_version == 1U; }, 1s));
}

TEST(Connection, WatchdogFadesTheCouplingWhenTheClientDiesAndARestartedClientReconnects) {
  ControllerStack stack("watchdog");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  // The client process: couples an object 3 cm from the handle, then is killed mid-stream.
  test::SpawnedProcess client(HAPTICCTRL_STREAMING_CLIENT, {std::to_string(stack.port())});
  ASSERT_TRUE(ControllerStack::eventually(
      [&] { return client.out().find("streaming") != std::string::npos; }, 10s))
      << client.err();
  const auto coupled = [&] { return std::abs(stack.position().rendered_wrench[0]); };
  EXPECT_TRUE(ControllerStack::eventually([&] { return coupled() > 0.5; }, 2s))
      << "coupled through the engagement ramp";
  client.signal(SIGKILL);
  client.wait();
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().watchdog_expiries == 1; }, 8s))
      << "the bridge's 3 s watchdog";
  EXPECT_EQ(stack.vpr().session_id, 0U);
  EXPECT_TRUE(ControllerStack::eventually([&] { return coupled() < 1e-9; }, 1s))
      << "coupling faded out";

  Connection restarted(address_of(stack));  // the client comes back
  StateSnapshot s;
  EXPECT_TRUE(restarted.wait_for_answer(0, 1s, s));
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().sessions_opened == 2U; }, 1s));
}

TEST(Connection, CloseEndsTheSession) {
  ControllerStack stack("close");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  c.close();
  EXPECT_FALSE(c.is_open());
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().sessions_closed == 1U; }, 1s));
  EXPECT_FALSE(c.send_wrench({}));
  EXPECT_THROW(c.set_power(true), ClientError);
}

TEST(Connection, AStoppingControllerClosesTheSessionAndTheClientIsTold) {
  ControllerStack stack("corestop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  StateSnapshot s;
  ASSERT_TRUE(c.wait_for_answer(0, 2s, s));
  stack.core().signal(SIGTERM);
  EXPECT_TRUE(ControllerStack::eventually([&] { return !c.is_open(); }));
  EXPECT_NE(c.snapshot().core_state, 1U) << "the last answers carried the stop";
  try {
    c.set_power(true);
    FAIL() << "a closed session refuses calls";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kClosed);
    EXPECT_THAT(e.what(), testing::HasSubstr("the controller stopped")) << e.what();
  }
}

TEST(Connection, ABridgeWithAnAllowListIgnoresEveryOtherAddress) {
  ControllerStack stack("allowlist", ControllerStack::kDefaultPeriodUs,
                        {"--allow-client", "127.0.0.2"});
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  ConnectOptions quick;
  quick.connect_timeout = 300ms;
  try {
    Connection c(address_of(stack), quick);  // from 127.0.0.1
    FAIL() << "a client off the allow-list got a session";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kTimeout) << e.what();
  }
  EXPECT_TRUE(ControllerStack::eventually(
      [&] {
        return stack.link_stats().dropped[static_cast<std::size_t>(shm::LinkDrop::kNotAllowed)] > 0;
      },
      1s))
      << "its handshakes were counted as not allowed";
  EXPECT_EQ(stack.link_stats().sessions_opened, 0U);
}

TEST(Connection, ASessionWhoseBridgeFallsSilentIsClosedAfterTheAnswerTimeout) {
  ControllerStack stack("silent");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  ConnectOptions options;
  options.answer_timeout = 300ms;
  Connection c(address_of(stack), options);
  StateSnapshot s;
  ASSERT_TRUE(c.wait_for_answer(0, 2s, s));
  stack.bridge().signal(SIGKILL);  // no REFUSE, no BYE: just silence
  const auto killed = std::chrono::steady_clock::now();
  ASSERT_TRUE(ControllerStack::eventually([&] { return !c.is_open(); }, 3s));
  EXPECT_GE(std::chrono::steady_clock::now() - killed, 250ms) << "not before the timeout";
  try {
    c.set_power(true);
    FAIL() << "a closed session refuses calls";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kClosed);
    EXPECT_THAT(e.what(), testing::HasSubstr("no answer from the bridge for 300 ms")) << e.what();
  }
}

TEST(Connection, NoControllerAndNoBridgeGiveClearErrors) {
  ConnectOptions quick;
  quick.connect_timeout = 200ms;
  try {
    Connection c({"127.0.0.1", 9}, quick);  // discard port: nobody answers
    FAIL();
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kTimeout);
    EXPECT_THAT(e.what(), testing::HasSubstr("is hapticctrl-udp running there?"));
  }
}

}  // namespace
}  // namespace hapticctrl::client
