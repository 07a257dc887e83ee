// J1 end to end, IMPEDANCE clients (the mode most VirtuoseAPI applications use), through the
// real processes and hapticctrl-netem: a commanded wrench rendered as commanded on an unheld
// handle, and a wall the client computes (reported as a surface) stable at any delay.
//
// The core runs in benchmark mode as in coupling_network_test.cpp: a VM stall is ridden through
// and counted, and an attempt whose core stopped anyway is retried (with_retries).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "support/contact_scenarios.hpp"
#include "support/json_fields.hpp"
#include "support/network_scenario.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

class ImpedanceCommand : public ::testing::TestWithParam<double> {};

TEST_P(ImpedanceCommand, IsRenderedWithin2PercentOnAnUnheldHandle) {
  // An IMPEDANCE client (protocol 1.3: its wrench inside the two-port) commands a constant force
  // along -x on an unheld handle in free space: the core renders it whole (the one-port guard
  // took 11 % of 6 N and 44 % of 1 N, f3c5aec).
  const double push = GetParam();
  with_retries("impedance " + std::to_string(push), [&](int attempt) {
    const std::string script = testing::TempDir() + "push-" + std::to_string(attempt) + ".txt";
    { std::ofstream(script) << "0.5 push " << -push << " 0 0\n"; }
    Scenario s("j1-imp-" + std::to_string(attempt), {},
               {"--command", "impedance", "--gap", "0.3", "--script", script});
    if (!s.started()) {
      ADD_FAILURE() << "the stack did not start: " << s.diagnostics();
      return true;
    }
    std::this_thread::sleep_for(2500ms);
    std::remove(script.c_str());
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    // From 20 ms after the command arrives (the rate limit brings 6 N in 6 ms) to the
    // workspace's edge, the speed brake's threshold, or 1 s.
    std::size_t start = 0;
    while (start < r.size() && r[start].wrench[0] > -0.5 * push) {
      ++start;
    }
    if (start >= r.size()) {
      ADD_FAILURE() << "the command never arrived: " << s.diagnostics();
      return true;
    }
    start = index_of(r, r[start].cycle + kCyclesPerSecond / 50);
    std::size_t end = start;
    // (Unheld, the handle reaches the speed brake, 1 m/s, after about 0.3 m under 6 N.)
    while (end < r.size() && r[end].cycle < r[start].cycle + kCyclesPerSecond &&
           r[end].position[0] > 0.32 && r[end].speed < 0.9) {
      ++end;
    }
    // In cycles, not records: the recorder may miss a few under load, and the window is about
    // 106 ms at 6 N (the brake's threshold is reached that soon).
    if (end == start || r[end - 1].cycle - r[start].cycle < kCyclesPerSecond / 10) {
      ADD_FAILURE() << "no judged window of 100 ms";
      return true;
    }
    const Judged j = judge(r, start, end, 0);
    std::printf("impedance %.0f N: %.3f N rendered over %.0f ms, the handle at up to %.2f m/s\n",
                push, -j.force,
                static_cast<double>(r[end - 1].cycle - r[start].cycle) * 1e3 /
                    static_cast<double>(kCyclesPerSecond),
                max_speed(r, start, end));
    EXPECT_NEAR(-j.force, push, 0.02 * push) << "within 2 %";
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J1, ImpedanceCommand, ::testing::Values(1.0, 6.0));

class ImpedanceWall : public ::testing::TestWithParam<WallCase> {};

TEST_P(ImpedanceWall, PushedAt10NTheHandleRestsAndFeelsThePush) {
  const WallCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    Scenario s(std::string("j1-impw-") + std::to_string(attempt), c.impairment,
               wall_demo(c.stiffness, "-x", "impedance"));
    if (const auto done = wait_for_wrenches(s)) {  // at 100 ms one way about 1.5 s after start
      return *done;
    }
    const std::optional<JudgedPush> push = push_and_judge(s, -10.0, c.name);
    if (!push) {
      return false;
    }
    const Judged& j = push->judged;
    std::printf("%s: after 1 s of 10 N, %.2f mm/s, %.2f N felt, %d cycles saturated\n", c.name,
                j.speed * 1e3, j.force, j.saturated);
    EXPECT_LT(j.speed, 0.005) << around_fastest(push->records, push->from, push->to);
    EXPECT_NEAR(j.force, 10.0, 1.0) << "the felt force is the push";
    EXPECT_EQ(j.saturated, 0);
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    const shm::VpPayload vp = s.stack.vp();
    const shm::VprPayload vpr = s.stack.vpr();
    std::printf("%s: core end %.4f J in, %.4f J out; the client reports %.4f J in\n", c.name,
                vp.channel_energy_in, vp.channel_energy_out, vpr.client_energy_in);
    EXPECT_LE(vp.channel_energy_out, vpr.client_energy_in + 1e-3);
    return true;
  });
}

// The demo reports its wall as a surface that the core renders in its cycle (docs/control.md):
// before, only the direct link held (at 2 ms the push bounced at up to 0.9 m/s, from 5 ms it
// went through).
INSTANTIATE_TEST_SUITE_P(
    J1, ImpedanceWall,
    ::testing::Values(
        WallCase{"k2000_delay0", 2000, {}},
        WallCase{"k2000_delay2ms_loss10", 2000, {"--delay-ms", "2", "--loss", "0.1"}},
        WallCase{"k2000_delay20ms_jitter2", 2000, {"--delay-ms", "20", "--jitter-ms", "2"}},
        WallCase{"k2000_delay100ms_loss10", 2000, {"--delay-ms", "100", "--loss", "0.1"}}),
    [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace hapticctrl::test
