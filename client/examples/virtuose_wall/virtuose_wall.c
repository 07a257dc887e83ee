/* A wall in the application, rendered as a force (COMMAND_TYPE_IMPEDANCE): the plane x = x0 +
 * 1 cm, x0 where the handle starts, pushing back along -x at 1000 N/m with 5 N.s/m of damping
 * while the handle is beyond it (docs/virtuose_api.md, "Frames, signs, orders and rates").
 *   virtuose_wall host#port [seconds]
 * Prints the deepest penetration and the force then; push the handle along +x meanwhile (the
 * panel's 1 and +, or hapticctrl-hmi force 3 0 0 0 0 0). Exit 0, or 1 naming what failed. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "VirtuoseAPI.h"

#define WALL_STIFFNESS 1000.0f /* N/m */
#define WALL_DAMPING 5.0f      /* N.s/m, only while inside */

struct wall {
  float x;           /* the plane, environment frame (m) */
  float deepest;     /* the deepest the handle went (m) */
  float force_there; /* the force rendered then (N, along x) */
  int failures;
};

/* Every 1 ms, right after the controller's answer: read the handle, set the force. */
static void step(VirtContext vc, void* arg) {
  struct wall* w = (struct wall*)arg;
  float pose[7];  /* x y z (m), then the orientation's quaternion qx qy qz qw: w last */
  float speed[6]; /* vx vy vz (m/s), wx wy wz (rad/s) */
  float force[6] = {0, 0, 0, 0, 0, 0}; /* fx fy fz (N), tx ty tz (N.m): on the hand */
  if (virtGetPosition(vc, pose) != 0 || virtGetSpeed(vc, speed) != 0) {
    ++w->failures;
    return;
  }
  const float depth = pose[0] - w->x;
  if (depth > 0.0f) {
    force[0] = -WALL_STIFFNESS * depth - WALL_DAMPING * speed[0]; /* -x: back out of the wall */
    if (force[0] > 0.0f)
      force[0] = 0.0f; /* a wall pushes, never pulls */
  }
  if (depth > w->deepest) {
    w->deepest = depth;
    w->force_there = force[0];
  }
  if (virtSetForce(vc, force) != 0)
    ++w->failures;
}

static int fail(VirtContext vc, const char* what) {
  fprintf(stderr, "virtuose_wall: %s: %s\n", what, virtGetErrorDetail(vc));
  if (vc != NULL)
    virtClose(vc);
  return 1;
}

int main(int argc, char** argv) {
  const double seconds = argc > 2 ? atof(argv[2]) : 10.0;
  struct wall w = {0, 0, 0, 0};
  float start[7], period = 0.001f;
  VirtContext vc = virtOpen(argc > 1 ? argv[1] : "127.0.0.1#5125");
  if (vc == NULL)
    return fail(NULL, "virtOpen");
  if (virtGetPosition(vc, start) != 0)
    return fail(vc, "virtGetPosition");
  w.x = start[0] + 0.01f;
  if (virtSetCommandType(vc, COMMAND_TYPE_IMPEDANCE) != 0)
    return fail(vc, "virtSetCommandType");
  if (virtSetPeriodicFunction(vc, step, &period, &w) != 0 || virtStartLoop(vc) != 0)
    return fail(vc, "the periodic function");
  if (virtSetPowerOn(vc, 1) != 0)
    return fail(vc, "virtSetPowerOn");
  printf("virtuose_wall: a wall at x = %.4f m, 1 cm ahead of the handle, for %.0f s\n", w.x,
         seconds);
  fflush(stdout);
  const struct timespec tick = {0, 100 * 1000 * 1000};
  for (double t = 0.0; t < seconds; t += 0.1)
    nanosleep(&tick, NULL);
  virtStopLoop(vc);
  virtSetPowerOn(vc, 0);
  virtClose(vc);
  printf("virtuose_wall: deepest %.2f mm into the wall, %.2f N rendered there, %d failed calls\n",
         w.deepest * 1000.0f, w.force_there, w.failures);
  return w.failures == 0 ? 0 : 1;
}
