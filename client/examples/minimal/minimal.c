/* The same with the VirtuoseAPI-style C API. Usage: minimal_c [host#port] */
#include "VirtuoseAPI.h" /* as a Virtuose application includes it */
#include <stdio.h>

int main(int argc, char** argv) {
  VirtContext vc = virtOpen(argc > 1 ? argv[1] : "127.0.0.1#5125");
  if (vc == NULL) {
    fprintf(stderr, "minimal_c: %s (%s)\n", virtGetErrorMessage(virtGetErrorCode(NULL)),
            virtGetErrorDetail(NULL));
    return 1;
  }
  float pose[7];
  int power = 0;
  if (virtSetCommandType(vc, COMMAND_TYPE_NONE) != 0 || virtGetPosition(vc, pose) != 0 ||
      virtGetPowerOn(vc, &power) != 0) {
    fprintf(stderr, "minimal_c: %s\n", virtGetErrorDetail(vc));
    virtClose(vc);
    return 1;
  }
  printf("handle at %.3f %.3f %.3f, power %d\n", pose[0], pose[1], pose[2], power);
  return virtClose(vc) == 0 ? 0 : 1;
}
