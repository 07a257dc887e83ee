// Tests of page_request.hpp: what a page may ask, validated: JSON text from a WebSocket becomes an
// HMI command or an operator wrench for LCM (hmi_command_t, hmi_force_t), or a refusal with its
// reason.
#include "hapticctrl/web_bridge/page_request.hpp"

#include <gtest/gtest.h>

#include <string>

#include "hapticctrl_lcm/hmi_command_t.hpp"

namespace hapticctrl::web_bridge {
namespace {

using Command = hapticctrl_lcm::hmi_command_t;

TEST(PageRequest, CommandsMapToTheirHmiCodes) {
  const struct {
    const char* name;
    std::int32_t code;
  } cases[] = {{"power_on", Command::POWER_ON},
               {"power_off", Command::POWER_OFF},
               {"emergency_stop", Command::EMERGENCY_STOP},
               {"emergency_reset", Command::EMERGENCY_RESET}};
  for (const auto& c : cases) {
    const PageRequest r = parse_page_request(
        std::string("{\"type\":\"command\",\"command\":\"") + c.name + "\"}", true);
    EXPECT_EQ(r.kind, PageRequestKind::kCommand) << c.name;
    EXPECT_EQ(r.command, c.code) << c.name;
    EXPECT_TRUE(r.accepted());
  }
}

TEST(PageRequest, OnlyTheEmergencyStopPassesWithoutRemoteCommands) {
  EXPECT_EQ(parse_page_request(R"({"type":"command","command":"emergency_stop"})", false).kind,
            PageRequestKind::kCommand);
  const PageRequest power = parse_page_request(R"({"type":"command","command":"power_on"})", false);
  EXPECT_EQ(power.kind, PageRequestKind::kRefused);
  EXPECT_NE(power.reason.find("--allow-remote-commands"), std::string::npos);
  EXPECT_EQ(parse_page_request(R"({"type":"force","wrench":[1,0,0,0,0,0]})", false).kind,
            PageRequestKind::kRefused);
}

TEST(PageRequest, ForcesWithinBoundsAreAccepted) {
  const PageRequest r =
      parse_page_request(R"({"type":"force","wrench":[100,-100,2.5,10,-10,0.25]})", true);
  ASSERT_EQ(r.kind, PageRequestKind::kForce);
  EXPECT_EQ(r.wrench[0], 100.0);
  EXPECT_EQ(r.wrench[4], -10.0);
  EXPECT_EQ(r.wrench[5], 0.25);
}

TEST(PageRequest, ForcesBeyondBoundsOrNonFiniteAreRefused) {
  for (const char* text : {R"({"type":"force","wrench":[100.001,0,0,0,0,0]})",
                           R"({"type":"force","wrench":[0,0,0,0,0,10.5]})",
                           R"({"type":"force","wrench":[1e308,0,0,0,0,0]})"}) {
    EXPECT_EQ(parse_page_request(text, true).kind, PageRequestKind::kOutOfRange) << text;
  }
}

TEST(PageRequest, MalformedMessagesAreNamedNotThrown) {
  for (const char* text :
       {"", "not json", "[1,2,3]", "42", "{}", R"({"type":3})", R"({"type":"dance"})",
        R"({"type":"command"})", R"({"type":"command","command":7})",
        R"({"type":"command","command":"self_destruct"})", R"({"type":"force"})",
        R"({"type":"force","wrench":[1,2,3]})", R"({"type":"force","wrench":[1,2,3,4,5,"6"]})",
        R"({"type":"force","wrench":[1,2,3,4,5,null]})", R"({"type":"force","wrench":"111111"})",
        R"({"type":"force","wrench":[0,0,-1e400,0,0,0]})",  // JSON has no infinity
        "{\"type\":\"command\",\"command\":\"\xff\xfe\"}", "{\"type\":\"comm", "\xef\xbb\xbf{"}) {
    const PageRequest r = parse_page_request(text, true);
    EXPECT_EQ(r.kind, PageRequestKind::kMalformed) << text;
    EXPECT_FALSE(r.reason.empty()) << text;
    EXPECT_NO_THROW((void)reply_json(r)) << text;
  }
}

TEST(PageRequest, DeepNestingAndOversizeAreRefused) {
  EXPECT_EQ(parse_page_request(std::string(1000, '[') + std::string(1000, ']'), true).kind,
            PageRequestKind::kMalformed);
  const std::string padded = R"({"type":"command","command":"power_on","pad":")" +
                             std::string(kMaxPageMessageBytes, 'x') + "\"}";
  EXPECT_EQ(parse_page_request(padded, true).reason, "message too long");
}

TEST(PageRequest, RepliesSayOkOrWhy) {
  EXPECT_EQ(reply_json(parse_page_request(R"({"type":"command","command":"power_on"})", true)),
            R"({"ok":true,"request":"power_on","type":"reply"})");
  const std::string refused =
      reply_json(parse_page_request(R"({"type":"command","command":"power_on"})", false));
  EXPECT_NE(refused.find("\"ok\":false"), std::string::npos);
  EXPECT_NE(refused.find("remote commands are disabled"), std::string::npos);
}

}  // namespace
}  // namespace hapticctrl::web_bridge
