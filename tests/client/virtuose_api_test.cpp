// The VirtuoseAPI-style C API against the real controller and bridge.
#include "hapticctrl/virtuose_api.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

#include "hapticctrl/shm/segment.hpp"
#include "support/controller_stack.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

std::string url(const ControllerStack& stack) {
  return "udpxdr://127.0.0.1:" + std::to_string(stack.port());
}

// H2: an application written against VirtuoseAPI 4.x compares these numbers (five differed).
static_assert(COMMAND_TYPE_NONE == 0 && COMMAND_TYPE_IMPEDANCE == 3 && COMMAND_TYPE_VIRTMECH == 5 &&
              COMMAND_TYPE_ARTICULAR_IMPEDANCE == 7);
static_assert(VIRT_E_INVALID_CONTEXT == 3 && VIRT_E_TIME_OUT == 6 && VIRT_E_NOT_IMPLEMENTED == 7 &&
              VIRT_E_INCORRECT_VALUE == 9 && VIRT_E_WRONG_MODE == 17 &&
              VIRT_E_MODE_NOT_SUPPORTED == 18 && VIRT_E_INCOMPATIBLE_VERSION == 20 &&
              VIRT_E_INCORRECT_VM_TYPE == 21);

TEST(VirtuoseApi, OpenFailuresHaveCodesAndDetails) {
  EXPECT_EQ(virtOpen(nullptr), nullptr);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_WRONG_FORMAT);
  EXPECT_EQ(virtOpen("udpxdr://127.0.0.1:0"), nullptr);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_WRONG_FORMAT);
  EXPECT_NE(std::string(virtGetErrorDetail(nullptr)).find("bad controller address"),
            std::string::npos);
  EXPECT_STREQ(virtGetErrorMessage(VIRT_E_TIME_OUT), "time out");
  EXPECT_STREQ(virtGetErrorMessage(VIRT_E_WRONG_MODE), "wrong mode");
  EXPECT_STREQ(virtGetErrorMessage(VIRT_E_CONTROLLER_REFUSED), "controller refused");
  EXPECT_STREQ(virtGetErrorMessage(-5), "unknown error");
  EXPECT_STREQ(virtGetErrorMessage(22), "unknown error");
  EXPECT_EQ(virtClose(nullptr), -1);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INVALID_CONTEXT);
}

TEST(VirtuoseApi, ParametersStateAndModes) {
  ControllerStack stack("capi");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string name = "127.0.0.1#" + std::to_string(stack.port());
  VirtContext vc = virtOpen(name.c_str());
  ASSERT_NE(vc, nullptr) << virtGetErrorDetail(nullptr);
  float identity[7] = {0, 0, 0, 0, 0, 0, 1};    // NOLINT(*-avoid-c-arrays)
  float inertia[3] = {0.001F, 0.001F, 0.001F};  // NOLINT(*-avoid-c-arrays)
  EXPECT_EQ(virtSetTimeStep(vc, 0.002F), 0);
  EXPECT_EQ(virtSetIndexingMode(vc, INDEXING_ALL), 0);
  EXPECT_EQ(virtSetForceFactor(vc, 1.0F), 0);
  EXPECT_EQ(virtSetSpeedFactor(vc, 1.0F), 0);
  EXPECT_EQ(virtSetBaseFrame(vc, identity), 0);
  EXPECT_EQ(virtSetObservationFrame(vc, identity), 0);
  EXPECT_EQ(virtSaturateTorque(vc, 20.0F, 2.0F), 0);
  EXPECT_EQ(virtSetTimeoutValue(vc, 0.2F), 0);
  EXPECT_EQ(stack.vpr().watchdog_timeout_us, 200'000U);
  EXPECT_DOUBLE_EQ(stack.vpr().force_limits[0], 20.0);

  // H2: a getter right after a successful setter returns the new value.
  float value = 0.0F;
  EXPECT_EQ(virtGetTimeStep(vc, &value), 0);
  EXPECT_FLOAT_EQ(value, 0.002F);
  EXPECT_EQ(virtGetForceFactor(vc, &value), 0);
  EXPECT_FLOAT_EQ(value, 1.0F);
  EXPECT_EQ(virtSetSpeedFactor(vc, 0.5F), 0);
  EXPECT_EQ(virtGetSpeedFactor(vc, &value), 0);
  EXPECT_FLOAT_EQ(value, 0.5F);
  EXPECT_EQ(virtGetTimeoutValue(vc, &value), 0);
  EXPECT_FLOAT_EQ(value, 0.2F);
  VirtIndexingType mode = INDEXING_NONE;
  EXPECT_EQ(virtSetIndexingMode(vc, INDEXING_TRANS), 0);
  EXPECT_EQ(virtGetIndexingMode(vc, &mode), 0);
  EXPECT_EQ(mode, INDEXING_TRANS);
  EXPECT_EQ(virtSetIndexingMode(vc, INDEXING_ALL), 0);
  float shifted[7] = {0.1F, 0, 0, 0, 0, 0, 1};  // NOLINT(*-avoid-c-arrays)
  float frame[7] = {};                          // NOLINT(*-avoid-c-arrays)
  EXPECT_EQ(virtSetObservationFrame(vc, shifted), 0);
  EXPECT_EQ(virtGetObservationFrame(vc, frame), 0);
  EXPECT_FLOAT_EQ(frame[0], 0.1F);
  EXPECT_FLOAT_EQ(frame[6], 1.0F);
  EXPECT_EQ(virtGetBaseFrame(vc, frame), 0);
  EXPECT_FLOAT_EQ(frame[0], 0.0F);
  EXPECT_EQ(virtSetObservationFrame(vc, identity), 0);
  int major = 0;
  int minor = -1;
  EXPECT_EQ(virtGetControlerVersion(vc, &major, &minor), 0);
  EXPECT_EQ(major, 1);
  EXPECT_GE(minor, 1);
  EXPECT_EQ(virtGetTimeStep(vc, nullptr), -1);
  EXPECT_EQ(virtGetErrorCode(vc), VIRT_E_INCORRECT_VALUE);

  EXPECT_EQ(virtSetForceFactor(vc, -1.0F), -1);
  EXPECT_EQ(virtGetErrorCode(vc), VIRT_E_INCORRECT_VALUE);
  EXPECT_NE(std::string(virtGetErrorDetail(vc)).find("force factor"), std::string::npos);

  float force[6] = {1, 0, 0, 0, 0, 0};  // NOLINT(*-avoid-c-arrays)
  EXPECT_EQ(virtSetCommandType(vc, COMMAND_TYPE_ARTICULAR), -1);
  EXPECT_EQ(virtGetErrorCode(vc), VIRT_E_MODE_NOT_SUPPORTED);
  EXPECT_EQ(virtSetCommandType(vc, COMMAND_TYPE_VIRTMECH), 0);
  EXPECT_EQ(stack.vpr().command_type, 2U) << "the protocol's VIRTMECH";
  VirtCommandType type = COMMAND_TYPE_NONE;
  EXPECT_EQ(virtGetCommandType(vc, &type), 0);
  EXPECT_EQ(type, COMMAND_TYPE_VIRTMECH) << "not the refused ARTICULAR";
  EXPECT_EQ(virtAddForce(vc, force), -1);
  EXPECT_EQ(virtGetErrorCode(vc), VIRT_E_WRONG_MODE);
  EXPECT_EQ(virtAttachVO(vc, 0.5F, inertia), 0);
  EXPECT_EQ(stack.vpr().flags, 1U);
  EXPECT_EQ(virtDetachVO(vc), 0);

  EXPECT_EQ(virtSetPowerOn(vc, 1), 0);
  int power = 0;
  EXPECT_EQ(virtGetPowerOn(vc, &power), 0);
  EXPECT_EQ(power, 1) << "a getter right after the setter reports the new value";
  int operational = 0;
  EXPECT_EQ(virtGetEmergencyStop(vc, &operational), 0);
  EXPECT_EQ(operational, 1) << "Haption's meaning: 1 while the arm is operational";
  float pose[7] = {};    // NOLINT(*-avoid-c-arrays)
  float speed[6] = {};   // NOLINT(*-avoid-c-arrays)
  float joints[6] = {};  // NOLINT(*-avoid-c-arrays)
  EXPECT_EQ(virtGetPosition(vc, pose), 0);
  EXPECT_NEAR(std::hypot(std::hypot(pose[3], pose[4]), std::hypot(pose[5], pose[6])), 1.0F, 1e-5F);
  EXPECT_EQ(virtGetSpeed(vc, speed), 0);
  EXPECT_EQ(virtGetForce(vc, force), 0);
  EXPECT_EQ(virtGetArticularPosition(vc, joints), 0);
  EXPECT_EQ(virtGetArticularSpeed(vc, joints), 0);
  unsigned int age_us = 0;
  EXPECT_EQ(virtGetTimeLastUpdate(vc, &age_us), 0);
  EXPECT_LT(age_us, 1'000'000U);
  EXPECT_EQ(virtGetPosition(vc, nullptr), -1);
  EXPECT_EQ(virtClose(vc), 0);
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().sessions_closed == 1U; }, 1s));
}

TEST(VirtuoseApi, OpenReturnsWithTheArmsPoseAndInvalidContextsAreRefusedWithoutACrash) {
  ControllerStack stack("capiopen");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string name = "127.0.0.1#" + std::to_string(stack.port());
  // H2: virtGetPosition right after virtOpen gave (0,0,0) in 9 opens of 10.
  for (int i = 0; i < 5; ++i) {
    VirtContext vc = virtOpen(name.c_str());
    ASSERT_NE(vc, nullptr) << virtGetErrorDetail(nullptr);
    float pose[7] = {};  // NOLINT(*-avoid-c-arrays)
    EXPECT_EQ(virtGetPosition(vc, pose), 0);
    EXPECT_NEAR(pose[0], static_cast<float>(stack.position().handle_pose[0]), 0.01F)
        << "the real handle, not a default pose";
    EXPECT_GT(pose[0], 0.1F);
    ASSERT_EQ(virtClose(vc), 0);
    // H2: a call on a closed context was a use after free.
    int power = 0;
    EXPECT_EQ(virtGetPowerOn(vc, &power), -1);
    EXPECT_EQ(virtGetErrorCode(vc), VIRT_E_INVALID_CONTEXT);
    EXPECT_EQ(virtSetPowerOn(vc, 1), -1);
    EXPECT_EQ(virtClose(vc), -1);
    EXPECT_TRUE(ControllerStack::eventually(
        [&] { return stack.link_stats().sessions_closed == static_cast<std::uint64_t>(i) + 1; },
        2s));
  }
  int power = 0;
  EXPECT_EQ(virtGetPowerOn(nullptr, &power), -1);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INVALID_CONTEXT) << "not VIRT_E_INCORRECT_VALUE";
}

TEST(VirtuoseApi, PowerOnWithTheEmergencyStopLatchedFailsAndTheStopReadsNotOperational) {
  ControllerStack stack("capiestop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string name = "127.0.0.1#" + std::to_string(stack.port());
  VirtContext vc = virtOpen(name.c_str());
  ASSERT_NE(vc, nullptr) << virtGetErrorDetail(nullptr);
  shm::Segment operator_side = shm::Segment::attach(stack.instance(), {.ctrl_writer = true});
  operator_side.ctrl_writer().send(shm::CtrlCode::kEmergencyStop, 0, 0);
  int operational = 1;
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return virtGetEmergencyStop(vc, &operational) == 0 && operational == 0; }));
  // H2: it returned success while the power stayed off.
  EXPECT_EQ(virtSetPowerOn(vc, 1), -1);
  EXPECT_EQ(virtGetErrorCode(vc), VIRT_E_CONTROLLER_REFUSED);
  EXPECT_NE(std::string(virtGetErrorDetail(vc)).find("emergency stop is latched"),
            std::string::npos);
  int power = 1;
  EXPECT_EQ(virtGetPowerOn(vc, &power), 0);
  EXPECT_EQ(power, 0);
  operator_side.ctrl_writer().send(shm::CtrlCode::kEmergencyReset, 0, 0);
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return virtGetEmergencyStop(vc, &operational) == 0 && operational == 1; }));
  EXPECT_EQ(virtSetPowerOn(vc, 1), 0) << virtGetErrorDetail(vc);
  EXPECT_EQ(virtClose(vc), 0);
}

struct LoopState {
  std::atomic<int> calls{0};
  float push = 3.0F;
};

void periodic(VirtContext vc, void* arg) {
  auto* state = static_cast<LoopState*>(arg);
  ++state->calls;
  float force[6] = {state->push, 0, 0, 0, 0, 0};  // NOLINT(*-avoid-c-arrays)
  float extra[6] = {1, 0, 0, 0, 0, 0};            // NOLINT(*-avoid-c-arrays)
  virtSetForce(vc, force);
  virtAddForce(vc, extra);
}

TEST(VirtuoseApi, PeriodicFunctionRendersImpedanceForces) {
  ControllerStack stack("capiloop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  VirtContext vc = virtOpen(url(stack).c_str());
  ASSERT_NE(vc, nullptr) << virtGetErrorDetail(nullptr);
  EXPECT_EQ(virtStartLoop(vc), -1);  // no periodic function yet
  LoopState state;
  const float cycle_s = static_cast<float>(stack.period_us()) * 1e-6F;
  float period = 2.2F * cycle_s;  // rounded to two controller cycles, and written back
  ASSERT_EQ(virtSetPeriodicFunction(vc, periodic, &period, &state), 0);
  EXPECT_FLOAT_EQ(period, 2.0F * cycle_s);
  ASSERT_EQ(virtSetCommandType(vc, COMMAND_TYPE_IMPEDANCE), 0);
  ASSERT_EQ(virtSetPowerOn(vc, 1), 0);
  ASSERT_EQ(virtStartLoop(vc), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] {
    return std::abs(stack.vpr().impedance_wrench[0] - 4.0) < 1e-6;  // virtSetForce + virtAddForce
  }));
  state.calls = 0;
  std::this_thread::sleep_for(800ms);
  EXPECT_EQ(virtStopLoop(vc), 0);
  const int expected = 800'000 / (2 * stack.period_us());  // one call every two cycles
  EXPECT_GT(state.calls.load(), expected / 2);
  EXPECT_LT(state.calls.load(), expected * 3 / 2 + 2);
  EXPECT_EQ(virtClose(vc), 0);
}

}  // namespace
}  // namespace hapticctrl
