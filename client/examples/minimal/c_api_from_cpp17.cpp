// The C API from a C++17 application: hapticctrl::client must not raise its C++ standard (it
// used to impose C++20 on every consumer). Prints the message of an error code and exits.
#include <hapticctrl/virtuose_api.h>

#include <cstdio>

static_assert(__cplusplus == 201703L, "linking hapticctrl::client changed the C++ standard");

int main() {
  std::printf("%s\n", virtGetErrorMessage(0));
  return 0;
}
