#ifndef HAPTICCTRL_VIRTUOSE_API_H
#define HAPTICCTRL_VIRTUOSE_API_H
/**
 * @file virtuose_api.h
 * A C API with the VirtuoseAPI calling conventions, so that existing Virtuose applications port
 * to hapticctrl with little change. Every function returns 0 on success and -1 on error (the
 * error then has a code, virtGetErrorCode(), and a detailed text, virtGetErrorDetail()).
 * Poses are float[7] {x, y, z, qx, qy, qz, qw}, speeds and forces float[6] {linear, angular},
 * SI units, in the environment (observation) frame.
 *
 * Real-time contract: virtOpen, virtClose and every virtSet* of a parameter block (a reliable
 * exchange with the controller, bounded by the timeout); virtGet*, virtSetPosition,
 * virtSetSpeed, virtSetForce and virtAddForce do not allocate and are safe in the application's
 * cycle: the only lock they take is the context registry's, which virtOpen and virtClose hold
 * for one set insertion or removal (it is what recognises a closed or foreign context).
 *
 * Differences from VirtuoseAPI: control frames carry either the object state (VIRTMECH) or a
 * wrench (IMPEDANCE), so virtAddForce needs COMMAND_TYPE_IMPEDANCE; the periodic function is
 * paced by the controller's answer stream (its period rounded to a multiple of the cycle).
 */
#ifdef __cplusplus
extern "C" {
#endif

/* The names are VirtuoseAPI's, kept for source compatibility. */
/* NOLINTBEGIN(readability-identifier-naming) */
typedef struct VirtContextS* VirtContext;

/* Command types, with VirtuoseAPI 4.x's values. hapticctrl's controller has NONE, IMPEDANCE
 * (the application sends a wrench) and VIRTMECH (it sends a virtual object's state); the others
 * are refused with VIRT_E_MODE_NOT_SUPPORTED. */
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

typedef enum {
  INDEXING_ALL = 0,
  INDEXING_TRANS = 1,
  INDEXING_NONE = 2,
  INDEXING_ALL_FORCE_FEEDBACK_INHIBITION = 3,
  INDEXING_TRANS_FORCE_FEEDBACK_INHIBITION = 4,
  INDEXING_NONE_FORCE_FEEDBACK_INHIBITION = 5
} VirtIndexingType;

/* Error codes, with VirtuoseAPI 4.x's names and values. */
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
/* hapticctrl's own, beyond VirtuoseAPI's range: another client holds the controller; the
 * controller refused a command (e.g. power on while the emergency stop is latched). */
#define VIRT_E_VIRTUOSE_BUSY 100
#define VIRT_E_CONTROLLER_REFUSED 101

/** Opens a session: "udpxdr://host:port", "host#port" or "host". Returns once the controller's
 *  first answer has arrived (the getters then report the arm), NULL on failure (VIRT_E_TIME_OUT
 *  when no answer came within 2 s). */
VirtContext virtOpen(const char* name);
int virtClose(VirtContext vc);

int virtSetTimeStep(VirtContext vc, float step);
int virtSetIndexingMode(VirtContext vc, VirtIndexingType mode);
int virtSetForceFactor(VirtContext vc, float factor);
int virtSetSpeedFactor(VirtContext vc, float factor);
int virtSetBaseFrame(VirtContext vc, float* pos);
int virtSetObservationFrame(VirtContext vc, float* pos);
int virtSetCommandType(VirtContext vc, VirtCommandType type);
int virtAttachVO(VirtContext vc, float mass, float* mxmymz);
int virtDetachVO(VirtContext vc);
/** Returns once the controller has switched the power (virtGetPowerOn then says so), or -1:
 *  VIRT_E_CONTROLLER_REFUSED while the emergency stop is latched, VIRT_E_TIME_OUT. Called from
 *  the periodic function it returns at the acknowledgement (the next answers show it). */
int virtSetPowerOn(VirtContext vc, int power);
int virtSetTimeoutValue(VirtContext vc, float seconds);
int virtSaturateTorque(VirtContext vc, float force_threshold, float moment_threshold);

/** VIRTMECH: the virtual object's pose; sent at once (with the last speed) unless a loop runs,
 *  in which case it goes out after the periodic function returns. */
int virtSetPosition(VirtContext vc, float* pos);
/** VIRTMECH: the virtual object's speed, sent with the next position. */
int virtSetSpeed(VirtContext vc, float* speed);
/** IMPEDANCE: the wrench to render; sent at once unless a loop runs. */
int virtSetForce(VirtContext vc, float* force);
/** IMPEDANCE: adds to the wrench of this cycle. */
int virtAddForce(VirtContext vc, float* force);

int virtGetPosition(VirtContext vc, float* pos);
int virtGetSpeed(VirtContext vc, float* speed);
int virtGetForce(VirtContext vc, float* force);
int virtGetArticularPosition(VirtContext vc, float* pos);
int virtGetArticularSpeed(VirtContext vc, float* speed);
int virtGetPowerOn(VirtContext vc, int* power);
/** As Haption's: 1 while the arm is operational (emergency stop not latched, controller
 *  answering), 0 otherwise. */
int virtGetEmergencyStop(VirtContext vc, int* emergency_stop);
/** Microseconds since the last controller answer arrived. */
int virtGetTimeLastUpdate(VirtContext vc, unsigned int* time);

/* The parameters as the controller acknowledged them: a getter right after a successful setter
 * returns the new value. Before any setter: time step 0 (the controller's answers pace the
 * application), factors 1, INDEXING_ALL, identity frames, COMMAND_TYPE_NONE. The timeout is the
 * watchdog in force (the bridge may cap what was asked). */
int virtGetTimeStep(VirtContext vc, float* step);
int virtGetIndexingMode(VirtContext vc, VirtIndexingType* indexing_mode);
int virtGetForceFactor(VirtContext vc, float* force_factor);
int virtGetSpeedFactor(VirtContext vc, float* speed_factor);
int virtGetBaseFrame(VirtContext vc, float* base);
int virtGetObservationFrame(VirtContext vc, float* obs);
int virtGetCommandType(VirtContext vc, VirtCommandType* type);
int virtGetTimeoutValue(VirtContext vc, float* time_value);
/** The controller's protocol version (major, minor), as its WELCOME said. */
int virtGetControlerVersion(VirtContext vc, int* major, int* minor);

/** The periodic function runs after each controller answer, every `*period` seconds. */
int virtSetPeriodicFunction(VirtContext vc, void (*fn)(VirtContext, void*), float* period,
                            void* arg);
int virtStartLoop(VirtContext vc);
/** Not from inside the periodic function. */
int virtStopLoop(VirtContext vc);

/** The last error of `vc` (or, when vc is NULL, closed or unknown, the calling thread's: its
 *  last virtOpen or its call with an invalid context, VIRT_E_INVALID_CONTEXT). */
int virtGetErrorCode(VirtContext vc);
/** A static text for an error code. */
char* virtGetErrorMessage(int code);
/** hapticctrl extension: the detailed text of the last error (the controller's reason). */
const char* virtGetErrorDetail(VirtContext vc);
/* NOLINTEND(readability-identifier-naming) */

#ifdef __cplusplus
}
#endif
#endif /* HAPTICCTRL_VIRTUOSE_API_H */
