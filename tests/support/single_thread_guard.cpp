/// @file single_thread_guard.cpp
/// Linked into every unit and sim test that its room does not list as starting threads
/// (hapticctrl_tests_start_threads in tests/CMakeLists.txt), in the plain build only. Such a test
/// is left out of the ThreadSanitizer build, which can only find a race between two threads of
/// one process; this definition of pthread_create, exported from the test's executable, takes
/// the place of the C library's for every caller (std::thread, a library's worker) and fails the
/// test on its first thread, so that the list cannot fall behind the code.
#include <pthread.h>
#include <unistd.h>

#include <cstdlib>
#include <string_view>

extern "C" int pthread_create(pthread_t* /*thread*/, const pthread_attr_t* /*attributes*/,
                              void* (* /*start*/)(void*), void* /*argument*/) {
  constexpr std::string_view kMessage =
      "single_thread_guard: this test started a thread, but its room's CMakeLists.txt does not "
      "list it in hapticctrl_tests_start_threads(), so ThreadSanitizer would never see it: list "
      "it there\n";
  [[maybe_unused]] const auto written = write(STDERR_FILENO, kMessage.data(), kMessage.size());
  std::_Exit(EXIT_FAILURE);  // no thread may start; nothing of the test's can be trusted to end
}
