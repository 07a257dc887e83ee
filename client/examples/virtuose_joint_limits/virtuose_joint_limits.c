/* Joint space as Virtuose applications use it (ViSP's testVirtuoseJointLimits is one): in
 * COMMAND_TYPE_ARTICULAR_IMPEDANCE the periodic function reads the joints' positions and speeds
 * and sets a torque per joint that drives one joint toward one of its limits, until
 * virtIsInBounds says the joint is there; then the other limit; then COMMAND_TYPE_ARTICULAR
 * takes the arm back to where it started, and the next joint goes. Nobody holds the handle.
 *   virtuose_joint_limits host#port
 * Prints one line per joint and limit. Exit 0 when every joint reached both limits, else 1
 * naming what failed (docs/control.md, "Joint space"). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "VirtuoseAPI.h"

#define JOINTS 6
#define PHASE_SECONDS 8.0 /* a joint gets this long to reach a limit, or to come back */

/* The torque that drives a joint: 0.8 of each joint's continuous torque (10, 10, 5, 1, 1, 1 N.m
 * on the simulated arm). */
static const float kDrive[JOINTS] = {8.0f, 8.0f, 4.0f, 0.8f, 0.8f, 0.8f};
/* virtIsInBounds' bits of each joint's lower and upper limit (J2 and J3 also stop at their
 * coupled limit, AXE_2_3). */
static const unsigned kLower[JOINTS] = {VIRT_BOUND_LEFT_AXE_1,
                                        VIRT_BOUND_INF_AXE_2 | VIRT_BOUND_INF_AXE_2_3,
                                        VIRT_BOUND_INF_AXE_3 | VIRT_BOUND_INF_AXE_2_3,
                                        VIRT_BOUND_LEFT_AXE_4,
                                        VIRT_BOUND_INF_AXE_5,
                                        VIRT_BOUND_LEFT_AXE_6};
static const unsigned kUpper[JOINTS] = {VIRT_BOUND_RIGHT_AXE_1,
                                        VIRT_BOUND_SUP_AXE_2 | VIRT_BOUND_SUP_AXE_2_3,
                                        VIRT_BOUND_SUP_AXE_3 | VIRT_BOUND_SUP_AXE_2_3,
                                        VIRT_BOUND_RIGHT_AXE_4,
                                        VIRT_BOUND_SUP_AXE_5,
                                        VIRT_BOUND_RIGHT_AXE_6};

/* Shared by main and the periodic function (the library's thread), under `lock`. */
struct state {
  pthread_mutex_t lock;
  int joint;         /* the joint driven, 0-5 */
  float sign;        /* +1: toward its upper limit, -1: its lower, 0: none (ARTICULAR) */
  unsigned bits;     /* virtIsInBounds at the last call */
  float q[JOINTS];   /* the last joint positions (rad) */
  float fastest;     /* the fastest joint speed seen in this phase (rad/s) */
  int fastest_joint; /* and which joint, 0-5 */
  int failures;
};

/* What the periodic function saw last. */
struct view {
  unsigned bits;
  float q[JOINTS];
  float fastest;
  int fastest_joint;
  int failures;
};

static struct view seen(struct state* s) {
  struct view v;
  pthread_mutex_lock(&s->lock);
  v.bits = s->bits;
  memcpy(v.q, s->q, sizeof v.q);
  v.fastest = s->fastest;
  v.fastest_joint = s->fastest_joint;
  v.failures = s->failures;
  pthread_mutex_unlock(&s->lock);
  return v;
}

static void set_drive(struct state* s, int joint, float sign) {
  pthread_mutex_lock(&s->lock);
  s->joint = joint;
  s->sign = sign;
  s->fastest = 0.0f;
  pthread_mutex_unlock(&s->lock);
}

static void step(VirtContext vc, void* arg) {
  struct state* s = (struct state*)arg;
  float q[JOINTS], qd[JOINTS], torque[JOINTS] = {0, 0, 0, 0, 0, 0};
  unsigned bits = 0;
  const int ok = virtGetArticularPosition(vc, q) == 0 && virtGetArticularSpeed(vc, qd) == 0 &&
                 virtIsInBounds(vc, &bits) == 0;
  pthread_mutex_lock(&s->lock);
  if (ok) {
    memcpy(s->q, q, sizeof q);
    s->bits = bits;
    for (int i = 0; i < JOINTS; ++i)
      if (fabsf(qd[i]) > s->fastest) {
        s->fastest = fabsf(qd[i]);
        s->fastest_joint = i;
      }
  } else {
    ++s->failures;
  }
  const float sign = s->sign;
  const int joint = s->joint;
  pthread_mutex_unlock(&s->lock);
  if (!ok || sign == 0.0f)
    return; /* ARTICULAR: main sets the positions */
  torque[joint] = sign * kDrive[joint];
  if (virtSetArticularForce(vc, torque) != 0) {
    pthread_mutex_lock(&s->lock);
    ++s->failures;
    pthread_mutex_unlock(&s->lock);
  }
}

static void sleep_ms(long ms) {
  const struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&t, NULL);
}

/* Drives `joint` toward one limit until its bound bit shows; returns the seconds it took, or -1. */
static double drive(struct state* s, int joint, float sign, unsigned bit) {
  set_drive(s, joint, sign);
  for (int t = 0; t < (int)(PHASE_SECONDS * 100); ++t) {
    sleep_ms(10);
    if ((seen(s).bits & bit) != 0)
      return t * 0.01;
  }
  return -1.0;
}

/* ARTICULAR back to `start`; 0 when every joint is within 0.05 rad of it. */
static int come_back(VirtContext vc, struct state* s, float* start) {
  float none[JOINTS] = {0, 0, 0, 0, 0, 0};
  set_drive(s, 0, 0.0f);
  if (virtSetCommandType(vc, COMMAND_TYPE_ARTICULAR) != 0 || virtSetArticularSpeed(vc, none) != 0)
    return -1;
  for (int t = 0; t < (int)(PHASE_SECONDS * 100); ++t) {
    virtSetArticularPosition(vc, start);
    sleep_ms(10);
    const struct view now = seen(s);
    float worst = 0.0f;
    for (int i = 0; i < JOINTS; ++i)
      if (fabsf(now.q[i] - start[i]) > worst)
        worst = fabsf(now.q[i] - start[i]);
    if (worst < 0.05f)
      return virtSetCommandType(vc, COMMAND_TYPE_ARTICULAR_IMPEDANCE);
  }
  return -1;
}

static int fail(VirtContext vc, const char* what) {
  fprintf(stderr, "virtuose_joint_limits: %s: %s\n", what, virtGetErrorDetail(vc));
  if (vc != NULL)
    virtClose(vc);
  return 1;
}

int main(int argc, char** argv) {
  struct state s;
  float start[JOINTS], period = 0.001f;
  memset(&s, 0, sizeof s);
  pthread_mutex_init(&s.lock, NULL);
  VirtContext vc = virtOpen(argc > 1 ? argv[1] : "127.0.0.1#5125");
  if (vc == NULL)
    return fail(NULL, "virtOpen");
  if (virtGetArticularPosition(vc, start) != 0)
    return fail(vc, "virtGetArticularPosition");
  if (virtSetCommandType(vc, COMMAND_TYPE_ARTICULAR_IMPEDANCE) != 0)
    return fail(vc, "virtSetCommandType");
  if (virtSetPeriodicFunction(vc, step, &period, &s) != 0 || virtStartLoop(vc) != 0)
    return fail(vc, "the periodic function");
  if (virtSetPowerOn(vc, 1) != 0)
    return fail(vc, "virtSetPowerOn");
  int missed = 0;
  for (int j = 0; j < JOINTS && seen(&s).failures == 0; ++j) {
    const double up = drive(&s, j, 1.0f, kUpper[j]);
    struct view now = seen(&s);
    printf("joint %d upper limit: %s after %.2f s at %.3f rad, fastest joint %d at %.2f rad/s\n",
           j + 1, up < 0 ? "NOT reached" : "reached", up < 0 ? PHASE_SECONDS : up, now.q[j],
           now.fastest_joint + 1, now.fastest);
    const double down = drive(&s, j, -1.0f, kLower[j]);
    now = seen(&s);
    printf("joint %d lower limit: %s after %.2f s at %.3f rad, fastest joint %d at %.2f rad/s\n",
           j + 1, down < 0 ? "NOT reached" : "reached", down < 0 ? PHASE_SECONDS : down, now.q[j],
           now.fastest_joint + 1, now.fastest);
    fflush(stdout);
    missed += (up < 0) + (down < 0);
    if (come_back(vc, &s, start) != 0) {
      virtStopLoop(vc);
      return fail(vc, "back to the start in COMMAND_TYPE_ARTICULAR");
    }
  }
  virtStopLoop(vc);
  virtSetPowerOn(vc, 0);
  virtClose(vc);
  const int failures = seen(&s).failures;
  printf("virtuose_joint_limits: %d of %d limits reached, %d failed calls\n", 2 * JOINTS - missed,
         2 * JOINTS, failures);
  return missed == 0 && failures == 0 ? 0 : 1;
}
