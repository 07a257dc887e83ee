// Tests of page_gateway.hpp: from a page's text message to the LCM HMI channels: validates it
// (page_request.hpp), limits each page's force messages to kMinForceInterval apart, publishes
// what passes and counts every outcome.
#include "hapticctrl/web_bridge/page_gateway.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace hapticctrl::web_bridge {
namespace {

class RecordingPublisher final : public HmiPublisher {
 public:
  bool publish(const hapticctrl_lcm::hmi_command_t& m) override {
    commands.push_back(m);
    return accept;
  }
  bool publish(const hapticctrl_lcm::hmi_force_t& m) override {
    forces.push_back(m);
    return accept;
  }
  std::vector<hapticctrl_lcm::hmi_command_t> commands;
  std::vector<hapticctrl_lcm::hmi_force_t> forces;
  bool accept = true;
};

using namespace std::chrono_literals;

/// The moment `t` after the clock's origin.
TimePoint at(Duration t) {
  return TimePoint{t};
}

TEST(PageGateway, ForwardsACommandWithItsOriginAndAcknowledgesIt) {
  RecordingPublisher out;
  PageGateway gateway(out, true);
  PageSession page{"10.0.0.7:5000"};
  const std::string reply =
      gateway.handle(page, R"({"type":"command","command":"power_on"})", at(5000ms));
  ASSERT_EQ(out.commands.size(), 1U);
  EXPECT_EQ(out.commands[0].command, hapticctrl_lcm::hmi_command_t::POWER_ON);
  EXPECT_EQ(out.commands[0].origin, "web 10.0.0.7:5000");
  EXPECT_EQ(out.commands[0].utime, 5'000'000);
  EXPECT_NE(reply.find("\"ok\":true"), std::string::npos);
  EXPECT_EQ(gateway.counters().commands_forwarded.load(), 1U);
}

TEST(PageGateway, ForwardsForcesSilentlyAndLimitsTheirRatePerPage) {
  RecordingPublisher out;
  PageGateway gateway(out, true);
  PageSession a{"a"};
  PageSession b{"b"};
  const char* force = R"({"type":"force","wrench":[5,0,0,0,0,0]})";
  EXPECT_EQ(gateway.handle(a, force, at(100ms)), "");
  EXPECT_EQ(gateway.handle(a, force, at(105ms)), "");  // too soon: dropped
  EXPECT_EQ(gateway.handle(b, force, at(105ms)), "");  // another page: its own budget
  EXPECT_EQ(gateway.handle(a, force, at(110ms)), "");
  ASSERT_EQ(out.forces.size(), 3U);
  EXPECT_EQ(out.forces[0].wrench[0], 5.0);
  EXPECT_EQ(gateway.counters().forces_forwarded.load(), 3U);
  EXPECT_EQ(gateway.counters().rate_limited.load(), 1U);
}

TEST(PageGateway, CountsEveryRefusalAndPublishesNothingForIt) {
  RecordingPublisher out;
  PageGateway gateway(out, false);
  PageSession page{"p"};
  EXPECT_NE(gateway.handle(page, R"({"type":"command","command":"power_on"})", TimePoint{})
                .find("\"ok\":false"),
            std::string::npos);
  (void)gateway.handle(page, R"({"type":"force","wrench":[1,0,0,0,0,0]})", TimePoint{});
  (void)gateway.handle(page, R"({"type":"force","wrench":[1000,0,0,0,0,0]})", TimePoint{});
  (void)gateway.handle(page, "}{", TimePoint{});
  EXPECT_TRUE(out.commands.empty());
  EXPECT_TRUE(out.forces.empty());
  EXPECT_EQ(gateway.counters().refused.load(), 2U);
  EXPECT_EQ(gateway.counters().out_of_range.load(), 1U);
  EXPECT_EQ(gateway.counters().malformed.load(), 1U);
  // The emergency stop goes through all the same.
  (void)gateway.handle(page, R"({"type":"command","command":"emergency_stop"})", TimePoint{});
  ASSERT_EQ(out.commands.size(), 1U);
  EXPECT_EQ(out.commands[0].command, hapticctrl_lcm::hmi_command_t::EMERGENCY_STOP);
}

TEST(PageGateway, TellsThePageWhenTheBusRefuses) {
  RecordingPublisher out;
  out.accept = false;
  PageGateway gateway(out, true);
  PageSession page{"p"};
  const std::string reply =
      gateway.handle(page, R"({"type":"command","command":"emergency_stop"})", TimePoint{});
  EXPECT_NE(reply.find("the LCM bus refused"), std::string::npos) << reply;
  EXPECT_NE(gateway.handle(page, R"({"type":"force","wrench":[0,0,0,0,0,0]})", TimePoint{})
                .find("\"ok\":false"),
            std::string::npos);
  EXPECT_EQ(gateway.counters().publish_failed.load(), 2U);
}

}  // namespace
}  // namespace hapticctrl::web_bridge
