// The C API's functions without a meaning here: hardware the simulated arm has not
// (VIRT_E_VARIABLE_NOT_AVAILABLE, outputs zeroed so that an application ignoring the error reads
// "nothing pressed, nothing measured") and features the controller has not
// (VIRT_E_NOT_IMPLEMENTED). A closed or foreign context still gives VIRT_E_INVALID_CONTEXT.
#include <array>
#include <cstdio>

#include "virtuose_context.hpp"

using hapticctrl::client::virtuose::context_of;
using hapticctrl::client::virtuose::fail;

namespace {

constexpr const char* kNoButtons = "the simulated arm has no buttons";
constexpr const char* kNoDeadMan = "the simulated arm has no dead-man sensor";
constexpr const char* kNoIo = "the simulated arm has no analog or digital inputs and outputs";
constexpr const char* kNoMouse = "the simulated arm has no mouse mode or trackball";
constexpr const char* kNoAxes = "the simulated arm has no additional axes";
constexpr const char* kNoGripper = "the simulated arm has no gripper";
constexpr const char* kNoIdentity = "the controller does not report a device type or serial number";
constexpr const char* kNoFailures =
    "the controller reports arm faults as a fail-safe, not per motor";
constexpr const char* kNoSpeedControl = "speed control is not implemented by hapticctrl";
constexpr const char* kNoTexture = "textures are not implemented by hapticctrl";
constexpr const char* kNoTrajectory = "trajectory recording is not implemented by hapticctrl";
constexpr const char* kNoVm = "virtual mechanisms are not implemented by hapticctrl";
constexpr const char* kNoCatchFrame = "the catch frame is the arm model's handle point";
constexpr const char* kNoFrameSpeed = "the observation frame does not move";
constexpr const char* kOneSession = "one session controls the arm: no observation-only session";
constexpr const char* kNoFriction =
    "articular friction compensation is not implemented by hapticctrl";
constexpr const char* kNoAvatarFrame =
    "the avatar is the handle through the indexing offset; no avatar frame";
constexpr const char* kNoLimitTorque =
    "torque limits are set with virtSaturateTorque (force and moment thresholds)";
constexpr const char* kNoAbsolutePosition = "the arm is moved by its operator, not to a position";
constexpr const char* kNoBeeper = "the simulated arm has no beeper";
constexpr const char* kNoDebugFile =
    "no debug file: virtSetOutputFile with DEBUG_SERVO or DEBUG_LOOP, or virtDisplayHardwareStatus";

/// Zeroes the outputs, then fails with `code`: VIRT_E_INVALID_CONTEXT first if `vc` is not live.
/// The detail is "<function>: <why>".
template <typename... Out>
int without(const char* function, VirtContext vc, int code, const char* why,
            Out*... outputs) noexcept {
  ((outputs != nullptr ? void(*outputs = Out{}) : void()), ...);
  if (context_of(vc) == nullptr) {
    return -1;
  }
  std::array<char, hapticctrl::client::virtuose::ErrorState::kDetailBytes> detail{};
  std::snprintf(detail.data(), detail.size(), "%s: %s", function, why);
  return fail(vc, code, detail.data());
}

/// The same for an array output of `n` floats.
int without_array(const char* function, VirtContext vc, int code, const char* why, float* out,
                  int n) noexcept {
  for (int i = 0; out != nullptr && i < n; ++i) {
    out[i] = 0.0F;
  }
  return without(function, vc, code, why);
}

constexpr int kNa = VIRT_E_VARIABLE_NOT_AVAILABLE;
constexpr int kNi = VIRT_E_NOT_IMPLEMENTED;

}  // namespace

extern "C" {
// NOLINTBEGIN(readability-identifier-naming,misc-unused-parameters): VirtuoseAPI's names

int virtGetButton(VirtContext VC, int, int* state) {
  return without(__func__, VC, kNa, kNoButtons, state);
}
int virtWaitPressButton(VirtContext VC, int) {
  return without(__func__, VC, kNa, kNoButtons);
}
int virtGetDeadMan(VirtContext VC, int* dead_man) {
  return without(__func__, VC, kNa, kNoDeadMan, dead_man);
}
int virtGetADC(VirtContext VC, int, float* adc) {
  return without(__func__, VC, kNa, kNoIo, adc);
}
int virtGetAnalogicInputs(VirtContext VC, float*) {
  return without(__func__, VC, kNa, kNoIo);
}
int virtGetTorInputs(VirtContext VC, unsigned int* tor_in) {
  return without(__func__, VC, kNa, kNoIo, tor_in);
}
int virtOutputsSetting(VirtContext VC, unsigned int) {
  return without(__func__, VC, kNa, kNoIo);
}
int virtSetPwmOutput(VirtContext VC, float*) {
  return without(__func__, VC, kNa, kNoIo);
}
int virtGetMouseState(VirtContext VC, int* actif, int* clic_gauche, int* clic_droit) {
  return without(__func__, VC, kNa, kNoMouse, actif, clic_gauche, clic_droit);
}
int virtGetTrackball(VirtContext VC, int* x_move, int* y_move) {
  return without(__func__, VC, kNa, kNoMouse, x_move, y_move);
}
int virtGetTrackballButton(VirtContext VC, int* actif, int* btn_gauche, int* btn_milieu,
                           int* btn_droit) {
  return without(__func__, VC, kNa, kNoMouse, actif, btn_gauche, btn_milieu, btn_droit);
}
int virtGetArticularPositionOfAdditionalAxe(VirtContext VC, float* pos) {
  return without(__func__, VC, kNa, kNoAxes, pos);
}
int virtGetArticularSpeedOfAdditionalAxe(VirtContext VC, float* speed) {
  return without(__func__, VC, kNa, kNoAxes, speed);
}
int virtSetArticularPositionOfAdditionalAxe(VirtContext VC, float*) {
  return without(__func__, VC, kNa, kNoAxes);
}
int virtSetArticularSpeedOfAdditionalAxe(VirtContext VC, float*) {
  return without(__func__, VC, kNa, kNoAxes);
}
int virtSetArticularForceOfAdditionalAxe(VirtContext VC, float*) {
  return without(__func__, VC, kNa, kNoAxes);
}
int virtSetFingerTipSpeed(VirtContext VC, float*) {
  return without(__func__, VC, kNa, kNoGripper);
}
int virtSetGripperCommandType(VirtContext VC, VirtGripperCommandType) {
  return without(__func__, VC, kNa, kNoGripper);
}
int virtGetDeviceID(VirtContext VC, int* device_type, int* serial_number) {
  return without(__func__, VC, kNa, kNoIdentity, device_type, serial_number);
}
int virtGetFailure(VirtContext VC, unsigned int* error) {
  return without(__func__, VC, kNa, kNoFailures, error);
}

int virtActiveSpeedControl(VirtContext VC, float, float) {
  return without(__func__, VC, kNi, kNoSpeedControl);
}
int virtActiveRotationSpeedControl(VirtContext VC, float, float) {
  return without(__func__, VC, kNi, kNoSpeedControl);
}
int virtDeactiveSpeedControl(VirtContext VC) {
  return without(__func__, VC, kNi, kNoSpeedControl);
}
int virtDeactiveRotationSpeedControl(VirtContext VC) {
  return without(__func__, VC, kNi, kNoSpeedControl);
}
int virtIsInSpeedControl(VirtContext VC, int* translation, int* rotation) {
  return without(__func__, VC, kNi, kNoSpeedControl, translation, rotation);
}
int virtSetForceInSpeedControl(VirtContext VC, float) {
  return without(__func__, VC, kNi, kNoSpeedControl);
}
int virtSetTorqueInSpeedControl(VirtContext VC, float) {
  return without(__func__, VC, kNi, kNoSpeedControl);
}
int virtGetCenterSphere(VirtContext VC, float* pos) {
  return without_array(__func__, VC, kNi, kNoSpeedControl, pos, 3);
}
int virtGetAxisOfRotation(VirtContext VC, float* axe) {
  return without_array(__func__, VC, kNi, kNoSpeedControl, axe, 3);
}
int virtSetTexture(VirtContext VC, float*, float*, int) {
  return without(__func__, VC, kNi, kNoTexture);
}
int virtSetTextureForce(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoTexture);
}
int virtTrajRecordStart(VirtContext VC) {
  return without(__func__, VC, kNi, kNoTrajectory);
}
int virtTrajRecordStop(VirtContext VC) {
  return without(__func__, VC, kNi, kNoTrajectory);
}
int virtTrajSetSamplingTimeStep(VirtContext VC, float, unsigned int* recordTime) {
  return without(__func__, VC, kNi, kNoTrajectory, recordTime);
}
int virtVmStartTrajSampling(VirtContext VC, unsigned int) {
  return without(__func__, VC, kNi, kNoTrajectory);
}
int virtVmGetTrajSamples(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoTrajectory);
}
int virtVmSetType(VirtContext VC, VirtVmType) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmActivate(VirtContext VC) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmDeactivate(VirtContext VC) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmSetBaseFrame(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmGetBaseFrame(VirtContext VC, float* base) {
  return without_array(__func__, VC, kNi, kNoVm, base, 7);
}
int virtVmSetBaseFrameToCurrentFrame(VirtContext VC) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmSetDefaultToCartesianPosition(VirtContext VC) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmSetDefaultToTransparentMode(VirtContext VC) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmSetRobotMode(VirtContext VC, int) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmWaitUpperBound(VirtContext VC) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmLoadSpline(VirtContext VC, char*) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmSaveCurrentSpline(VirtContext VC, char*) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmDeleteSpline(VirtContext VC, char*) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtSetCatchFrame(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoCatchFrame);
}
int virtGetCatchFrame(VirtContext VC, float* frame) {
  return without_array(__func__, VC, kNi, kNoCatchFrame, frame, 7);
}
int virtSetObservationFrameSpeed(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoFrameSpeed);
}
int virtDisableControlConnexion(VirtContext VC, int) {
  return without(__func__, VC, kNi, kOneSession);
}

// Haption's library's exports beyond its header (J6).
int virtSetFrictionForce(VirtContext VC, float, float, float) {
  return without(__func__, VC, kNi, kNoFriction);
}
int virtVmSetMinArtiBounds(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtVmSetMaxArtiBounds(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoVm);
}
int virtGetAvatarFrame(VirtContext VC, float* frame) {
  return without_array(__func__, VC, kNi, kNoAvatarFrame, frame, 7);
}
int virtSetAvatarFrame(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoAvatarFrame);
}
int virtGetLimitTorque(VirtContext VC, float* torque) {
  return without(__func__, VC, kNi, kNoLimitTorque, torque);
}
int virtSetLimitTorque(VirtContext VC, float) {
  return without(__func__, VC, kNi, kNoLimitTorque);
}
int virtSetAbsolutePosition(VirtContext VC, float*) {
  return without(__func__, VC, kNi, kNoAbsolutePosition);
}
int virtBeepOnLimit(VirtContext VC, int) {
  return without(__func__, VC, kNa, kNoBeeper);
}
int virtGenerateDebugFile(VirtContext VC) {
  return without(__func__, VC, kNi, kNoDebugFile);
}

// NOLINTEND(readability-identifier-naming,misc-unused-parameters)
}  // extern "C"
