// The HMI's operator access against a real hapticctrl-core.
#include "hapticctrl/hmi/operator.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "support/controller_stack.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::hmi {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

std::string attach_error(const std::string& instance) {
  try {
    Operator op(instance, false);
  } catch (const HmiError& e) {
    return e.what();
  }
  return "attached";
}

TEST(Operator, NoControllerSaysSoAndNamesTheRunningInstances) {
  ControllerStack stack("opnames");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string e = attach_error("no-such-instance");
  EXPECT_NE(e.find("no controller is running for instance 'no-such-instance'"), std::string::npos)
      << e;
  EXPECT_NE(e.find(stack.instance()), std::string::npos) << "lists the live instance: " << e;
  EXPECT_NE(attach_error("bad name!").find("instance"), std::string::npos);
  const auto listed = shm::listed_instances();
  EXPECT_NE(std::find(listed.begin(), listed.end(), stack.instance()), listed.end());
}

TEST(Operator, CommandsTakeEffectAndTheForceRampsIntoTheRegion) {
  ControllerStack stack("opcmd");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator op(stack.instance(), true);
  ASSERT_TRUE(op.force_available()) << op.force_unavailable();
  EXPECT_TRUE(op.send_and_wait(
      shm::CtrlCode::kPowerOn, [](const ControllerStatus& s) { return s.powered(); }, 2s));
  EXPECT_TRUE(op.send_and_wait(
      shm::CtrlCode::kEmergencyStop, [](const ControllerStatus& s) { return s.emergency_stop(); },
      2s));
  EXPECT_FALSE(op.status().powered()) << "the emergency stop cuts the power";
  EXPECT_TRUE(op.send_and_wait(
      shm::CtrlCode::kEmergencyReset, [](const ControllerStatus& s) { return !s.emergency_stop(); },
      2s));

  EXPECT_FALSE(op.request_force({150, 0, 0, 0, 0, 0})) << "beyond the operator limits";
  ASSERT_TRUE(op.request_force({4, 0, 0, 0, 0.2, 0}));
  op.settle_force();
  EXPECT_TRUE(op.force().settled());
  EXPECT_TRUE(ControllerStack::eventually([&] {
    return op.status().position.operator_wrench == shm::Vector6{4, 0, 0, 0, 0.2, 0};
  })) << "the core applies the wrench on the simulated handle";
  EXPECT_EQ(op.status().requested_force, (shm::Vector6{4, 0, 0, 0, 0.2, 0}));
}

TEST(Operator, ASecondForceWriterIsTurnedAwayButCommandsStillWork) {
  ControllerStack stack("opforce");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  {
    Operator first(stack.instance(), true);
    ASSERT_TRUE(first.request_force({1, 0, 0, 0, 0, 0}));
    first.settle_force();
  }
  // Another process holds the force region: a panel playing a sequence.
  const std::string sequence = "/tmp/hapticctrl-opforce-" + std::to_string(getpid()) + ".txt";
  std::ofstream(sequence) << "0 1 0 0 0 0 0\n10 1 0 0 0 0 0\n";
  test::SpawnedProcess player(HAPTICCTRL_HMI_BINARY, {"--instance", stack.instance(), "play",
                                                      sequence, "--log", "/dev/null"});
  ASSERT_TRUE(ControllerStack::eventually([&] {
    return player.err().find("playing 2 samples") != std::string::npos;
  })) << player.err();
  Operator second(stack.instance(), true);
  EXPECT_FALSE(second.force_available());
  EXPECT_NE(second.force_unavailable().find("already written by live process"), std::string::npos)
      << second.force_unavailable();
  EXPECT_FALSE(second.request_force({2, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(second.send_and_wait(
      shm::CtrlCode::kPowerOn, [](const ControllerStatus& s) { return s.powered(); }, 2s));
  std::remove(sequence.c_str());
}

TEST(Operator, ANewForceWriterStartsFromTheWrenchInTheRegion) {
  ControllerStack stack("opresume");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  {
    Operator first(stack.instance(), true);
    ASSERT_TRUE(first.request_force({1, 0, 0, 0, 0, 0}));
    first.settle_force();
  }
  Operator again(stack.instance(), true);
  EXPECT_EQ(again.force().applied(), (shm::Vector6{1, 0, 0, 0, 0, 0})) << "no jump to zero";
}

}  // namespace
}  // namespace hapticctrl::hmi
