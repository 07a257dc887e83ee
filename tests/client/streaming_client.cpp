// A client process for the watchdog test: couples a virtual object 3 cm from the handle and
// streams its state on every answer until killed; prints "streaming" after 30 answers.
// A separate executable (not a fork of the test): sanitizer runtimes do not support starting
// threads in a child forked from a multi-threaded process.
// usage: hapticctrl-test-streaming-client PORT
#include <cstdio>
#include <string>

#include "hapticctrl/client/connection.hpp"

int main(int argc, char** argv) {
  namespace hc = hapticctrl::client;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s PORT\n", argv[0]);
    return 64;
  }
  try {
    hc::Connection c({"127.0.0.1", static_cast<std::uint16_t>(std::stoi(argv[1]))});
    c.set_command_type(hc::CommandType::kVirtmech);
    c.attach_object(0.5, {0.001, 0.001, 0.001});
    c.set_power(true);
    hc::StateSnapshot s;
    c.wait_for_answer(0, std::chrono::seconds(1), s);
    hc::Pose7 object = s.handle_pose;
    object[0] += 0.03;
    for (int i = 0; i < 1'000'000; ++i) {
      if (c.wait_for_answer(s.cycle, std::chrono::milliseconds(100), s)) {
        c.send_object_state(object, {});
        if (i == 30) {
          std::printf("streaming\n");
          std::fflush(stdout);
        }
      }
    }
    return 0;
  } catch (const hc::ClientError& e) {
    std::fprintf(stderr, "streaming client: %s\n", e.what());
    return 1;
  }
}
