// The C API's sessions, errors and diagnostics against the real controller and bridge.
#include "hapticctrl/virtuose_api.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/controller_stack.hpp"
#include "virtuose_session.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;
using test::VirtuoseSession;

// H2: an application written against VirtuoseAPI 4.x compares these numbers (five differed).
static_assert(COMMAND_TYPE_NONE == 0 && COMMAND_TYPE_IMPEDANCE == 3 && COMMAND_TYPE_VIRTMECH == 5 &&
              COMMAND_TYPE_ARTICULAR_IMPEDANCE == 7);
static_assert(VIRT_E_INVALID_CONTEXT == 3 && VIRT_E_TIME_OUT == 6 && VIRT_E_NOT_IMPLEMENTED == 7 &&
              VIRT_E_INCORRECT_VALUE == 9 && VIRT_E_WRONG_MODE == 17 &&
              VIRT_E_MODE_NOT_SUPPORTED == 18 && VIRT_E_INCOMPATIBLE_VERSION == 20 &&
              VIRT_E_INCORRECT_VM_TYPE == 21 && VIRT_E_ALREADY_CALLED == 22);
static_assert(INDEXING_ROT_FORCE_FEEDBACK_INHIBITION == 6 && INDEXING_ROT == 7 &&
              VM_TYPE_Crank == 8 && GRIPPER_COMMAND_TYPE_IMPEDANCE == 2 && DEBUG_LOOP == 2);
static_assert(VIRT_BOUND_SUP_AXE_2_3 == 0x2000 && VIRT_ALARM_SATURATE == 0x8000 &&
              VIRT_ALARM_CALLBACK_OVERRUN == 0x20000 && VIRT_BREAKDOWN_MOTOR_8 == 0x80);

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
  EXPECT_STREQ(virtGetErrorMessage(22), "already called");
  EXPECT_STREQ(virtGetErrorMessage(23), "unknown error");
  EXPECT_EQ(virtClose(nullptr), -1);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INVALID_CONTEXT);
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

TEST(VirtuoseApi, VersionsAxesAndTheLastErrorOfASession) {
  int major = 0;
  int minor = 0;
  ASSERT_EQ(virtAPIVersion(&major, &minor), 0);
  EXPECT_EQ(major, 4) << "the VirtuoseAPI level the header matches (4.04)";
  EXPECT_EQ(minor, 4);
  ControllerStack stack("capiversion");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  ASSERT_EQ(virtGetControlerVersion(vc.get(), &major, &minor), 0);
  EXPECT_EQ(major, 1);
  EXPECT_EQ(minor, 4) << "the bridge's protocol, from its WELCOME";
  int axes = 0;
  ASSERT_EQ(virtGetNbAxes(vc.get(), &axes), 0);
  EXPECT_EQ(axes, 6);
  axes = 0;
  ASSERT_EQ(virtGetNumberOfAxes(vc.get(), &axes), 0);  // exported by Haption's library (J6)
  EXPECT_EQ(axes, 6);
  int error = -1;
  ASSERT_EQ(virtGetError(vc.get(), &error), 0);
  EXPECT_EQ(error, VIRT_E_NO_ERROR);
  EXPECT_EQ(virtSetForceFactor(vc.get(), -2.0F), -1);
  ASSERT_EQ(virtGetError(vc.get(), &error), 0);
  EXPECT_EQ(error, VIRT_E_INCORRECT_VALUE);
  EXPECT_EQ(virtGetError(nullptr, &error), -1);
}

TEST(VirtuoseApi, DebugLinesGoToTheOutputFileAndTheHardwareStatusIsTheControllers) {
  ControllerStack stack("capidebug");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() / (stack.instance() + "-virtuose.log");
  std::string name = log.string();
  ASSERT_EQ(virtSetOutputFile(vc.get(), name.data()), 0) << vc.detail();
  std::string missing = "/nonexistent-dir/x.log";
  EXPECT_EQ(virtSetOutputFile(vc.get(), missing.data()), -1);
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_FILE_NOT_FOUND);
  EXPECT_EQ(virtSetDebugFlags(vc.get(), 0x4), -1) << "DEBUG_SERVO and DEBUG_LOOP only";
  ASSERT_EQ(virtSetDebugFlags(vc.get(), DEBUG_SERVO | DEBUG_LOOP), 0);
  float period = 0.01F;
  ASSERT_EQ(virtSetPeriodicFunction(
                vc.get(), [](VirtContext, void*) {}, &period, nullptr),
            0);
  ASSERT_EQ(virtStartLoop(vc.get()), 0);
  std::this_thread::sleep_for(200ms);
  ASSERT_EQ(virtStopLoop(vc.get()), 0);
  ASSERT_EQ(virtSetDebugFlags(vc.get(), 0), 0);
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("virtuose servo: cycle "), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("virtuose loop: cycle "), std::string::npos) << text.str();
  std::filesystem::remove(log);

  char* buffer = nullptr;
  std::size_t size = 0;
  FILE* status = open_memstream(&buffer, &size);
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(virtDisplayHardwareStatus(vc.get(), status), 0);
  std::fclose(status);
  const std::string shown(buffer, size);
  free(buffer);  // NOLINT(*-no-malloc,*-owning-memory): open_memstream's
  EXPECT_NE(shown.find("protocol 1.4"), std::string::npos) << shown;
  EXPECT_NE(shown.find("core running"), std::string::npos) << shown;
  EXPECT_NE(shown.find("power off"), std::string::npos) << shown;
  EXPECT_EQ(virtDisplayHardwareStatus(vc.get(), nullptr), -1);
}
}  // namespace
}  // namespace hapticctrl
