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

#include "support/json_fields.hpp"
#include "support/network_scenario.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

/// hapticctrl-hmi on the scenario's instance, run to its end (bounded).
int run_hmi(const Scenario& s, std::vector<std::string> args, std::chrono::seconds bound) {
  args.insert(args.begin(), {"--instance", s.stack.instance()});
  SpawnedProcess hmi(HAPTICCTRL_HMI_BINARY, args);
  return hmi.wait(bound);
}

/// The demo with its sphere on a wall `toward` of the handle, stiff and barely damped.
std::vector<std::string> wall_demo(double stiffness, const std::string& toward,
                                   const std::string& command = "virtmech") {
  return {"--obstacle",
          "wall",
          "--toward",
          toward,
          "--gap",
          "0",
          "--contact-stiffness",
          std::to_string(stiffness),
          "--contact-damping",
          "2",
          "--command",
          command};
}

/// `args` and `more` after them.
std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

/// Mean rendered force along `axis` and the windowed speed over records [from, to).
struct Judged {
  double force = 0.0;
  double speed = 0.0;
  int saturated = 0;
};

Judged judge(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to,
             std::size_t axis) {
  Judged j;
  to = std::min(to, r.size());
  for (std::size_t i = from; i < to; ++i) {
    j.force += r[i].wrench[axis] / static_cast<double>(to - from);
    j.saturated += (r[i].state_word & shm::state_bits::kSaturated) != 0 ? 1 : 0;
  }
  j.speed = windowed_speed(r, from, to);
  return j;
}

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

struct WallCase {
  const char* name;
  double stiffness;
  std::vector<std::string> impairment;
};

void PrintTo(const WallCase& c, std::ostream* os) {  // NOLINT(readability-identifier-naming)
  *os << c.name;
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
    const std::uint64_t pushed_at = s.recorder->newest_cycle();
    EXPECT_EQ(run_hmi(s, {"force", "10", "0", "0", "0", "0", "0"}, 10s), 0);
    std::this_thread::sleep_for(3s);
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    const std::size_t from = index_of(r, pushed_at + kCyclesPerSecond);
    const std::size_t to = index_of(r, pushed_at + 3 * kCyclesPerSecond);
    if (longest_silence(r, from, to) >= 30 * kCyclesPerSecond / 1000) {
      std::printf("%s: the link was held up in the judged window: tried again\n", c.name);
      return false;
    }
    const Judged j = judge(r, from, to, 0);
    const shm::VpPayload vp = s.stack.vp();
    std::printf(
        "%s: after 1 s of 10 N, %.2f mm/s (50 ms windows), %.2f N felt, %d cycles saturated;"
        " k %.0f + %.0f N/m along the contact, loop %.1f ms\n",
        c.name, j.speed * 1e3, -j.force, j.saturated, vp.gains[0], vp.normal_gains[0],
        static_cast<double>(vp.loop_delay_ns) / 1e6);
    EXPECT_LT(j.speed, 0.005) << around_fastest(r, from, to);
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

/// The energy the port put out into the hand over records [from, to): the rendered force's
/// work on the handle's travel (positive: the device pushed the hand).
double port_energy(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to) {
  double energy = 0.0;
  for (std::size_t i = from + 1; i < std::min(to, r.size()); ++i) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      energy += r[i].wrench[axis] * (r[i].position[axis] - r[i - 1].position[axis]);
    }
  }
  return energy;
}

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

/// Waits until an IMPEDANCE client's wrenches flow (powered, the client fresh), then 0.5 s more:
/// pushed before, the handle went 7 cm into the wall before its first report arrived (100 ms
/// one way). nullopt: they flow; otherwise the attempt's verdict (false: retry, the machine).
std::optional<bool> wait_for_wrenches(Scenario& s) {
  if (!s.started()) {
    ADD_FAILURE() << "the stack did not start: " << s.diagnostics();
    return true;
  }
  const auto live = [&] {
    const std::uint32_t w = s.stack.position().state_word;
    return (w & shm::state_bits::kPowered) != 0 && (w & shm::state_bits::kClientStale) == 0;
  };
  if (!ControllerStack::eventually(live, 10s)) {
    if (s.core_failed_safe()) {
      return false;
    }
    ADD_FAILURE() << "the client's wrenches never flowed: " << s.diagnostics();
    return true;
  }
  std::this_thread::sleep_for(500ms);
  return std::nullopt;
}

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
    const std::uint64_t pushed_at = s.recorder->newest_cycle();
    EXPECT_EQ(run_hmi(s, {"force", "-10", "0", "0", "0", "0", "0"}, 10s), 0);
    std::this_thread::sleep_for(3s);
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    const std::size_t from = index_of(r, pushed_at + kCyclesPerSecond);
    const std::size_t to = index_of(r, pushed_at + 3 * kCyclesPerSecond);
    if (longest_silence(r, from, to) >= 30 * kCyclesPerSecond / 1000) {
      std::printf("%s: the link was held up in the judged window: tried again\n", c.name);
      return false;
    }
    const Judged j = judge(r, from, to, 0);
    std::printf("%s: after 1 s of 10 N, %.2f mm/s, %.2f N felt, %d cycles saturated\n", c.name,
                j.speed * 1e3, j.force, j.saturated);
    EXPECT_LT(j.speed, 0.005) << around_fastest(r, from, to);
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

/// Mean handle position along `axis` over records [from, to).
double mean_position(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to,
                     std::size_t axis) {
  to = std::min(to, r.size());
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) {
    sum += r[i].position[axis];
  }
  return to > from ? sum / static_cast<double>(to - from) : std::nan("");
}

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
