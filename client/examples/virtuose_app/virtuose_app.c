/* A Virtuose application as its authors write them: only VirtuoseAPI 4.x's names, types and
 * values (no hapticctrl extension). The install test builds it against the installed package,
 * with find_package and with pkg-config, and runs it against the real controller:
 *   virtuose_app host#port
 * Exit 0 with "virtuose_app: ok" when every check held; 1 naming the first that did not. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "VirtuoseAPI.h"

static VirtContext vc = NULL;
static int checks = 0;

static int check(int ok, const char* what) {
  ++checks;
  if (!ok) {
    int code = virtGetErrorCode(vc);
    fprintf(stderr, "virtuose_app: %s failed (error %d: %s)\n", what, code,
            virtGetErrorMessage(code));
  }
  return ok;
}

static void sleep_ms(long ms) {
  struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&t, NULL);
}

struct loop_state {
  int calls;
  int failures;
};

/* The application's simulation step: the object follows the avatar, and reads its force. */
static void step(VirtContext context, void* arg) {
  struct loop_state* s = (struct loop_state*)arg;
  float pose[7];
  float force[6];
  ++s->calls;
  if (virtGetAvatarPosition(context, pose) != 0 || virtSetPosition(context, pose) != 0 ||
      virtGetForce(context, force) != 0) {
    ++s->failures;
  }
}

static int run(const char* address) {
  int major = 0, minor = 0, value = 0;
  float pose[7], physical[7], frame[7] = {0.1f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};
  float step_s = 0.0f, factor = 0.0f, period = 0.002f;
  float k[6] = {10, 10, 10, 1000, 1000, 1000}, b[6] = {0.1f, 0.1f, 0.1f, 10, 10, 10};
  VirtIndexingType indexing = INDEXING_ALL;
  VirtCommandType type = COMMAND_TYPE_NONE;
  struct loop_state loop = {0, 0};
  char output[] = "/dev/null";

  if (!check(virtAPIVersion(&major, &minor) == 0 && major == 4, "virtAPIVersion"))
    return 1;
  vc = virtOpen(address);
  if (!check(vc != NULL, "virtOpen"))
    return 1;
  /* The first pose is the handle's, at once. */
  if (!check(virtGetPosition(vc, pose) == 0, "virtGetPosition"))
    return 1;
  if (!check(fabsf(pose[3] * pose[3] + pose[4] * pose[4] + pose[5] * pose[5] + pose[6] * pose[6] -
                   1.0f) < 1e-4f &&
                 sqrtf(pose[0] * pose[0] + pose[1] * pose[1] + pose[2] * pose[2]) > 0.05f,
             "the first pose is the handle's"))
    return 1;
  if (!check(virtGetEmergencyStop(vc, &value) == 0 && value == 1,
             "virtGetEmergencyStop reads 1 while operational"))
    return 1;
  /* Setters, then getters. */
  if (!check(
          virtSetTimeStep(vc, 0.002f) == 0 && virtGetTimeStep(vc, &step_s) == 0 && step_s == 0.002f,
          "virtSetTimeStep / virtGetTimeStep"))
    return 1;
  if (!check(virtSetIndexingMode(vc, INDEXING_TRANS) == 0 &&
                 virtGetIndexingMode(vc, &indexing) == 0 && indexing == INDEXING_TRANS,
             "virtSetIndexingMode / virtGetIndexingMode"))
    return 1;
  if (!check(virtSetForceFactor(vc, 0.5f) == 0 && virtGetForceFactor(vc, &factor) == 0 &&
                 factor == 0.5f && virtSetForceFactor(vc, 1.0f) == 0,
             "virtSetForceFactor / virtGetForceFactor"))
    return 1;
  if (!check(virtSetObservationFrame(vc, frame) == 0 && virtGetObservationFrame(vc, pose) == 0 &&
                 pose[0] == 0.1f,
             "virtSetObservationFrame / virtGetObservationFrame"))
    return 1;
  if (!check(virtSetCommandType(vc, COMMAND_TYPE_VIRTMECH) == 0 &&
                 virtGetCommandType(vc, &type) == 0 && type == COMMAND_TYPE_VIRTMECH,
             "virtSetCommandType / virtGetCommandType"))
    return 1;
  if (!check(virtSetOutputFile(vc, output) == 0 &&
                 virtSetDebugFlags(vc, DEBUG_SERVO | DEBUG_LOOP) == 0,
             "virtSetOutputFile, virtSetDebugFlags"))
    return 1;
  if (!check(virtEnableForceFeedback(vc, 1) == 0, "virtEnableForceFeedback"))
    return 1;
  if (!check(virtAttachQSVO(vc, k, b) == 0, "virtAttachQSVO"))
    return 1;
  if (!check(virtGetPhysicalPosition(vc, physical) == 0 && virtGetAvatarPosition(vc, pose) == 0 &&
                 fabsf(physical[0] - pose[0]) < 1e-3f,
             "virtGetPhysicalPosition and virtGetAvatarPosition agree before any shift"))
    return 1;
  if (!check(virtIsInShiftPosition(vc, &value) == 0 && value == 0, "virtIsInShiftPosition"))
    return 1;
  if (!check(virtGetButton(vc, 1, &value) == -1 &&
                 virtGetErrorCode(vc) == VIRT_E_VARIABLE_NOT_AVAILABLE,
             "virtGetButton says the variable is not available"))
    return 1;
  if (!check(virtSetPosition(vc, pose) == 0, "virtSetPosition"))
    return 1;
  if (!check(virtSetPowerOn(vc, 1) == 0 && virtGetPowerOn(vc, &value) == 0 && value == 1,
             "virtSetPowerOn / virtGetPowerOn"))
    return 1;
  if (!check(virtSetPeriodicFunction(vc, step, &period, &loop) == 0 && virtStartLoop(vc) == 0,
             "virtSetPeriodicFunction, virtStartLoop"))
    return 1;
  sleep_ms(400);
  if (!check(virtStopLoop(vc) == 0 && loop.calls > 50 && loop.failures == 0,
             "the periodic function ran every 2 ms"))
    return 1;
  if (!check(virtSetPowerOn(vc, 0) == 0 && virtClose(vc) == 0, "virtSetPowerOn(0), virtClose"))
    return 1;
  if (!check(virtGetPowerOn(vc, &value) == -1 && virtGetErrorCode(vc) == VIRT_E_INVALID_CONTEXT,
             "a closed context is refused"))
    return 1;
  printf("virtuose_app: ok, %d checks, %d periodic calls\n", checks, loop.calls);
  return 0;
}

int main(int argc, char** argv) {
  return run(argc > 1 ? argv[1] : "127.0.0.1#5125");
}
