// J1 end to end: the coupling in contact, through the real processes and hapticctrl-netem. The
// demo's sphere rests on a stiff wall in its own physics (--obstacle wall, little damping) and
// reports it as a contact; the operator pushes through the force region. Every scenario failed
// on f3c5aec (J1 review; reproduced 2026-12-03 with the same demo: a 5000 N/m wall with 2 N.s/m
// chattered at 43 mm/s at 5 ms one way and 167 mm/s at 10 ms, and at 20 ms the handle went
// through it to the workspace's edge with 0.7 N felt).
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

/// Waits (at most 3 s) until the handle has been still for 200 ms (< 1 mm/s, 50 ms windows).
void wait_until_still(Scenario& s) {
  const std::uint64_t span = 200 * static_cast<std::uint64_t>(kCyclesPerSecond) / 1000;
  for (int polls = 0; polls < 30; ++polls) {
    std::this_thread::sleep_for(100ms);
    const auto r = s.recorder->records();
    if (!r.empty() && r.back().cycle > span &&
        windowed_speed(r, index_of(r, r.back().cycle - span), r.size()) < 0.001) {
      return;
    }
  }
}

/// The demo's summary (it prints it when it ends) and the core's end of the channel: each end's
/// energy out against the other end's in, printed and checked (J1: within 1 mJ). Each end
/// compares its output with the other's report of a loop ago (docs/control.md), so the totals
/// agree once nothing moves: the handle is let come to rest first, and the core's total in is
/// the largest it reached while the demo ended (it restarts at zero with the session). (CI on
/// 734e716: judged while a released hand still moved, the client's out was 2.3 mJ above.)
void expect_balanced_channel(Scenario& s, const char* name) {
  wait_until_still(s);
  const shm::VpPayload vp = s.stack.vp();
  const shm::VprPayload vpr = s.stack.vpr();
  s.demo->signal(SIGTERM);
  double core_in = vp.channel_energy_in;
  for (int polls = 0; polls < 10000 && s.demo->wait(1ms) == -1; ++polls) {
    core_in = std::max(core_in, s.stack.vp().channel_energy_in);
  }
  core_in = std::max(core_in, s.stack.vp().channel_energy_in);
  const std::string summary = s.demo->out();
  const double client_out = json_number(summary, "channel_energy_out");
  const double client_in = json_number(summary, "channel_energy_in");
  std::printf("%s: channel, core end %.4f J in, %.4f J out; client end %.4f J in, %.4f J out\n",
              name, core_in, vp.channel_energy_out, client_in, client_out);
  EXPECT_LE(vp.channel_energy_out, vpr.client_energy_in + 1e-3)
      << "the core's end gives no more than the client put in";
  ASSERT_FALSE(std::isnan(client_out)) << "no summary from the demo: " << summary;
  EXPECT_LE(client_out, core_in + 1e-3) << "the client's end gives no more than the core put in";
}

class StiffWall : public ::testing::TestWithParam<WallCase> {};

TEST_P(StiffWall, PushedAt10NTheHandleRestsAndFeelsThePush) {
  // J1: after 1 s of pushing, < 5 mm/s, the felt force the push +-10 %, never at the saturation;
  // each end of the channel gives no more than the other put in.
  const WallCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    Scenario s(std::string("j1-wall-") + std::to_string(attempt), c.impairment,
               wall_demo(c.stiffness, "x"));
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    const std::optional<JudgedPush> push = push_and_judge(s, 10.0, c.name);
    if (!push) {
      return false;
    }
    const Judged& j = push->judged;
    const shm::VpPayload vp = s.stack.vp();
    std::printf(
        "%s: after 1 s of 10 N, %.2f mm/s (50 ms windows), %.2f N felt, %d cycles saturated;"
        " k %.0f + %.0f N/m along the contact, loop %.1f ms\n",
        c.name, j.speed * 1e3, -j.force, j.saturated, vp.gains[0], vp.normal_gains[0],
        static_cast<double>(vp.loop_delay_ns) / 1e6);
    EXPECT_LT(j.speed, 0.005) << around_fastest(push->records, push->from, push->to);
    EXPECT_NEAR(-j.force, 10.0, 1.0) << "the felt force is the push";
    EXPECT_EQ(j.saturated, 0);
    EXPECT_EQ(vp.contacts, 1U) << "the demo's contact is in force";
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    expect_balanced_channel(s, c.name);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(
    J1, StiffWall,
    ::testing::Values(
        WallCase{"k5000_delay1ms_loss10", 5000, {"--delay-ms", "1", "--loss", "0.1"}},
        WallCase{"k5000_delay10ms_loss10", 5000, {"--delay-ms", "10", "--loss", "0.1"}},
        WallCase{"k3000_delay20ms_jitter2", 3000, {"--delay-ms", "20", "--jitter-ms", "2"}},
        WallCase{"k3000_delay100ms_loss10", 3000, {"--delay-ms", "100", "--loss", "0.1"}}),
    [](const auto& p) { return std::string(p.param.name); });

class ContactHand : public ::testing::TestWithParam<WallCase> {};

TEST_P(ContactHand, AHandWanderingIntoAndAlongTheWallGetsNoEnergyAndTheChannelBalances) {
  // A spring-damper hand (300 N/m, 5 N.s/m) presses 3 N into the wall and wanders (2 cm per
  // axis, 0.2-2 Hz) for 8 s: the port to the hand puts out at most 1 mJ, and each end of the
  // channel at most what the other put in (+ 1 mJ). The wall is the demo's reported contact,
  // rendered in the servo cycle (J2), the coupling acting along it.
  const WallCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    Scenario s(std::string("j1-hand-") + std::to_string(attempt), c.impairment,
               wall_demo(c.stiffness, "x"));
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    const std::string sequence = testing::TempDir() + "press-" + s.stack.instance() + ".seq";
    { std::ofstream(sequence) << "0 3 0 0 0 0 0\n8 3 0 0 0 0 0\n"; }
    const std::uint64_t from_cycle = s.recorder->newest_cycle();
    EXPECT_EQ(run_hmi(s,
                      {"play", sequence, "--log", "-", "--hand", "300,5", "--wander", "0.02",
                       "--seed", "11"},
                      20s),
              0);
    std::remove(sequence.c_str());
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    const std::size_t first = index_of(r, from_cycle);
    const double energy = port_energy(r, first, r.size());
    double largest = 0.0;
    for (std::size_t i = first; i < r.size(); ++i) {
      largest = std::max(largest, r[i].force);
    }
    std::printf("%s: the port put out %.3f mJ; peak %.2f N\n", c.name, energy * 1e3, largest);
    EXPECT_LE(energy, 1e-3) << "the port to the hand gave at most 1 mJ";
    EXPECT_LT(largest, 34.0) << "never at the saturation";
    expect_balanced_channel(s, c.name);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J1, ContactHand,
                         ::testing::Values(WallCase{"k3000_delay10ms_loss10",
                                                    3000,
                                                    {"--delay-ms", "10", "--loss", "0.1"}},
                                           WallCase{"k2000_delay100ms_loss10_jitter2",
                                                    2000,
                                                    {"--delay-ms", "100", "--loss", "0.1",
                                                     "--jitter-ms", "2"}}),
                         [](const auto& p) { return std::string(p.param.name); });

struct BlackoutCase {
  const char* name;
  int blackout_ms;
  const char* command;
};

class ContactBlackout : public ::testing::TestWithParam<BlackoutCase> {};

TEST_P(ContactBlackout, TheHandleIsNeverSnappedBackAndTheForceReturnsWithin300ms) {
  // J1's worst safety finding: the hand pushes 5 N into a 3000 N/m wall (here along -x, where
  // the workspace leaves room) through a blackout; the faded wall let it through (f3c5aec:
  // snapped back at 0.25-1.12 m/s with steps of 0.6-10 N). The wall is held while the link is
  // silent; when it returns: <= 0.1 m/s, no step over 1 N/ms, the push felt within 300 ms.
  const BlackoutCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    Scenario s(std::string("j1-cbo") + std::to_string(c.blackout_ms) + c.command[0] + "-" +
                   std::to_string(attempt),
               {"--delay-ms", "1"}, wall_demo(3000, "-x", c.command));
    std::uint64_t coupled_at = 0;
    const bool impedance = std::string(c.command) == "impedance";
    if (const auto done = impedance ? wait_for_wrenches(s) : couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    EXPECT_EQ(run_hmi(s, {"force", "-5", "0", "0", "0", "0", "0"}, 10s), 0);
    std::this_thread::sleep_for(1500ms);
    const std::uint64_t cut = s.recorder->newest_cycle();
    s.relay.toggle_blackout();
    std::this_thread::sleep_for(std::chrono::milliseconds(c.blackout_ms));
    const std::uint64_t back = s.recorder->newest_cycle();
    s.relay.toggle_blackout();
    std::this_thread::sleep_for(2s);
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    std::size_t fresh = index_of(r, back);
    while (fresh < r.size() && r[fresh].stale()) {
      ++fresh;
    }
    if (fresh >= r.size()) {
      ADD_FAILURE() << "no fresh samples after the blackout";
      return true;
    }
    const std::size_t judged_to = index_of(r, r[fresh].cycle + 2 * kCyclesPerSecond);
    std::size_t full = fresh;
    while (full < judged_to && r[full].wrench[0] < 0.9 * 5.0) {
      ++full;
    }
    const double travelled = r[index_of(r, cut)].position[0] - r[fresh].position[0];
    // The handle's speed out of the wall (+x) over 20 ms windows: a snap-back.
    double snap = 0.0;
    const std::uint64_t window = 20 * static_cast<std::uint64_t>(kCyclesPerSecond) / 1000;
    for (std::size_t i = fresh, j = fresh; i < judged_to; ++i) {
      while (r[i].cycle - r[j].cycle > window) {
        ++j;
      }
      if (r[i].cycle - r[j].cycle >= window / 2) {
        snap = std::max(snap, (r[i].position[0] - r[j].position[0]) /
                                  (static_cast<double>(r[i].cycle - r[j].cycle) /
                                   static_cast<double>(kCyclesPerSecond)));
      }
    }
    const double at_return = r[fresh].speed;
    const double peak_speed = max_speed(r, fresh, judged_to);
    const double step = largest_force_step(r, index_of(r, cut), judged_to);
    if (s.long_cycle_explains(step)) {
      return false;
    }
    std::printf(
        "%s: the handle went %.1f mm into the held wall and moved at %.3f m/s when the link "
        "returned; after it peak %.3f m/s, out of the wall at most %.3f m/s, largest step %.2f N "
        "per cycle, the push felt again after %.0f ms\n",
        c.name, travelled * 1e3, at_return, peak_speed, snap, step,
        static_cast<double>(r[std::min(full, r.size() - 1)].cycle - r[fresh].cycle) * 1e3 /
            static_cast<double>(kCyclesPerSecond));
    // The wall the hand felt is held while the link is silent: the hand does not go through it
    // (it went 30 cm through the faded wall in 2 s at the viscous hold's 0.16-0.21 m/s, and was
    // still that fast when the link returned, 2026-12-03), and the return neither snaps it back
    // nor carries it out: J1's 0.1 m/s. (f3c5aec snapped it back at 0.25, 0.59 and 1.12 m/s
    // after 0.1, 0.3 and 2 s.)
    EXPECT_LT(travelled, 0.002) << "the held wall: " << around_fastest(r, index_of(r, cut), fresh);
    EXPECT_LE(peak_speed, 0.1) << "J1: peak speed after the link returns: "
                               << around_fastest(r, fresh, judged_to);
    EXPECT_LE(step, kReleaseStep + 1e-6) << "no step over 1 N/ms in any cycle";
    EXPECT_LT(full, judged_to) << "the push is felt again";
    if (full < judged_to) {
      EXPECT_LE(r[full].cycle - r[fresh].cycle,
                static_cast<std::uint64_t>(3 * kCyclesPerSecond / 10))
          << "within 300 ms of the link's return";
    }
    return true;
  });
}

// The demo's sphere on its wall (VIRTMECH, reporting the contact), and the demo as an IMPEDANCE
// client that reports its wall as a surface.
INSTANTIATE_TEST_SUITE_P(J1, ContactBlackout,
                         ::testing::Values(BlackoutCase{"virtmech_100ms", 100, "virtmech"},
                                           BlackoutCase{"virtmech_300ms", 300, "virtmech"},
                                           BlackoutCase{"virtmech_2000ms", 2000, "virtmech"},
                                           BlackoutCase{"impedance_2000ms", 2000, "impedance"}),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(ContactClientKilled, TheHeldWallStaysUntilTheSessionEndsThenLetsGoWithoutAStep) {
  // The client dies while the hand pushes 5 N into its 3000 N/m wall: the wall the hand felt is
  // held (a static plane, docs/control.md "Contact") until the bridge's watchdog ends the session
  // (3 s), then let go at the release rate.
  with_retries("client killed in contact", [](int attempt) {
    Scenario s("j1-ckill-" + std::to_string(attempt), {"--delay-ms", "1"}, wall_demo(3000, "-x"));
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    EXPECT_EQ(run_hmi(s, {"force", "-5", "0", "0", "0", "0", "0"}, 10s), 0);
    std::this_thread::sleep_for(1500ms);
    const std::uint64_t cut = s.recorder->newest_cycle();
    s.demo->signal(SIGKILL);
    std::this_thread::sleep_for(4500ms);  // past the bridge's 3 s watchdog
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    const std::size_t from = index_of(r, cut + kCyclesPerSecond / 10);
    const std::size_t held_to = index_of(r, cut + 5 * kCyclesPerSecond / 2);
    double least = 1e9;
    for (std::size_t i = from; i < held_to; ++i) {
      least = std::min(least, r[i].wrench[0]);
    }
    const double moved = r[index_of(r, cut)].position[0] - r[held_to].position[0];
    std::size_t released = held_to;
    while (released < r.size() && r[released].wrench[0] > 0.5) {
      ++released;
    }
    const double step = largest_force_step(r, index_of(r, cut), r.size());
    if (s.long_cycle_explains(step)) {
      return false;
    }
    std::printf(
        "client killed in contact: the wall held at least %.2f N for 2.5 s, the handle %.1f mm "
        "deeper; let go %.0f ms after the kill; largest step %.2f N per cycle\n",
        least, moved * 1e3,
        static_cast<double>(r[std::min(released, r.size() - 1)].cycle - cut) * 1e3 /
            static_cast<double>(kCyclesPerSecond),
        step);
    EXPECT_GT(least, 0.9 * 5.0) << "the wall the hand felt, while the session lasts";
    EXPECT_LT(moved, 0.002);
    EXPECT_LT(released, r.size()) << "let go when the watchdog ended the session";
    EXPECT_LE(step, kReleaseStep + 1e-6) << "no step over 1 N/ms in any cycle";
    EXPECT_TRUE(ControllerStack::eventually(
        [&] { return s.stack.link_stats().watchdog_expiries == 1U; }, 3s));
    return true;
  });
}

}  // namespace
}  // namespace hapticctrl::test
