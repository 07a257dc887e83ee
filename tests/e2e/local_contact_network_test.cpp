// J2 end to end: a contact the client reports rendered in the core's cycle (the local contact
// model, docs/control.md), through the real processes and hapticctrl-netem: the surface felt at
// its stiffness at any delay, its Coulomb friction, and a wall that jumps into the handle.
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

struct LocalCase {
  const char* name;
  std::vector<std::string> demo;  ///< the demo's scene
  double stiffness;               ///< the object's surface, N/m
  std::vector<std::string> impairment;
  double mu = 0.6;  ///< the surface's Coulomb friction (the demo's --friction)
};

void PrintTo(const LocalCase& c, std::ostream* os) {  // NOLINT(readability-identifier-naming)
  *os << c.name;
}

class LocalContact : public ::testing::TestWithParam<LocalCase> {};

TEST_P(LocalContact, TheSurfaceIsFeltAtItsStiffnessAtAnyDelay) {
  // J2: the object rests on its surface in the client's physics; the operator pushes 5 N, then
  // 10 N, into it through the force region. The stiffness felt (5 N over the handle's travel
  // between the two pushes) is the surface's within 10 %, and so is the penetration at 10 N (F
  // / k from where the handle rested unpushed), whatever the delay: the surface is rendered in
  // the servo cycle. Through the coupling alone (before J2) a 2000 N/m wall was felt at the
  // coupling's series stiffness: 211 N/m at 10 ms one way, 71-74 N/m at 20 ms.
  const LocalCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    Scenario s(std::string("j2-local-") + std::to_string(attempt), c.impairment, c.demo);
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    const auto hold = [&](double force) {
      EXPECT_EQ(run_hmi(s, {"force", std::to_string(force), "0", "0", "0", "0", "0"}, 10s), 0);
      const std::uint64_t at = s.recorder->newest_cycle();
      std::this_thread::sleep_for(2s);
      return at;
    };
    const std::uint64_t rest_at = s.recorder->newest_cycle();
    const std::uint64_t five_at = hold(5.0);
    const std::uint64_t ten_at = hold(10.0);
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    // Each force judged over its last second (the first lets the handle settle).
    const std::size_t rest_from = index_of(r, rest_at - kCyclesPerSecond / 2);
    const std::size_t five_from = index_of(r, five_at + kCyclesPerSecond);
    const std::size_t ten_from = index_of(r, ten_at + kCyclesPerSecond);
    const std::size_t end = index_of(r, ten_at + 2 * kCyclesPerSecond);
    if (longest_silence(r, five_from, end) >= 30 * kCyclesPerSecond / 1000) {
      std::printf("%s: the link was held up in the judged windows: tried again\n", c.name);
      return false;
    }
    const double x0 = mean_position(r, rest_from, index_of(r, rest_at), 0);
    const double x5 = mean_position(r, five_from, index_of(r, five_at + 2 * kCyclesPerSecond), 0);
    const double x10 = mean_position(r, ten_from, end, 0);
    const Judged five = judge(r, five_from, index_of(r, five_at + 2 * kCyclesPerSecond), 0);
    const Judged ten = judge(r, ten_from, end, 0);
    const double k_felt = (ten.force - five.force) / (x10 - x5);
    const shm::VpPayload vp = s.stack.vp();
    std::printf(
        "%s: %.2f / %.2f N felt for 5 / 10 N; k_felt %.0f N/m (k_felt / k_object %.3f); "
        "penetration at 10 N %.2f mm (F / k %.2f mm); %.2f mm/s at 10 N; %d cycles saturated; "
        "coupling k %.0f N/m, loop %.1f ms\n",
        c.name, -five.force, -ten.force, -k_felt, -k_felt / c.stiffness, (x10 - x0) * 1e3,
        10.0 / c.stiffness * 1e3, ten.speed * 1e3, five.saturated + ten.saturated, vp.gains[0],
        static_cast<double>(vp.loop_delay_ns) / 1e6);
    EXPECT_GE(-k_felt / c.stiffness, 0.9) << "J2: k_felt / k_object";
    EXPECT_LE(-k_felt / c.stiffness, 1.1);
    EXPECT_NEAR((x10 - x0) * c.stiffness, 10.0, 1.0) << "penetration at 10 N within 10 % of F / k";
    EXPECT_LT(ten.speed, 0.005) << around_fastest(r, ten_from, end);
    EXPECT_EQ(five.saturated + ten.saturated, 0);
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(
    J2, LocalContact,
    ::testing::Values(LocalCase{"wall2000_direct", wall_demo(2000, "x"), 2000, {}},
                      LocalCase{"wall2000_delay10ms_loss10_jitter2",
                                wall_demo(2000, "x"),
                                2000,
                                {"--delay-ms", "10", "--loss", "0.1", "--jitter-ms", "2"}},
                      LocalCase{"wall2000_delay100ms_loss10_jitter2",
                                wall_demo(2000, "x"),
                                2000,
                                {"--delay-ms", "100", "--loss", "0.1", "--jitter-ms", "2"}},
                      LocalCase{"sphere_delay20ms_loss10_jitter2",
                                {"--toward", "x", "--gap", "0"},
                                2000,
                                {"--delay-ms", "20", "--loss", "0.1", "--jitter-ms", "2"}}),
    [](const auto& p) { return std::string(p.param.name); });

class LocalFriction : public ::testing::TestWithParam<LocalCase> {};

TEST_P(LocalFriction, SlidingAlongTheSurfaceRendersItsCoulombFriction) {
  // J2: pressed 10 N into the demo's wall (friction mu), the handle held along it by two thirds
  // of mu x 10 N sticks (still, the friction holding it), and pushed by 1.1 x mu x 10 N slides,
  // held back by mu x the normal force: mu measured as the rendered tangential force over the
  // normal one, within 10 %, over the first 0.35 s of the slide (the arm's small mass along y
  // accelerates under the tenth left: judged later, the speed brake at 1 m/s added its damping).
  const LocalCase& c = GetParam();
  const double mu_surface = c.mu;
  const std::string stick = std::to_string(mu_surface * 10.0 * 2.0 / 3.0);
  const std::string slide = std::to_string(mu_surface * 10.0 * 1.1);
  with_retries(c.name, [&](int attempt) {
    Scenario s(std::string("j2-friction-") + std::to_string(attempt), c.impairment, c.demo);
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    EXPECT_EQ(run_hmi(s, {"force", "10", "0", "0", "0", "0", "0"}, 10s), 0);
    std::this_thread::sleep_for(1s);
    EXPECT_EQ(run_hmi(s, {"force", "10", stick, "0", "0", "0", "0"}, 10s), 0);
    const std::uint64_t stuck_at = s.recorder->newest_cycle();
    std::this_thread::sleep_for(1500ms);
    EXPECT_EQ(run_hmi(s, {"force", "10", slide, "0", "0", "0", "0"}, 10s), 0);
    const std::uint64_t slide_at = s.recorder->newest_cycle();
    std::this_thread::sleep_for(700ms);
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    const std::size_t stuck_from = index_of(r, stuck_at + kCyclesPerSecond / 2);
    const std::size_t stuck_to = index_of(r, stuck_at + 3 * kCyclesPerSecond / 2);
    const std::size_t slide_from = index_of(r, slide_at + kCyclesPerSecond / 10);
    const std::size_t slide_to = index_of(r, slide_at + 35 * kCyclesPerSecond / 100);
    if (longest_silence(r, stuck_from, slide_to) >= 30 * kCyclesPerSecond / 1000) {
      std::printf("%s: the link was held up in the judged windows: tried again\n", c.name);
      return false;
    }
    const Judged stuck_x = judge(r, stuck_from, stuck_to, 0);
    const Judged stuck_y = judge(r, stuck_from, stuck_to, 1);
    double mu = 0.0;
    for (std::size_t i = slide_from; i < slide_to; ++i) {
      mu += (r[i].wrench[1] / r[i].wrench[0]) / static_cast<double>(slide_to - slide_from);
    }
    const double slid = r[slide_to - 1].position[1] - r[slide_from].position[1];
    std::printf(
        "%s: held by %s N along it, %.2f N back (normal %.2f N) at %.2f mm/s; pushed by %s N, "
        "slid %.1f mm (at most %.2f m/s) with mu %.3f rendered (%.2f)\n",
        c.name, stick.c_str(), -stuck_y.force, -stuck_x.force, stuck_y.speed * 1e3, slide.c_str(),
        slid * 1e3, max_speed(r, slide_from, slide_to), mu, mu_surface);
    EXPECT_NEAR(-stuck_y.force, std::stod(stick), 0.1 * std::stod(stick))
        << "sticking: the friction holds the push along it";
    EXPECT_LT(stuck_y.speed, 0.005) << "and the handle stays";
    EXPECT_GT(slid, 0.005) << slide << " N is past mu_s x 10 N: it slides";
    EXPECT_LT(max_speed(r, slide_from, slide_to), 0.8) << "below the speed brake";
    EXPECT_NEAR(mu, mu_surface, 0.1 * mu_surface) << "J2: sliding renders mu within 10 %";
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(
    J2, LocalFriction,
    ::testing::Values(LocalCase{"wall_direct", wall_demo(2000, "x"), 2000, {}},
                      LocalCase{"wall_delay20ms_loss10_jitter2",
                                wall_demo(2000, "x"),
                                2000,
                                {"--delay-ms", "20", "--loss", "0.1", "--jitter-ms", "2"}},
                      LocalCase{"wall_mu03_delay50ms_loss10_jitter2",
                                with(wall_demo(2000, "x"), {"--friction", "0.3"}),
                                2000,
                                {"--delay-ms", "50", "--loss", "0.1", "--jitter-ms", "2"},
                                0.3}),
    [](const auto& p) { return std::string(p.param.name); });

class LocalPlaneJump : public ::testing::TestWithParam<LocalCase> {};

TEST_P(LocalPlaneJump, AWallThatJumps5mmIntoTheHandleGivesNoStepAndNoEnergy) {
  // J2's passive model updates, through the real processes: the hand rests pushing 5 N on the
  // demo's 2000 N/m wall when the demo's script moves the wall 5 mm into it at once (at 5 s of
  // the demo's time). No force step above 1 N/ms, no energy out of the port to the hand (at
  // most 1 mJ), and the core holds back the depth the handle did not earn (telemetry).
  const LocalCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    const std::string script =
        testing::TempDir() + "jump-" + std::to_string(attempt) + "-" + c.name + ".script";
    { std::ofstream(script) << "5.0 obstacle -0.005 0 0\n"; }
    Scenario s(std::string("j2-jump-") + std::to_string(attempt), c.impairment,
               with(c.demo, {"--script", script}));
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      std::remove(script.c_str());
      return *done;
    }
    EXPECT_EQ(run_hmi(s, {"force", "5", "0", "0", "0", "0", "0"}, 10s), 0);
    const std::uint64_t pushed_at = s.recorder->newest_cycle();
    // The jump comes at 5 s of the demo's time, coupled within its first 2 s: judged from the
    // rest before it to 2 s after it.
    ControllerStack::eventually([&] { return s.stack.vp().surface_hidden > 0.001; }, 8s);
    const std::uint64_t jumped_at = s.recorder->newest_cycle();
    std::this_thread::sleep_for(2s);
    const shm::VpPayload vp = s.stack.vp();
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    std::remove(script.c_str());
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    const std::size_t from = index_of(r, pushed_at + kCyclesPerSecond);
    const std::size_t to = index_of(r, jumped_at + 2 * kCyclesPerSecond);
    const double step = largest_force_step(r, from, to);
    if (s.long_cycle_explains(step)) {
      return false;
    }
    const double energy = port_energy(r, from, to);
    std::printf(
        "%s: the wall jumped 5 mm into the handle: largest step %.3f N per cycle, the port put "
        "out %.3f mJ, %.2f mm held back, %.2f N felt after it (%.2f mm/s)\n",
        c.name, step, energy * 1e3, vp.surface_hidden * 1e3,
        -judge(r, index_of(r, jumped_at + kCyclesPerSecond), to, 0).force,
        windowed_speed(r, index_of(r, jumped_at), to) * 1e3);
    EXPECT_GT(pushed_at, coupled_at) << "pushed before the jump";
    EXPECT_GT(jumped_at, pushed_at + kCyclesPerSecond) << "the jump came after the rest";
    EXPECT_GE(vp.surface_hidden, 0.004) << "the jump reached the core and was held back";
    EXPECT_LE(vp.surface_hidden, 0.0055);
    EXPECT_LE(step, kReleaseStep + 1e-6) << "no step over 1 N/ms";
    EXPECT_LE(energy, 1e-3) << "the port to the hand gave at most 1 mJ";
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J2, LocalPlaneJump,
                         ::testing::Values(LocalCase{"wall_direct", wall_demo(2000, "x"), 2000, {}},
                                           LocalCase{"wall_delay20ms_loss10_jitter2",
                                                     wall_demo(2000, "x"),
                                                     2000,
                                                     {"--delay-ms", "20", "--loss", "0.1",
                                                      "--jitter-ms", "2"}}),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace hapticctrl::test
