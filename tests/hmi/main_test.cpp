// hapticctrl-hmi's one-shot commands, run as the real binary against a real core.
#include <gtest/gtest.h>

#include "support/controller_stack.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

struct HmiRun {
  int status;
  std::string out;
  std::string err;
};

HmiRun hmi(const std::vector<std::string>& args) {
  SpawnedProcess p(HAPTICCTRL_HMI_BINARY, args);
  const int status = p.wait(20s);
  return {status, p.out(), p.err()};
}

std::vector<std::string> on(const ControllerStack& s, std::vector<std::string> args) {
  args.insert(args.begin(), {"--instance", s.instance()});
  return args;
}

TEST(HmiCommands, UsageErrorsExit64AndAMissingControllerExits1WithAHint) {
  const HmiRun usage = hmi({"force", "1"});
  EXPECT_EQ(usage.status, 64);
  EXPECT_NE(usage.err.find("force needs 6 numbers"), std::string::npos) << usage.err;
  EXPECT_NE(usage.err.find("(see hapticctrl-hmi --help)"), std::string::npos) << usage.err;
  const HmiRun missing = hmi({"--instance", "nobody-here", "status"});
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("no controller is running for instance 'nobody-here'"),
            std::string::npos)
      << missing.err;
}

TEST(HmiCommands, PowerEmergencyStopForceAndStatusFromAScript) {
  ControllerStack stack("hmicmd");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  EXPECT_EQ(hmi(on(stack, {"power-on"})).out, "powered on\n");
  EXPECT_EQ(hmi(on(stack, {"estop"})).out, "emergency stop latched\n");
  const HmiRun refused = hmi(on(stack, {"--timeout-ms", "300", "power-on"}));
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("reset it first"), std::string::npos) << refused.err;
  EXPECT_EQ(hmi(on(stack, {"reset"})).status, 0);
  EXPECT_EQ(hmi(on(stack, {"power-on"})).status, 0);
  const HmiRun force = hmi(on(stack, {"force", "3", "0", "0", "0", "0", "0"}));
  EXPECT_EQ(force.status, 0) << force.err;
  EXPECT_TRUE(ControllerStack::eventually([&] {
    const HmiRun s = hmi(on(stack, {"status", "--json"}));
    return s.out.find("\"operator_wrench\":[3,0,0,0,0,0]") != std::string::npos &&
           s.out.find("\"powered\":true") != std::string::npos;
  })) << hmi(on(stack, {"status", "--json"})).out;
  EXPECT_EQ(hmi(on(stack, {"zero-force"})).status, 0);
  EXPECT_NE(hmi(on(stack, {"status"})).out.find("running, powered"), std::string::npos);
}

TEST(HmiCommands, StopShutsTheControllerDownAndSaysWhy) {
  ControllerStack stack("hmistop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const HmiRun stop = hmi(on(stack, {"stop"}));
  EXPECT_EQ(stop.status, 0) << stop.err;
  EXPECT_NE(stop.out.find("stopped (stopping, stop requested)"), std::string::npos) << stop.out;
  EXPECT_EQ(stack.core().wait(5s), 0);
}

}  // namespace
}  // namespace hapticctrl::test
