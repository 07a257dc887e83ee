#ifndef HAPTICCTRL_VIRTUOSE_API_H
#define HAPTICCTRL_VIRTUOSE_API_H
/**
 * @file virtuose_api.h
 * hapticctrl's C API: every function, type and constant of Haption's VirtuoseAPI 4.x under its
 * names and numeric values, so that a Virtuose application builds against hapticctrl with
 * another include path and link line ("VirtuoseAPI.h" and "virtuoseAPI.h" include this file).
 * docs/virtuose_api.md gives each function's status and meaning here.
 *
 * Conventions: every int function returns 0 on success and -1 on error; the error then has a
 * code (virtGetErrorCode), a static text (virtGetErrorMessage) and, a hapticctrl extension, a
 * detailed one (virtGetErrorDetail). Poses are float[7] {x, y, z, qx, qy, qz, qw}, speeds and
 * forces float[6] {linear, angular}, SI units, in the application's environment frame.
 * Functions for hardware the simulated arm has not (buttons, dead-man, analog and digital I/O,
 * additional axes, gripper, trackball) fail with VIRT_E_VARIABLE_NOT_AVAILABLE and zero their
 * outputs; features the controller has not (speed control, articular and texture commands,
 * trajectories, virtual mechanisms, catch frame) fail with VIRT_E_NOT_IMPLEMENTED.
 *
 * Real-time contract: virtOpen, virtClose, virtSetPowerOn and every setter of a parameter (a
 * reliable exchange with the controller, bounded by the timeout) block; so do virtSetOutputFile
 * and virtDisplayHardwareStatus (file I/O). Every other function (the getters, virtSetPosition,
 * virtSetSpeed, virtSetForce, virtAddForce, virtForceShiftButton, the conversions) allocates
 * nothing and is safe in the application's cycle and its periodic function: the only lock they
 * take is the context registry's, which virtOpen and virtClose hold for one set insertion or
 * removal (it is what recognises a closed or foreign context).
 *
 * Differences from Haption's library: control frames carry either the object state (VIRTMECH)
 * or a wrench (IMPEDANCE), so virtAddForce needs COMMAND_TYPE_IMPEDANCE; the periodic function
 * is paced by the controller's answers (its period a multiple of the controller's cycle);
 * indexing is done in this library, shifted by virtForceShiftButton (the arm has no shift button).
 */
#include <stdio.h> /* FILE, for virtDisplayHardwareStatus */

#include "virtuose_types.h" /* the types and constants, beside this file */

#ifdef __cplusplus
extern "C" {
#endif

/* The names are VirtuoseAPI's, kept for source compatibility. */
/* NOLINTBEGIN(readability-identifier-naming,modernize-use-using) */

/* --- session ------------------------------------------------------------------------------- */

/** Opens a session: "udpxdr://host:port", "host#port" or "host". Returns once the controller's
 *  first answer has arrived (the getters then report the arm), NULL on failure (VIRT_E_TIME_OUT
 *  when no answer came within 2 s). Blocks. */
VirtContext virtOpen(const char* nom);
/** Stops the loop, says goodbye (acknowledged) and frees the context. Blocks. */
int virtClose(VirtContext VC);
/** The VirtuoseAPI level this library implements: 4.04 (major 4, minor 4). */
int virtAPIVersion(int* major, int* minor);
/** The controller's protocol version (major, minor), as its WELCOME said. */
int virtGetControlerVersion(VirtContext VC, int* major, int* minor);
/** The number of joints the controller's answers carry (6). */
int virtGetNbAxes(VirtContext VC, int* nbAxes);
/** Not available: the controller does not say the device's type and serial number. */
int virtGetDeviceID(VirtContext VC, int* device_type, int* serial_number);
/** Not implemented: one session controls the arm; there is no observation-only session. */
int virtDisableControlConnexion(VirtContext VC, int disable);

/* --- errors -------------------------------------------------------------------------------- */

/** The last error of `VC` (or, when VC is NULL, closed or unknown, the calling thread's: its
 *  last virtOpen or its call with an invalid context, VIRT_E_INVALID_CONTEXT). */
int virtGetErrorCode(VirtContext VC);
/** The same into `*error`; returns 0 for a live context. */
int virtGetError(VirtContext VC, int* error);
/** A static text for an error code. */
char* virtGetErrorMessage(int code);
/** hapticctrl extension: the detailed text of the last error (the controller's reason). */
const char* virtGetErrorDetail(VirtContext VC);

/* --- parameters: acknowledged by the controller; a getter after a successful setter returns
 * the new value. Before any setter: time step 0 (the controller's answers pace the
 * application), factors 1, INDEXING_ALL, identity frames, COMMAND_TYPE_NONE. ---------------- */

int virtSetTimeStep(VirtContext VC, float step);
int virtGetTimeStep(VirtContext VC, float* step);
int virtSetIndexingMode(VirtContext VC, VirtIndexingType indexing_mode);
int virtGetIndexingMode(VirtContext VC, VirtIndexingType* indexing_mode);
int virtSetForceFactor(VirtContext VC, float force_factor);
int virtGetForceFactor(VirtContext VC, float* force_factor);
int virtSetSpeedFactor(VirtContext VC, float speed_factor);
int virtGetSpeedFactor(VirtContext VC, float* speed_factor);
/** The arm's base in the environment frame. */
int virtSetBaseFrame(VirtContext VC, float* base);
int virtGetBaseFrame(VirtContext VC, float* base);
int virtSetObservationFrame(VirtContext VC, float* obs);
int virtGetObservationFrame(VirtContext VC, float* obs);
/** Not implemented: the observation frame does not move. */
int virtSetObservationFrameSpeed(VirtContext VC, float* speed);
int virtSetCommandType(VirtContext VC, VirtCommandType type);
int virtGetCommandType(VirtContext VC, VirtCommandType* type);
/** Not available: no gripper. */
int virtSetGripperCommandType(VirtContext VC, VirtGripperCommandType type);
/** The watchdog: the controller fades the coupling out when the application is silent this
 *  long. The getter gives the one in force (the bridge may cap what was asked). */
int virtSetTimeoutValue(VirtContext VC, float time_value);
int virtGetTimeoutValue(VirtContext VC, float* time_value);
/** Lower force [N] and torque [N.m] limits than the device's (0: the device's). */
int virtSaturateTorque(VirtContext VC, float forceThreshold, float momentThreshold);
/** Not implemented: the handle point is the arm model's. */
int virtSetCatchFrame(VirtContext VC, float* frame);
int virtGetCatchFrame(VirtContext VC, float* frame);
/** DEBUG_SERVO and/or DEBUG_LOOP lines to the output file; 0 stops them. */
int virtSetDebugFlags(VirtContext VC, unsigned short flag);
/** Where the debug lines go (appended); NULL: back to stderr. VIRT_E_FILE_NOT_FOUND if it
 *  cannot be opened. */
int virtSetOutputFile(VirtContext VC, char* name);

/* --- the virtual object (VIRTMECH) ---------------------------------------------------------- */

/** Couples the application's object, of this mass [kg] and principal inertia [kg.m^2]. */
int virtAttachVO(VirtContext VC, float mass, float* mxmymz);
/** The same: the object is coupled to the avatar (the handle as indexing moved it). */
int virtAttachVOAvatar(VirtContext VC, float mass, float* mxmymz);
/** A quasi-static object: no mass, coupled with stiffness Ks and damping Bs, each {rotation x3,
 *  translation x3} as VirtuoseAPI orders them. The coupling is isotropic: the smallest of each
 *  three is used, and the controller may lower it further to stay stable over the link. */
int virtAttachQSVO(VirtContext VC, float* Ks, float* Bs);
int virtDetachVO(VirtContext VC);
int virtDetachVOAvatar(VirtContext VC);
/** The coupling stiffness / damping in force, float[6] in virtAttachQSVO's order (0 while not
 *  coupled). */
int virtGetSimulationStiffness(VirtContext VC, float* stiffness);
int virtGetSimulationDamping(VirtContext VC, float* damping);

/* --- power ------------------------------------------------------------------------------------ */

/** Returns once the controller has switched the power (virtGetPowerOn then says so), or -1:
 *  VIRT_E_CONTROLLER_REFUSED while the emergency stop is latched, VIRT_E_TIME_OUT. Called from
 *  the periodic function it returns at the acknowledgement (the next answers show it). */
int virtSetPowerOn(VirtContext VC, int power);
int virtGetPowerOn(VirtContext VC, int* power);
/** As Haption's: 1 while the arm is operational (emergency stop not latched, controller
 *  answering), 0 otherwise. */
int virtGetEmergencyStop(VirtContext VC, int* emergency_stop);
/** 0: the application's forces are not rendered (zero wrench, or the object follows the
 *  handle); 1 (the default): they are. */
int virtEnableForceFeedback(VirtContext VC, int enable);

/* --- commands, per cycle -------------------------------------------------------------------- */

/** VIRTMECH: the virtual object's pose; sent at once (with the last speed) unless a loop runs,
 *  in which case it goes out after the periodic function returns. */
int virtSetPosition(VirtContext VC, float* pos);
/** VIRTMECH: the virtual object's speed, sent with the next position. */
int virtSetSpeed(VirtContext VC, float* speed);
/** IMPEDANCE: the wrench to render; sent at once unless a loop runs. */
int virtSetForce(VirtContext VC, float* force);
/** IMPEDANCE: adds to the wrench of this cycle. */
int virtAddForce(VirtContext VC, float* force);

/** Floats per contact in virtSetContacts. */
#define VIRT_CONTACT_FLOATS 11
/** Contacts virtSetContacts takes at most. */
#define VIRT_MAX_CONTACTS 8
/** hapticctrl extension (not Haption's; protocol 1.3, docs/virtuose_api.md): the contacts the
 *  virtual object (VIRTMECH) or the handle's point (IMPEDANCE) is in or near, which the
 *  controller renders on the handle in its servo cycle (stiff at any network delay). `count`
 *  contacts of VIRT_CONTACT_FLOATS floats each, environment frame as virtSetPosition's: point
 *  x y z (VIRTMECH: on the object; IMPEDANCE: where the handle's point meets the surface),
 *  unit normal x y z (the direction the surface pushes), signed gap along it (< 0
 *  penetrating), stiffness N/m (at most the controller's limit), damping N.s/m, static and
 *  dynamic friction coefficients. Sent with the next position or force; count 0 clears them.
 *  Call it every step the contacts change; a contact not refreshed within 30 ms fades out.
 *  VIRT_E_INCORRECT_VALUE for a value out of range, VIRT_E_INCOMPATIBLE_VERSION when the
 *  controller does not take contacts, VIRT_E_WRONG_MODE outside VIRTMECH and IMPEDANCE.
 *  Allocates nothing. */
int virtSetContacts(VirtContext VC, int count, float* contacts);

/* --- state, per cycle: the latest controller answer ----------------------------------------- */

/** The avatar: the handle as indexing moved it (virtForceShiftButton), environment frame. */
int virtGetPosition(VirtContext VC, float* pos);
int virtGetAvatarPosition(VirtContext VC, float* pos);
int virtGetSpeed(VirtContext VC, float* speed);
/** The handle itself, without indexing. */
int virtGetPhysicalPosition(VirtContext VC, float* pos);
int virtGetPhysicalSpeed(VirtContext VC, float* speed);
/** VIRTMECH: the wrench the coupling applies to the virtual object. */
int virtGetForce(VirtContext VC, float* force);
int virtGetArticularPosition(VirtContext VC, float* pos);
int virtGetArticularSpeed(VirtContext VC, float* speed);
/** Microseconds since the last controller answer arrived. */
int virtGetTimeLastUpdate(VirtContext VC, unsigned int* time);
/** VIRT_ALARM_SATURATE (the controller clipped the wrench in the last answer),
 *  VIRT_ALARM_CALLBACK_OVERRUN (the periodic function outlasted its period since the last
 *  call of virtGetAlarm). The simulated arm has no temperature, battery or position error. */
int virtGetAlarm(VirtContext VC, unsigned int* alarm);
/** Not available: the controller reports arm faults as a fail-safe, not per motor. */
int virtGetFailure(VirtContext VC, unsigned int* error);
/** VIRT_BOUND_* bits of the joints in their walls, from the controller's answer. */
int virtIsInBounds(VirtContext VC, unsigned int* bounds);
/** 1 while shifted (indexing under way), 0 otherwise. */
int virtIsInShiftPosition(VirtContext VC, int* decalage);
/** Presses (1) or releases (0) the shift: while pressed the avatar keeps still on the indexed
 *  axes (virtSetIndexingMode) and the handle moves freely; releasing keeps the new offset. */
int virtForceShiftButton(VirtContext VC, int forceShiftButton);
/** Writes the session's and the controller's state to `fichier`. Blocks (file I/O). */
int virtDisplayHardwareStatus(VirtContext VC, FILE* fichier);

/* --- the periodic function ------------------------------------------------------------------ */

/** The function runs after a controller answer, every `*period` seconds: the period is rounded to
 *  a multiple of the controller's cycle and written back. Not while the loop runs. */
int virtSetPeriodicFunction(VirtContext VC, void (*fn)(VirtContext, void*), float* period,
                            void* arg);
int virtStartLoop(VirtContext VC);
/** Not from inside the periodic function. */
int virtStopLoop(VirtContext VC);

/* --- conversions (no context needed: VC may be NULL) -------------------------------------- */

/** A pose d[7] to a homogeneous matrix m[16], row-major. */
int virtConvertDeplToHomogeneMatrix(VirtContext VC, float* d, float* m);
/** A homogeneous matrix m[16], row-major, to a pose d[7]. */
int virtConvertHomogeneMatrixToDepl(VirtContext VC, float* d, float* m);
/** rgb[3] in [0, 1] to its luma (Rec. 601 weights). */
int virtConvertRGBToGrayscale(VirtContext VC, float* rgb, float* gray);

/* --- not available on the simulated arm: VIRT_E_VARIABLE_NOT_AVAILABLE, outputs zeroed ------- */

int virtGetButton(VirtContext VC, int button_number, int* state);
int virtWaitPressButton(VirtContext VC, int button_number);
int virtGetDeadMan(VirtContext VC, int* dead_man);
int virtGetADC(VirtContext VC, int line, float* adc);
int virtGetAnalogicInputs(VirtContext VC, float* inputs);
int virtGetTorInputs(VirtContext VC, unsigned int* tor_in);
int virtOutputsSetting(VirtContext VC, unsigned int outputs);
int virtSetPwmOutput(VirtContext VC, float* pwm);
int virtGetMouseState(VirtContext VC, int* actif, int* clic_gauche, int* clic_droit);
int virtGetTrackball(VirtContext VC, int* x_move, int* y_move);
int virtGetTrackballButton(VirtContext VC, int* actif, int* btn_gauche, int* btn_milieu,
                           int* btn_droit);
int virtGetArticularPositionOfAdditionalAxe(VirtContext VC, float* pos);
int virtGetArticularSpeedOfAdditionalAxe(VirtContext VC, float* speed);
int virtSetArticularPositionOfAdditionalAxe(VirtContext VC, float* pos);
int virtSetArticularSpeedOfAdditionalAxe(VirtContext VC, float* speed);
int virtSetArticularForceOfAdditionalAxe(VirtContext VC, float* effort);
int virtSetFingerTipSpeed(VirtContext VC, float* speed);

/* --- not implemented by the controller: VIRT_E_NOT_IMPLEMENTED ------------------------------- */

int virtActiveSpeedControl(VirtContext VC, float radius, float speedFactor);
int virtActiveRotationSpeedControl(VirtContext VC, float angle, float speedFactor);
int virtDeactiveSpeedControl(VirtContext VC);
int virtDeactiveRotationSpeedControl(VirtContext VC);
/** Also sets both outputs to 0 (speed control is never active). */
int virtIsInSpeedControl(VirtContext VC, int* translation, int* rotation);
int virtSetForceInSpeedControl(VirtContext VC, float force);
int virtSetTorqueInSpeedControl(VirtContext VC, float torque);
int virtGetCenterSphere(VirtContext VC, float* pos);
int virtGetAxisOfRotation(VirtContext VC, float* axe);
int virtSetArticularPosition(VirtContext VC, float* pos);
int virtSetArticularSpeed(VirtContext VC, float* speed);
int virtSetArticularForce(VirtContext VC, float* force);
int virtSetTexture(VirtContext VC, float* position, float* intensite, int reinit);
int virtSetTextureForce(VirtContext VC, float* texture_force);
int virtTrajRecordStart(VirtContext VC);
int virtTrajRecordStop(VirtContext VC);
int virtTrajSetSamplingTimeStep(VirtContext VC, float timeStep, unsigned int* recordTime);
int virtVmStartTrajSampling(VirtContext VC, unsigned int nbSamples);
int virtVmGetTrajSamples(VirtContext VC, float* samples);
int virtVmSetType(VirtContext VC, VirtVmType type);
int virtVmActivate(VirtContext VC);
int virtVmDeactivate(VirtContext VC);
int virtVmSetBaseFrame(VirtContext VC, float* base);
int virtVmGetBaseFrame(VirtContext VC, float* base);
int virtVmSetBaseFrameToCurrentFrame(VirtContext VC);
int virtVmSetDefaultToCartesianPosition(VirtContext VC);
int virtVmSetDefaultToTransparentMode(VirtContext VC);
int virtVmSetRobotMode(VirtContext VC, int OnOff);
int virtVmWaitUpperBound(VirtContext VC);
int virtVmLoadSpline(VirtContext VC, char* file_name);
int virtVmSaveCurrentSpline(VirtContext VC, char* file_name);
int virtVmDeleteSpline(VirtContext VC, char* file_name);

/* Exported by Haption's library beyond what its header declares (J6), with the signatures
 * public wrappers of it call them with (virtGetNumberOfAxes's as virtGetNbAxes's): declared
 * here so that programs written against later headers link. virtGetNumberOfAxes is
 * implemented; the others fail as their neighbours do (docs/virtuose_api.md). */
int virtGetNumberOfAxes(VirtContext VC, int* nbAxes);
int virtSetFrictionForce(VirtContext VC, float fx, float fy, float fz);
int virtVmSetMinArtiBounds(VirtContext VC, float* bounds);
int virtVmSetMaxArtiBounds(VirtContext VC, float* bounds);
int virtGetAvatarFrame(VirtContext VC, float* frame);
int virtSetAvatarFrame(VirtContext VC, float* frame);
int virtGetLimitTorque(VirtContext VC, float* torque);
int virtSetLimitTorque(VirtContext VC, float torque);
int virtSetAbsolutePosition(VirtContext VC, float* pos);
int virtBeepOnLimit(VirtContext VC, int enable);
int virtGenerateDebugFile(VirtContext VC);

/* NOLINTEND(readability-identifier-naming,modernize-use-using) */

#ifdef __cplusplus
}
#endif
#endif /* HAPTICCTRL_VIRTUOSE_API_H */
