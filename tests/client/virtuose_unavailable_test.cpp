// The C API's functions without a meaning here fail with VirtuoseAPI's codes and a clear text,
// zero their outputs, and still recognise an invalid context.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "hapticctrl/virtuose_api.h"
#include "support/controller_stack.hpp"
#include "virtuose_session.hpp"

namespace hapticctrl {
namespace {

using test::ControllerStack;
using test::VirtuoseSession;

struct Case {
  const char* name;
  int code;
  std::function<int(VirtContext)> call;
};

std::vector<Case> cases() {
  static float f[16] = {};  // NOLINT(*-avoid-c-arrays)
  static int i = 0;
  static unsigned u = 0;
  static char file[] = "x.spline";  // NOLINT(*-avoid-c-arrays)
  const int na = VIRT_E_VARIABLE_NOT_AVAILABLE;
  const int ni = VIRT_E_NOT_IMPLEMENTED;
  return {
      {"virtGetButton", na, [](VirtContext v) { return virtGetButton(v, 1, &i); }},
      {"virtWaitPressButton", na, [](VirtContext v) { return virtWaitPressButton(v, 1); }},
      {"virtGetDeadMan", na, [](VirtContext v) { return virtGetDeadMan(v, &i); }},
      {"virtGetADC", na, [](VirtContext v) { return virtGetADC(v, 0, f); }},
      {"virtGetAnalogicInputs", na, [](VirtContext v) { return virtGetAnalogicInputs(v, f); }},
      {"virtGetTorInputs", na, [](VirtContext v) { return virtGetTorInputs(v, &u); }},
      {"virtGetTorInputs", na, [](VirtContext v) { return virtGetDigitalInputs(v, &u); }},
      {"virtOutputsSetting", na, [](VirtContext v) { return virtOutputsSetting(v, 1); }},
      {"virtSetPwmOutput", na, [](VirtContext v) { return virtSetPwmOutput(v, f); }},
      {"virtGetMouseState", na, [](VirtContext v) { return virtGetMouseState(v, &i, &i, &i); }},
      {"virtGetTrackball", na, [](VirtContext v) { return virtGetTrackball(v, &i, &i); }},
      {"virtGetTrackballButton", na,
       [](VirtContext v) { return virtGetTrackballButton(v, &i, &i, &i, &i); }},
      {"virtGetArticularPositionOfAdditionalAxe", na,
       [](VirtContext v) { return virtGetArticularPositionOfAdditionalAxe(v, f); }},
      {"virtGetArticularSpeedOfAdditionalAxe", na,
       [](VirtContext v) { return virtGetArticularSpeedOfAdditionalAxe(v, f); }},
      {"virtSetArticularPositionOfAdditionalAxe", na,
       [](VirtContext v) { return virtSetArticularPositionOfAdditionalAxe(v, f); }},
      {"virtSetArticularSpeedOfAdditionalAxe", na,
       [](VirtContext v) { return virtSetArticularSpeedOfAdditionalAxe(v, f); }},
      {"virtSetArticularForceOfAdditionalAxe", na,
       [](VirtContext v) { return virtSetArticularForceOfAdditionalAxe(v, f); }},
      {"virtSetFingerTipSpeed", na, [](VirtContext v) { return virtSetFingerTipSpeed(v, f); }},
      {"virtSetGripperCommandType", na,
       [](VirtContext v) { return virtSetGripperCommandType(v, GRIPPER_COMMAND_TYPE_POSITION); }},
      {"virtGetDeviceID", na, [](VirtContext v) { return virtGetDeviceID(v, &i, &i); }},
      {"virtGetFailure", na, [](VirtContext v) { return virtGetFailure(v, &u); }},
      // Haption's library's exports beyond its header (J6).
      {"virtSetFrictionForce", ni, [](VirtContext v) { return virtSetFrictionForce(v, 1, 0, 0); }},
      {"virtVmSetMinArtiBounds", ni, [](VirtContext v) { return virtVmSetMinArtiBounds(v, f); }},
      {"virtVmSetMaxArtiBounds", ni, [](VirtContext v) { return virtVmSetMaxArtiBounds(v, f); }},
      {"virtGetAvatarFrame", ni, [](VirtContext v) { return virtGetAvatarFrame(v, f); }},
      {"virtSetAvatarFrame", ni, [](VirtContext v) { return virtSetAvatarFrame(v, f); }},
      {"virtGetLimitTorque", ni, [](VirtContext v) { return virtGetLimitTorque(v, f); }},
      {"virtSetLimitTorque", ni, [](VirtContext v) { return virtSetLimitTorque(v, 1); }},
      {"virtSetAbsolutePosition", ni, [](VirtContext v) { return virtSetAbsolutePosition(v, f); }},
      {"virtBeepOnLimit", na, [](VirtContext v) { return virtBeepOnLimit(v, 1); }},
      {"virtGenerateDebugFile", ni, [](VirtContext v) { return virtGenerateDebugFile(v); }},
      {"virtActiveSpeedControl", ni,
       [](VirtContext v) { return virtActiveSpeedControl(v, 0.1F, 1.0F); }},
      {"virtActiveRotationSpeedControl", ni,
       [](VirtContext v) { return virtActiveRotationSpeedControl(v, 0.1F, 1.0F); }},
      {"virtDeactiveSpeedControl", ni, [](VirtContext v) { return virtDeactiveSpeedControl(v); }},
      {"virtDeactiveRotationSpeedControl", ni,
       [](VirtContext v) { return virtDeactiveRotationSpeedControl(v); }},
      {"virtIsInSpeedControl", ni, [](VirtContext v) { return virtIsInSpeedControl(v, &i, &i); }},
      {"virtSetForceInSpeedControl", ni,
       [](VirtContext v) { return virtSetForceInSpeedControl(v, 1.0F); }},
      {"virtSetTorqueInSpeedControl", ni,
       [](VirtContext v) { return virtSetTorqueInSpeedControl(v, 1.0F); }},
      {"virtGetCenterSphere", ni, [](VirtContext v) { return virtGetCenterSphere(v, f); }},
      {"virtGetAxisOfRotation", ni, [](VirtContext v) { return virtGetAxisOfRotation(v, f); }},
      {"virtSetTexture", ni, [](VirtContext v) { return virtSetTexture(v, f, f, 0); }},
      {"virtSetTextureForce", ni, [](VirtContext v) { return virtSetTextureForce(v, f); }},
      {"virtTrajRecordStart", ni, [](VirtContext v) { return virtTrajRecordStart(v); }},
      {"virtTrajRecordStop", ni, [](VirtContext v) { return virtTrajRecordStop(v); }},
      {"virtTrajSetSamplingTimeStep", ni,
       [](VirtContext v) { return virtTrajSetSamplingTimeStep(v, 0.01F, &u); }},
      {"virtVmStartTrajSampling", ni, [](VirtContext v) { return virtVmStartTrajSampling(v, 10); }},
      {"virtVmGetTrajSamples", ni, [](VirtContext v) { return virtVmGetTrajSamples(v, f); }},
      {"virtVmSetType", ni, [](VirtContext v) { return virtVmSetType(v, VM_TYPE_Rx); }},
      {"virtVmActivate", ni, [](VirtContext v) { return virtVmActivate(v); }},
      {"virtVmDeactivate", ni, [](VirtContext v) { return virtVmDeactivate(v); }},
      {"virtVmSetBaseFrame", ni, [](VirtContext v) { return virtVmSetBaseFrame(v, f); }},
      {"virtVmGetBaseFrame", ni, [](VirtContext v) { return virtVmGetBaseFrame(v, f); }},
      {"virtVmSetBaseFrameToCurrentFrame", ni,
       [](VirtContext v) { return virtVmSetBaseFrameToCurrentFrame(v); }},
      {"virtVmSetDefaultToCartesianPosition", ni,
       [](VirtContext v) { return virtVmSetDefaultToCartesianPosition(v); }},
      {"virtVmSetDefaultToTransparentMode", ni,
       [](VirtContext v) { return virtVmSetDefaultToTransparentMode(v); }},
      {"virtVmSetRobotMode", ni, [](VirtContext v) { return virtVmSetRobotMode(v, 1); }},
      {"virtVmWaitUpperBound", ni, [](VirtContext v) { return virtVmWaitUpperBound(v); }},
      {"virtVmLoadSpline", ni, [](VirtContext v) { return virtVmLoadSpline(v, file); }},
      {"virtVmSaveCurrentSpline", ni,
       [](VirtContext v) { return virtVmSaveCurrentSpline(v, file); }},
      {"virtVmDeleteSpline", ni, [](VirtContext v) { return virtVmDeleteSpline(v, file); }},
      {"virtSetCatchFrame", ni, [](VirtContext v) { return virtSetCatchFrame(v, f); }},
      {"virtGetCatchFrame", ni, [](VirtContext v) { return virtGetCatchFrame(v, f); }},
      {"virtSetObservationFrameSpeed", ni,
       [](VirtContext v) { return virtSetObservationFrameSpeed(v, f); }},
      {"virtDisableControlConnexion", ni,
       [](VirtContext v) { return virtDisableControlConnexion(v, 1); }},
  };
}

TEST(VirtuoseUnavailable, EachFailsWithItsCodeAndSaysWhyAndAnInvalidContextIsSaidFirst) {
  ControllerStack stack("capiunavailable");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  for (const Case& c : cases()) {
    EXPECT_EQ(c.call(vc.get()), -1) << c.name;
    EXPECT_EQ(virtGetErrorCode(vc.get()), c.code) << c.name;
    const std::string detail = virtGetErrorDetail(vc.get());
    EXPECT_EQ(detail.rfind(std::string(c.name) + ": ", 0), 0U) << detail;
    EXPECT_GT(detail.size(), std::string(c.name).size() + 20) << "says why: " << detail;
    EXPECT_EQ(c.call(nullptr), -1) << c.name;
    EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INVALID_CONTEXT) << c.name;
  }
  int pressed = 7;
  int translation = 7;
  int rotation = 7;
  EXPECT_EQ(virtGetButton(vc.get(), 0, &pressed), -1);
  EXPECT_EQ(pressed, 0) << "an application ignoring the error reads nothing pressed";
  EXPECT_EQ(virtIsInSpeedControl(vc.get(), &translation, &rotation), -1);
  EXPECT_EQ(translation + rotation, 0) << "speed control is never active";
  float frame[7] = {1, 1, 1, 1, 1, 1, 1};  // NOLINT(*-avoid-c-arrays)
  EXPECT_EQ(virtGetCatchFrame(vc.get(), frame), -1);
  EXPECT_EQ(frame[6], 0.0F);
}

}  // namespace
}  // namespace hapticctrl
