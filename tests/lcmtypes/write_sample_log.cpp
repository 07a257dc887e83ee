// Writes tests/support/sample_log.hpp's log to the given path (for the Java decoding test).
#include <cstdio>
#include <exception>

#include "support/sample_log.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s LOG\n", argv[0]);
    return 64;
  }
  try {
    hapticctrl::test::write_sample_log(argv[1]);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
