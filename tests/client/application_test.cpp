// Tests of application.hpp: connect_retrying against the real hapticctrl-core and hapticctrl-udp
// on loopback (a controller held by another client), close_quietly, and the distance contacts
// are reported from.
#include "hapticctrl/client/application.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/controller_stack.hpp"

namespace hapticctrl::client {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

TEST(Application, TheRefusalsAnApplicationWaitsOutAreRetried) {
  const RetryPolicy first;
  RetryPolicy again;
  again.reconnecting = true;
  for (const ErrorCode code :
       {ErrorCode::kBusy, ErrorCode::kNoController, ErrorCode::kTimeout, ErrorCode::kClosed}) {
    EXPECT_TRUE(retried(code, first));
  }
  EXPECT_FALSE(retried(ErrorCode::kRejected, first)) << "a refused setup, the first time";
  EXPECT_TRUE(retried(ErrorCode::kRejected, again)) << "failing safe again while reconnecting";
  EXPECT_FALSE(retried(ErrorCode::kInvalidArgument, again));
}

TEST(Application, ContactsAreReportedFromWhatTheHandleCanReachOverTheRoundTrip) {
  LinkStatistics link;
  EXPECT_DOUBLE_EQ(contact_report_distance(link), kContactNear);
  link.rtt_mean_us = 20'000;  // 10 ms one way
  EXPECT_DOUBLE_EQ(contact_report_distance(link), 0.005 + 1.0 * 0.040);
  link.loop_delay_us = 50'000;
  EXPECT_DOUBLE_EQ(contact_report_distance(link), 0.005 + 1.0 * 0.100) << "the larger delay";
}

TEST(Application, ABusyControllerIsWaitedForThenJoined) {
  ControllerStack stack("retrying");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const Address address{"127.0.0.1", stack.port()};
  std::optional<Connection> holder;
  holder.emplace(address);
  std::vector<std::string> said;
  const auto say = [&said](const ClientError& e) { said.emplace_back(e.what()); };
  int setups = 0;
  const auto setup = [&setups](Connection&) { ++setups; };
  RetryPolicy brief;
  brief.patience = 600ms;
  brief.interval = 100ms;
  ConnectOptions quick;
  quick.connect_timeout = 200ms;
  try {
    (void)connect_retrying(
        address, quick, setup, [] { return true; }, brief, say);
    FAIL() << "the controller was busy all along";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kBusy) << e.what();
  }
  ASSERT_FALSE(said.empty());
  EXPECT_EQ(said.size(), 1U) << "each reason once";
  EXPECT_EQ(setups, 0);
  int asked = 0;
  EXPECT_FALSE(connect_retrying(
                   address, quick, setup, [&asked] { return ++asked < 3; }, brief, say)
                   .has_value())
      << "the application stopped waiting";
  close_quietly(*holder);
  close_quietly(*holder);  // twice: nothing to close, nothing thrown
  RetryPolicy patient = brief;
  patient.patience = 5s;
  std::optional<Connection> joined = connect_retrying(
      address, quick, setup, [] { return true; }, patient, say);
  ASSERT_TRUE(joined.has_value());
  EXPECT_TRUE(joined->is_open());
  EXPECT_EQ(setups, 1) << "set up once, when it joined";
}

}  // namespace
}  // namespace hapticctrl::client
