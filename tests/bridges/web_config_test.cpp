// Tests of web_config.hpp: command line of hapticctrl-web.
#include "hapticctrl/web_bridge/web_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::web_bridge {
namespace {

TEST(WebConfig, DefaultsServeThisHostOnlyWithoutRemoteCommands) {
  const WebConfig c = WebConfig::parse({});
  EXPECT_EQ(c.listen, "127.0.0.1:8080");
  EXPECT_FALSE(c.allow_remote_commands);
  EXPECT_EQ(c.push_rate_hz, 30.0);
  EXPECT_NE(c.lcm_url.find("ttl=0"), std::string::npos);
}

TEST(WebConfig, ParsesEveryOption) {
  const WebConfig c = WebConfig::parse({"--listen", "0.0.0.0:9000", "--allow-remote", "--www",
                                        "/srv/www", "--arm-model", "m.arm", "--instance", "lab",
                                        "--lcm-url", "memq://", "--rate", "60", "--max-pages", "2",
                                        "--allow-remote-commands", "--duration", "1.5", "--json"});
  EXPECT_EQ(c.listen, "0.0.0.0:9000");
  EXPECT_TRUE(c.allow_remote);
  EXPECT_EQ(c.www_dir, "/srv/www");
  EXPECT_EQ(c.arm_model_path, "m.arm");
  EXPECT_EQ(c.instance, "lab");
  EXPECT_EQ(c.lcm_url, "memq://");
  EXPECT_EQ(c.push_rate_hz, 60.0);
  EXPECT_EQ(c.max_pages, 2);
  EXPECT_TRUE(c.allow_remote_commands);
  EXPECT_EQ(c.duration_s, 1.5);
  EXPECT_TRUE(c.json);
}

TEST(WebConfig, RefusesBadValuesNamingTheOption) {
  for (const auto& args : std::vector<std::vector<std::string>>{{"--listen", "8080"},
                                                                {"--listen", "localhost:8080"},
                                                                {"--listen", "127.0.0.1:70000"},
                                                                {"--listen", "127.0.0.1:"},
                                                                {"--rate", "0"},
                                                                {"--rate", "61"},
                                                                {"--rate", "fast"},
                                                                {"--max-pages", "0"},
                                                                {"--duration", "-1"},
                                                                {"--instance"},
                                                                {"--bogus"}}) {
    try {
      (void)WebConfig::parse(args);
      ADD_FAILURE() << args[0] << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr(args[0].substr(0, 8))) << e.what();
    }
  }
}

TEST(WebConfig, ServingBeyondLoopbackMustBeMeant) {
  try {
    (void)WebConfig::parse({"--listen", "0.0.0.0:8080"});
    FAIL() << "listened beyond loopback without --allow-remote";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("--allow-remote")) << e.what();
  }
  EXPECT_EQ(WebConfig::parse({"--listen", "127.0.0.2:8080"}).listen, "127.0.0.2:8080");
}

}  // namespace
}  // namespace hapticctrl::web_bridge
