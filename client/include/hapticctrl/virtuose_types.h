#ifndef HAPTICCTRL_VIRTUOSE_TYPES_H
#define HAPTICCTRL_VIRTUOSE_TYPES_H
/**
 * @file virtuose_types.h
 * The types and constants of hapticctrl's C API (virtuose_api.h, which includes this file):
 * VirtuoseAPI 4.x's under their names and numeric values. No function; nothing to link.
 */

#ifdef __cplusplus
extern "C" {
#endif

/* The names are VirtuoseAPI's, kept for source compatibility. */
/* NOLINTBEGIN(readability-identifier-naming,modernize-use-using) */

/** A session handle, as VirtuoseAPI's: an opaque pointer. A closed or foreign one is recognised
 *  (VIRT_E_INVALID_CONTEXT), never dereferenced. */
typedef void* VirtContext;
/** The periodic function: called with the context and the argument given to
 *  virtSetPeriodicFunction. */
typedef void (*VirtPeriodicFunction)(VirtContext, void*);

/** Command types, VirtuoseAPI's values. The controller has NONE, IMPEDANCE (the application sends
 *  a wrench) and VIRTMECH (it sends a virtual object's state); the others are refused with
 *  VIRT_E_MODE_NOT_SUPPORTED (JOINT, CARTESIAN and ADMITTANCE are 3.x's). */
typedef enum {
  COMMAND_TYPE_NONE = 0,
  COMMAND_TYPE_JOINT = 1,
  COMMAND_TYPE_CARTESIAN = 2,
  COMMAND_TYPE_IMPEDANCE = 3,
  COMMAND_TYPE_ADMITTANCE = 4,
  COMMAND_TYPE_VIRTMECH = 5,
  COMMAND_TYPE_ARTICULAR = 6,
  COMMAND_TYPE_ARTICULAR_IMPEDANCE = 7
} VirtCommandType;

/** Gripper command types (the simulated arm has no gripper: VIRT_E_VARIABLE_NOT_AVAILABLE). */
typedef enum {
  GRIPPER_COMMAND_TYPE_NONE = 0,
  GRIPPER_COMMAND_TYPE_POSITION = 1,
  GRIPPER_COMMAND_TYPE_IMPEDANCE = 2
} VirtGripperCommandType;

/** What a shift (virtForceShiftButton) indexes, and whether forces stop meanwhile. */
typedef enum {
  INDEXING_ALL = 0,
  INDEXING_TRANS = 1,
  INDEXING_NONE = 2,
  INDEXING_ALL_FORCE_FEEDBACK_INHIBITION = 3,
  INDEXING_TRANS_FORCE_FEEDBACK_INHIBITION = 4,
  INDEXING_ROT_FORCE_FEEDBACK_INHIBITION = 6,
  INDEXING_ROT = 7
} VirtIndexingType;

/** Virtual mechanism types (virtual mechanisms are not implemented). */
typedef enum {
  VM_TYPE_CartMotion = 0,
  VM_TYPE_Spline = 1,
  VM_TYPE_Rx = 2,
  VM_TYPE_Tx = 3,
  VM_TYPE_TxRx = 4,
  VM_TYPE_TxTyTz = 5,
  VM_TYPE_RxRyRz = 6,
  VM_TYPE_TxTy = 7,
  VM_TYPE_Crank = 8
} VirtVmType;

/* virtSetDebugFlags: what is written to the output file (virtSetOutputFile, else stderr). */
#define DEBUG_SERVO 0x0001 /**< one line per controller answer */
#define DEBUG_LOOP 0x0002  /**< one line per periodic function call */

/* Error codes, VirtuoseAPI's names and values. */
#define VIRT_E_NO_ERROR 0
#define VIRT_E_OUT_OF_MEMORY 1
#define VIRT_E_COMMUNICATION_FAILURE 2
#define VIRT_E_INVALID_CONTEXT 3
#define VIRT_E_FILE_NOT_FOUND 4
#define VIRT_E_WRONG_FORMAT 5
#define VIRT_E_TIME_OUT 6
#define VIRT_E_NOT_IMPLEMENTED 7
#define VIRT_E_VARIABLE_NOT_AVAILABLE 8
#define VIRT_E_INCORRECT_VALUE 9
#define VIRT_E_SYNTAX_ERROR 10
#define VIRT_E_HARDWARE_ERROR 11
#define VIRT_E_POSITION_DISCONTINUITY 12
#define VIRT_E_VIRTUOSE_DLL_NOT_FOUND 13
#define VIRT_E_PERIODIC_FUNCTION 14
#define VIRT_E_PERFORMANCE_COUNTER 15
#define VIRT_E_MAJOR_MINOR_VERSION 16
#define VIRT_E_WRONG_MODE 17
#define VIRT_E_MODE_NOT_SUPPORTED 18
#define VIRT_E_CALL_TIME 19
#define VIRT_E_INCOMPATIBLE_VERSION 20
#define VIRT_E_INCORRECT_VM_TYPE 21
#define VIRT_E_ALREADY_CALLED 22
/* hapticctrl's own, beyond VirtuoseAPI's range: another client holds the controller; the
 * controller refused a command (e.g. power on while the emergency stop is latched). */
#define VIRT_E_VIRTUOSE_BUSY 100
#define VIRT_E_CONTROLLER_REFUSED 101

/* virtIsInBounds: the joints in their walls (lower limit: LEFT or INF, upper: RIGHT or SUP). */
#define VIRT_BOUND_LEFT_AXE_1 0x0001
#define VIRT_BOUND_RIGHT_AXE_1 0x0002
#define VIRT_BOUND_SUP_AXE_2 0x0004
#define VIRT_BOUND_INF_AXE_2 0x0008
#define VIRT_BOUND_SUP_AXE_3 0x0010
#define VIRT_BOUND_INF_AXE_3 0x0020
#define VIRT_BOUND_RIGHT_AXE_4 0x0040
#define VIRT_BOUND_LEFT_AXE_4 0x0080
#define VIRT_BOUND_SUP_AXE_5 0x0100
#define VIRT_BOUND_INF_AXE_5 0x0200
#define VIRT_BOUND_LEFT_AXE_6 0x0400
#define VIRT_BOUND_RIGHT_AXE_6 0x0800
#define VIRT_BOUND_INF_AXE_2_3 0x1000
#define VIRT_BOUND_SUP_AXE_2_3 0x2000

/* virtGetAlarm. */
#define VIRT_ALARM_OVERHEAT 0x00004000
#define VIRT_ALARM_SATURATE 0x00008000
#define VIRT_ALARM_CALLBACK_OVERRUN 0x00020000
#define VIRT_ALARM_ERROR_POSITION 0x00040000
#define VIRT_ALARM_LOW_BATTERY 0x00100000

/* virtGetFailure (per-motor failures: not reported by the controller). */
#define VIRT_BREAKDOWN_MOTOR_1 0x0001
#define VIRT_BREAKDOWN_MOTOR_2 0x0002
#define VIRT_BREAKDOWN_MOTOR_3 0x0004
#define VIRT_BREAKDOWN_MOTOR_4 0x0008
#define VIRT_BREAKDOWN_MOTOR_5 0x0010
#define VIRT_BREAKDOWN_MOTOR_6 0x0020
#define VIRT_BREAKDOWN_MOTOR_7 0x0040
#define VIRT_BREAKDOWN_MOTOR_8 0x0080

/* VirtuoseAPI's other names of three functions. */
#define virtConvertDisplToTransformationMatrix virtConvertDeplToHomogeneMatrix
#define virtConvertTransformationMatrixToDispl virtConvertHomogeneMatrixToDepl
#define virtGetDigitalInputs virtGetTorInputs

/* NOLINTEND(readability-identifier-naming,modernize-use-using) */

#ifdef __cplusplus
}
#endif
#endif /* HAPTICCTRL_VIRTUOSE_TYPES_H */
