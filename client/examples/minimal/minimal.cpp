// Connects, reads one controller cycle, renders a light spring in IMPEDANCE for one second.
// Usage: minimal_cpp [udpxdr://host:port]
#include <hapticctrl/client/connection.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  namespace hc = hapticctrl::client;
  try {
    hc::Connection link(hc::Address::parse(argc > 1 ? argv[1] : "udpxdr://127.0.0.1:5125"));
    link.set_command_type(hc::CommandType::kImpedance);
    hc::StateSnapshot s;
    std::uint64_t cycle = 0;
    for (int i = 0; i < 1000 && link.wait_for_answer(cycle, std::chrono::milliseconds(100), s);
         ++i) {
      cycle = s.cycle;
      const double k = 50.0;  // N/m towards the handle's start pose
      link.send_wrench({-k * s.handle_pose[0], 0.0, 0.0, 0.0, 0.0, 0.0});
    }
    const hc::LinkStatistics st = link.statistics();
    std::printf("cycle %llu, round trip %.0f us (mean of %llu), answers lost %llu\n",
                static_cast<unsigned long long>(cycle), st.rtt_mean_us,
                static_cast<unsigned long long>(st.rtt_samples),
                static_cast<unsigned long long>(st.answers_lost));
    return 0;
  } catch (const hc::ClientError& e) {
    std::fprintf(stderr, "minimal_cpp: %s\n", e.what());
    return 1;
  }
}
