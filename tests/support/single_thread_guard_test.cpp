// The guard of single-threaded tests (single_thread_guard.cpp) fails a program at its first
// thread, whoever starts it: this program starts one through std::thread, and ctest expects the
// guard's message (tests/CMakeLists.txt).
#include <cstdio>
#include <thread>

int main() {
  std::thread worker([] {});
  worker.join();
  std::puts("the thread ran: the guard did not see it");
  return 0;
}
