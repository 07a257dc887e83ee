// Tests of core_config.hpp: command line of `hapticctrl-core`, validated.
#include "hapticctrl/rt_core/core_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

CoreConfig parse(const std::vector<std::string>& args) {
  return parse_core_args(args);
}

void expect_error(const std::vector<std::string>& args, const std::string& text) {
  try {
    parse_core_args(args);
    FAIL() << "expected an error containing " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr(text)) << e.what();
  }
}

TEST(CoreConfig, Defaults) {
  const CoreConfig c = parse({});
  EXPECT_EQ(c.instance, "default");
  EXPECT_EQ(c.period, 1ms);
  EXPECT_EQ(c.rt_policy, RtPolicy::kWarn);
  EXPECT_EQ(c.duration, 0ns);
  EXPECT_FALSE(c.benchmark_mode);
}

TEST(CoreConfig, ParsesEveryOption) {
  const CoreConfig c = parse({"--instance",  "a1",
                              "--period-us", "250",
                              "--duration",  "1.5",
                              "--rt",        "ignore",
                              "--priority",  "70",
                              "--cpu",       "-1",
                              "--json",      "--histogram",
                              "/tmp/h",      "--inject-overrun",
                              "100:5",       "--trip-miss-ppm",
                              "1000",        "--miss-window",
                              "500",         "--sim-substep-us",
                              "400",         "--benchmark-mode"});
  EXPECT_EQ(c.instance, "a1");
  EXPECT_EQ(c.period, 250us);
  EXPECT_EQ(c.duration, 1500ms);
  EXPECT_EQ(c.rt_policy, RtPolicy::kIgnore);
  EXPECT_EQ(c.priority, 70);
  EXPECT_EQ(c.cpu, -1);
  EXPECT_TRUE(c.json);
  EXPECT_EQ(c.histogram_path, "/tmp/h");
  EXPECT_EQ(c.inject_at_cycle, 100U);
  EXPECT_EQ(c.inject_cycles, 5U);
  EXPECT_TRUE(c.allow_fault_injection);
  EXPECT_EQ(c.chronic.trip_window_ppm, 1000U);
  EXPECT_EQ(c.chronic.window_cycles, 500U);
  EXPECT_EQ(c.sim_substep, 400us);
  EXPECT_TRUE(c.benchmark_mode);
}

TEST(CoreConfig, RejectsBadInputWithTheOptionName) {
  expect_error({"--period-us", "50"}, "--period-us: expected a number from 100 to 10000, got '50'");
  expect_error({"--period-us", "20000"}, "expected a number from 100 to 10000");
  expect_error({"--period-us", "1ms"}, "got '1ms'");
  expect_error({"--rt", "maybe"}, "--rt must be enforce, warn or ignore");
  expect_error({"--priority", "99"}, "--priority");
  expect_error({"--inject-overrun", "5"}, "CYCLE:K");
  expect_error({"--sim-substep-us", "2000"},
               "--sim-substep-us: expected a number from 10 to 1000, got '2000'");
  expect_error({"--duration", "nan"}, "--duration: expected a number from 0 to 1e+07, got 'nan'");
  expect_error({"--duration", "inf"}, "--duration: expected a number from 0 to 1e+07, got 'inf'");
  expect_error({"--instance"}, "--instance: 1 required TEXT missing");
  expect_error({"--frobnicate"}, "not expected: --frobnicate");
}

}  // namespace
}  // namespace hapticctrl::rt_core
