/* Every function, type and constant of VirtuoseAPI 4.x's public header, by its name and value,
 * as an application written for Haption's library uses them: compiled as C against
 * "VirtuoseAPI.h", so a missing declaration, a changed signature or a changed value fails the
 * build (H2). At run time, it checks that each function is there (not NULL) and counts them. */
#include <stddef.h>
#include <stdio.h>

#include "VirtuoseAPI.h"

/* Haption's values. */
/* VirtContext is an opaque pointer, as Haption's. */
_Static_assert(sizeof(VirtContext) == sizeof(void*), "VirtContext");
_Static_assert(COMMAND_TYPE_NONE == 0 && COMMAND_TYPE_IMPEDANCE == 3 &&
                   COMMAND_TYPE_VIRTMECH == 5 && COMMAND_TYPE_ARTICULAR == 6 &&
                   COMMAND_TYPE_ARTICULAR_IMPEDANCE == 7,
               "VirtCommandType");
_Static_assert(GRIPPER_COMMAND_TYPE_NONE == 0 && GRIPPER_COMMAND_TYPE_POSITION == 1 &&
                   GRIPPER_COMMAND_TYPE_IMPEDANCE == 2,
               "VirtGripperCommandType");
_Static_assert(INDEXING_ALL == 0 && INDEXING_TRANS == 1 && INDEXING_NONE == 2 &&
                   INDEXING_ALL_FORCE_FEEDBACK_INHIBITION == 3 &&
                   INDEXING_TRANS_FORCE_FEEDBACK_INHIBITION == 4 &&
                   INDEXING_ROT_FORCE_FEEDBACK_INHIBITION == 6 && INDEXING_ROT == 7,
               "VirtIndexingType");
_Static_assert(VM_TYPE_CartMotion == 0 && VM_TYPE_Spline == 1 && VM_TYPE_Rx == 2 &&
                   VM_TYPE_Tx == 3 && VM_TYPE_TxRx == 4 && VM_TYPE_TxTyTz == 5 &&
                   VM_TYPE_RxRyRz == 6 && VM_TYPE_TxTy == 7 && VM_TYPE_Crank == 8,
               "VirtVmType");
_Static_assert(DEBUG_SERVO == 1 && DEBUG_LOOP == 2, "DEBUG_*");
_Static_assert(VIRT_E_NO_ERROR == 0 && VIRT_E_OUT_OF_MEMORY == 1 &&
                   VIRT_E_COMMUNICATION_FAILURE == 2 && VIRT_E_INVALID_CONTEXT == 3 &&
                   VIRT_E_FILE_NOT_FOUND == 4 && VIRT_E_WRONG_FORMAT == 5 && VIRT_E_TIME_OUT == 6 &&
                   VIRT_E_NOT_IMPLEMENTED == 7 && VIRT_E_VARIABLE_NOT_AVAILABLE == 8 &&
                   VIRT_E_INCORRECT_VALUE == 9 && VIRT_E_SYNTAX_ERROR == 10 &&
                   VIRT_E_HARDWARE_ERROR == 11 && VIRT_E_POSITION_DISCONTINUITY == 12 &&
                   VIRT_E_VIRTUOSE_DLL_NOT_FOUND == 13 && VIRT_E_PERIODIC_FUNCTION == 14 &&
                   VIRT_E_PERFORMANCE_COUNTER == 15 && VIRT_E_MAJOR_MINOR_VERSION == 16 &&
                   VIRT_E_WRONG_MODE == 17 && VIRT_E_MODE_NOT_SUPPORTED == 18 &&
                   VIRT_E_CALL_TIME == 19 && VIRT_E_INCOMPATIBLE_VERSION == 20 &&
                   VIRT_E_INCORRECT_VM_TYPE == 21 && VIRT_E_ALREADY_CALLED == 22,
               "VIRT_E_*");
_Static_assert(VIRT_BOUND_LEFT_AXE_1 == 0x1 && VIRT_BOUND_RIGHT_AXE_1 == 0x2 &&
                   VIRT_BOUND_SUP_AXE_2 == 0x4 && VIRT_BOUND_INF_AXE_2 == 0x8 &&
                   VIRT_BOUND_SUP_AXE_3 == 0x10 && VIRT_BOUND_INF_AXE_3 == 0x20 &&
                   VIRT_BOUND_RIGHT_AXE_4 == 0x40 && VIRT_BOUND_LEFT_AXE_4 == 0x80 &&
                   VIRT_BOUND_SUP_AXE_5 == 0x100 && VIRT_BOUND_INF_AXE_5 == 0x200 &&
                   VIRT_BOUND_LEFT_AXE_6 == 0x400 && VIRT_BOUND_RIGHT_AXE_6 == 0x800 &&
                   VIRT_BOUND_INF_AXE_2_3 == 0x1000 && VIRT_BOUND_SUP_AXE_2_3 == 0x2000,
               "VIRT_BOUND_*");
_Static_assert(VIRT_ALARM_OVERHEAT == 0x4000 && VIRT_ALARM_SATURATE == 0x8000 &&
                   VIRT_ALARM_CALLBACK_OVERRUN == 0x20000 && VIRT_ALARM_ERROR_POSITION == 0x40000 &&
                   VIRT_ALARM_LOW_BATTERY == 0x100000,
               "VIRT_ALARM_*");
_Static_assert(VIRT_BREAKDOWN_MOTOR_1 == 0x1 && VIRT_BREAKDOWN_MOTOR_2 == 0x2 &&
                   VIRT_BREAKDOWN_MOTOR_3 == 0x4 && VIRT_BREAKDOWN_MOTOR_4 == 0x8 &&
                   VIRT_BREAKDOWN_MOTOR_5 == 0x10 && VIRT_BREAKDOWN_MOTOR_6 == 0x20 &&
                   VIRT_BREAKDOWN_MOTOR_7 == 0x40 && VIRT_BREAKDOWN_MOTOR_8 == 0x80,
               "VIRT_BREAKDOWN_*");

/* Each function redeclared with the parameter types of Haption's 4.04 prototype: C refuses a
 * redeclaration whose type differs ("conflicting types"). */
#define VC VirtContext
int virtActiveRotationSpeedControl(VC, float, float);
int virtActiveSpeedControl(VC, float, float);
int virtAddForce(VC, float*);
int virtAPIVersion(int*, int*);
int virtAttachQSVO(VC, float*, float*);
int virtAttachVO(VC, float, float*);
int virtAttachVOAvatar(VC, float, float*);
int virtClose(VC);
int virtConvertDeplToHomogeneMatrix(VC, float*, float*);
int virtConvertHomogeneMatrixToDepl(VC, float*, float*);
int virtConvertRGBToGrayscale(VC, float*, float*);
int virtDeactiveRotationSpeedControl(VC);
int virtDeactiveSpeedControl(VC);
int virtDetachVO(VC);
int virtDetachVOAvatar(VC);
int virtDisableControlConnexion(VC, int);
int virtDisplayHardwareStatus(VC, FILE*);
int virtEnableForceFeedback(VC, int);
int virtForceShiftButton(VC, int);
int virtGetADC(VC, int, float*);
int virtGetAlarm(VC, unsigned int*);
int virtGetAnalogicInputs(VC, float*);
int virtGetArticularPosition(VC, float*);
int virtGetArticularPositionOfAdditionalAxe(VC, float*);
int virtGetArticularSpeed(VC, float*);
int virtGetArticularSpeedOfAdditionalAxe(VC, float*);
int virtGetAvatarPosition(VC, float*);
int virtGetAxisOfRotation(VC, float*);
int virtGetBaseFrame(VC, float*);
int virtGetButton(VC, int, int*);
int virtGetCatchFrame(VC, float*);
int virtGetCenterSphere(VC, float*);
int virtGetCommandType(VC, VirtCommandType*);
int virtGetControlerVersion(VC, int*, int*);
int virtGetDeadMan(VC, int*);
int virtGetDeviceID(VC, int*, int*);
int virtGetEmergencyStop(VC, int*);
int virtGetError(VC, int*);
int virtGetErrorCode(VC);
char* virtGetErrorMessage(int);
int virtGetFailure(VC, unsigned int*);
int virtGetForce(VC, float*);
int virtGetForceFactor(VC, float*);
int virtGetIndexingMode(VC, VirtIndexingType*);
int virtGetMouseState(VC, int*, int*, int*);
int virtGetObservationFrame(VC, float*);
int virtGetPhysicalPosition(VC, float*);
int virtGetPhysicalSpeed(VC, float*);
int virtGetPosition(VC, float*);
int virtGetPowerOn(VC, int*);
int virtGetSpeed(VC, float*);
int virtGetSpeedFactor(VC, float*);
int virtGetTimeLastUpdate(VC, unsigned int*);
int virtGetTimeoutValue(VC, float*);
int virtGetTimeStep(VC, float*);
int virtGetTorInputs(VC, unsigned int*);
int virtGetTrackball(VC, int*, int*);
int virtGetTrackballButton(VC, int*, int*, int*, int*);
int virtIsInBounds(VC, unsigned int*);
int virtIsInShiftPosition(VC, int*);
int virtIsInSpeedControl(VC, int*, int*);
VirtContext virtOpen(const char*);
int virtOutputsSetting(VC, unsigned int);
int virtSaturateTorque(VC, float, float);
int virtSetArticularForce(VC, float*);
int virtSetArticularForceOfAdditionalAxe(VC, float*);
int virtSetArticularPosition(VC, float*);
int virtSetArticularPositionOfAdditionalAxe(VC, float*);
int virtSetArticularSpeed(VC, float*);
int virtSetArticularSpeedOfAdditionalAxe(VC, float*);
int virtSetBaseFrame(VC, float*);
int virtSetCatchFrame(VC, float*);
int virtSetCommandType(VC, VirtCommandType);
int virtSetDebugFlags(VC, unsigned short);
int virtSetForce(VC, float*);
int virtSetForceFactor(VC, float);
int virtSetForceInSpeedControl(VC, float);
int virtSetGripperCommandType(VC, VirtGripperCommandType);
int virtSetIndexingMode(VC, VirtIndexingType);
int virtSetObservationFrame(VC, float*);
int virtSetObservationFrameSpeed(VC, float*);
int virtSetOutputFile(VC, char*);
int virtSetPeriodicFunction(VC, void (*)(VC, void*), float*, void*);
int virtSetPosition(VC, float*);
int virtSetPowerOn(VC, int);
int virtSetPwmOutput(VC, float*);
int virtSetSpeed(VC, float*);
int virtSetSpeedFactor(VC, float);
int virtSetTexture(VC, float*, float*, int);
int virtSetTextureForce(VC, float*);
int virtSetTimeoutValue(VC, float);
int virtSetTimeStep(VC, float);
int virtSetTorqueInSpeedControl(VC, float);
int virtStartLoop(VC);
int virtStopLoop(VC);
int virtTrajRecordStart(VC);
int virtTrajRecordStop(VC);
int virtTrajSetSamplingTimeStep(VC, float, unsigned int*);
int virtVmActivate(VC);
int virtVmDeactivate(VC);
int virtVmDeleteSpline(VC, char*);
int virtVmGetBaseFrame(VC, float*);
int virtVmGetTrajSamples(VC, float*);
int virtVmLoadSpline(VC, char*);
int virtVmSaveCurrentSpline(VC, char*);
int virtVmSetBaseFrame(VC, float*);
int virtVmSetBaseFrameToCurrentFrame(VC);
int virtVmSetDefaultToCartesianPosition(VC);
int virtVmSetDefaultToTransparentMode(VC);
int virtVmSetRobotMode(VC, int);
int virtVmSetType(VC, VirtVmType);
int virtVmStartTrajSampling(VC, unsigned int);
int virtVmWaitUpperBound(VC);
int virtWaitPressButton(VC, int);
int virtGetNbAxes(VC, int*);
int virtSetFingerTipSpeed(VC, float*);
int virtGetSimulationStiffness(VC, float*);
int virtGetSimulationDamping(VC, float*);
int virtGetNumberOfAxes(VC, int*);
int virtSetFrictionForce(VC, float, float, float);
int virtVmSetMinArtiBounds(VC, float*);
int virtVmSetMaxArtiBounds(VC, float*);
int virtGetAvatarFrame(VC, float*);
int virtSetAvatarFrame(VC, float*);
int virtGetLimitTorque(VC, float*);
int virtSetLimitTorque(VC, float);
int virtSetAbsolutePosition(VC, float*);
int virtBeepOnLimit(VC, int);
int virtGenerateDebugFile(VC);
#undef VC

typedef void (*any_function)(void);
#define F(name) (any_function) name
static const any_function functions[] = {
    F(virtActiveRotationSpeedControl), F(virtActiveSpeedControl), F(virtAddForce),
    F(virtAPIVersion), F(virtAttachQSVO), F(virtAttachVO), F(virtAttachVOAvatar), F(virtClose),
    F(virtConvertDeplToHomogeneMatrix), F(virtConvertHomogeneMatrixToDepl),
    F(virtConvertRGBToGrayscale), F(virtDeactiveRotationSpeedControl), F(virtDeactiveSpeedControl),
    F(virtDetachVO), F(virtDetachVOAvatar), F(virtDisableControlConnexion),
    F(virtDisplayHardwareStatus), F(virtEnableForceFeedback), F(virtForceShiftButton),
    F(virtGetADC), F(virtGetAlarm), F(virtGetAnalogicInputs), F(virtGetArticularPosition),
    F(virtGetArticularPositionOfAdditionalAxe), F(virtGetArticularSpeed),
    F(virtGetArticularSpeedOfAdditionalAxe), F(virtGetAvatarPosition), F(virtGetAxisOfRotation),
    F(virtGetBaseFrame), F(virtGetButton), F(virtGetCatchFrame), F(virtGetCenterSphere),
    F(virtGetCommandType), F(virtGetControlerVersion), F(virtGetDeadMan), F(virtGetDeviceID),
    F(virtGetEmergencyStop), F(virtGetError), F(virtGetErrorCode), F(virtGetErrorMessage),
    F(virtGetFailure), F(virtGetForce), F(virtGetForceFactor), F(virtGetIndexingMode),
    F(virtGetMouseState), F(virtGetObservationFrame), F(virtGetPhysicalPosition),
    F(virtGetPhysicalSpeed), F(virtGetPosition), F(virtGetPowerOn), F(virtGetSpeed),
    F(virtGetSpeedFactor), F(virtGetTimeLastUpdate), F(virtGetTimeoutValue), F(virtGetTimeStep),
    F(virtGetTorInputs), F(virtGetTrackball), F(virtGetTrackballButton), F(virtIsInBounds),
    F(virtIsInShiftPosition), F(virtIsInSpeedControl), F(virtOpen), F(virtOutputsSetting),
    F(virtSaturateTorque), F(virtSetArticularForce), F(virtSetArticularForceOfAdditionalAxe),
    F(virtSetArticularPosition), F(virtSetArticularPositionOfAdditionalAxe),
    F(virtSetArticularSpeed), F(virtSetArticularSpeedOfAdditionalAxe), F(virtSetBaseFrame),
    F(virtSetCatchFrame), F(virtSetCommandType), F(virtSetDebugFlags), F(virtSetForce),
    F(virtSetForceFactor), F(virtSetForceInSpeedControl), F(virtSetGripperCommandType),
    F(virtSetIndexingMode), F(virtSetObservationFrame), F(virtSetObservationFrameSpeed),
    F(virtSetOutputFile), F(virtSetPeriodicFunction), F(virtSetPosition), F(virtSetPowerOn),
    F(virtSetPwmOutput), F(virtSetSpeed), F(virtSetSpeedFactor), F(virtSetTexture),
    F(virtSetTextureForce), F(virtSetTimeoutValue), F(virtSetTimeStep),
    F(virtSetTorqueInSpeedControl), F(virtStartLoop), F(virtStopLoop), F(virtTrajRecordStart),
    F(virtTrajRecordStop), F(virtTrajSetSamplingTimeStep), F(virtVmActivate), F(virtVmDeactivate),
    F(virtVmDeleteSpline), F(virtVmGetBaseFrame), F(virtVmGetTrajSamples), F(virtVmLoadSpline),
    F(virtVmSaveCurrentSpline), F(virtVmSetBaseFrame), F(virtVmSetBaseFrameToCurrentFrame),
    F(virtVmSetDefaultToCartesianPosition), F(virtVmSetDefaultToTransparentMode),
    F(virtVmSetRobotMode), F(virtVmSetType), F(virtVmStartTrajSampling), F(virtVmWaitUpperBound),
    F(virtWaitPressButton), F(virtGetNbAxes), F(virtSetFingerTipSpeed),
    F(virtGetSimulationStiffness), F(virtGetSimulationDamping),
    /* The header's other names. */
    F(virtConvertDisplToTransformationMatrix), F(virtConvertTransformationMatrixToDispl),
    F(virtGetDigitalInputs),
    /* Haption's library's exports beyond its header (J6). */
    F(virtGetNumberOfAxes), F(virtSetFrictionForce), F(virtVmSetMinArtiBounds),
    F(virtVmSetMaxArtiBounds), F(virtGetAvatarFrame), F(virtSetAvatarFrame), F(virtGetLimitTorque),
    F(virtSetLimitTorque), F(virtSetAbsolutePosition), F(virtBeepOnLimit),
    F(virtGenerateDebugFile)};
#undef F

enum { kHaptionFunctions = 118, kOtherNames = 3, kUndocumentedExports = 11 };

int main(void) {
  const size_t n = sizeof functions / sizeof functions[0];
  VirtPeriodicFunction periodic = NULL;
  VirtContext context = NULL;
  (void)periodic;
  (void)context;
  for (size_t i = 0; i < n; ++i) {
    if (functions[i] == NULL) {
      fprintf(stderr, "function %zu is missing\n", i);
      return 1;
    }
  }
  if (n != kHaptionFunctions + kOtherNames + kUndocumentedExports) {
    fprintf(stderr,
            "%zu functions listed, VirtuoseAPI 4.04 has %d, %d other names and %d exports "
            "beyond its header\n",
            n, kHaptionFunctions, kOtherNames, kUndocumentedExports);
    return 1;
  }
  printf("VirtuoseAPI 4.04: %d functions, %d other names and %d further exports declared\n",
         kHaptionFunctions, kOtherNames, kUndocumentedExports);
  return 0;
}
