// H1 end to end: the coupling over an impaired network, through the real processes. The demo
// client (a weighted sphere, VIRTMECH) talks to hapticctrl-udp through hapticctrl-netem (delay,
// jitter, loss, blackouts); a recorder follows what the core renders on the handle, cycle by
// cycle. Each scenario was unstable or unsafe before H1 (2026-12-02, on 3b69386): the weighted
// sphere shook the handle at +-35 N and 5.6 m/s, 1 ms of delay made the coupling oscillate at
// the saturation, a blackout longer than 100 ms ended the session, and a lost client dropped
// ~5 N in one cycle.
//
// A 1 ms core on this 2-vCPU VM fails safe on a whole-VM stall (5 consecutive misses) every few
// seconds (an idle core alone: 5.8-6.3 s, 2026-12-02; ../shared/PITFALLS.md), so the core runs in
// benchmark mode: the simulated arm pauses through a stall, which the core counts as a would-be
// fail-safe (printed per scenario) and rides through. An attempt whose core stopped anyway is
// retried (up to 3 attempts) and counted in the test's output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "support/network_scenario.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

TEST(CouplingOverNetwork, AWeightedSphereComesToRestAndStaysThereWithoutChatter) {
  with_retries("rest", [](int attempt) {
    Scenario s("h1-rest-" + std::to_string(attempt), {});
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 10s, coupled_at)) {
      return *done;
    }
    const auto r = s.recorder->records();
    const std::size_t settled = index_of(r, coupled_at + 3 * kCyclesPerSecond);
    EXPECT_LT(settled + kCyclesPerSecond, r.size()) << "recorded " << r.size() << " cycles";
    EXPECT_LT(max_speed(r, settled, r.size()), 0.1)
        << "at rest within 3 s and never above 0.1 m/s afterwards";
    EXPECT_EQ(coupling_toggles(r, index_of(r, coupled_at)), 0) << "no coupling on/off chatter";
    double largest = 0.0;
    for (std::size_t i = index_of(r, coupled_at); i < r.size(); ++i) {
      largest = std::max(largest, r[i].force);
    }
    EXPECT_LT(largest, 34.0) << "never at the saturation: nobody pushes";
    // Transparency: at rest the handle carries the sphere's weight, 0.5 kg x 9.81 m/s^2.
    double weight = 0.0;
    const std::size_t last_two = index_of(r, r.back().cycle - 2 * kCyclesPerSecond);
    for (std::size_t i = last_two; i < r.size(); ++i) {
      weight += r[i].force / static_cast<double>(r.size() - last_two);
    }
    std::printf("rest: the handle carries %.3f N (m g = %.3f N)\n", weight, 0.5 * 9.81);
    EXPECT_NEAR(weight, 0.5 * 9.81, 0.02 * 0.5 * 9.81) << "the weight within 2 %";
    return true;
  });
}

/// hapticctrl-hmi on the scenario's instance, run to its end (bounded).
int run_hmi(const Scenario& s, std::vector<std::string> args, std::chrono::seconds bound) {
  args.insert(args.begin(), {"--instance", s.stack.instance()});
  SpawnedProcess hmi(HAPTICCTRL_HMI_BINARY, args);
  return hmi.wait(bound);
}

/// Mean handle x and mean wrench the handle renders along x over the last `cycles` records.
std::pair<double, double> at_rest(const std::vector<CycleRecord>& r, std::size_t cycles) {
  double x = 0.0;
  double f = 0.0;
  const std::size_t from = r.size() > cycles ? r.size() - cycles : 0;
  for (std::size_t i = from; i < r.size(); ++i) {
    x += r[i].position[0] / static_cast<double>(r.size() - from);
    f += r[i].wrench[0] / static_cast<double>(r.size() - from);
  }
  return {x, f};
}

/// The demo's fixed sphere's centre x, as it printed it ("fixed sphere at (x y z)").
double fixed_sphere_x(const std::string& demo_err) {
  const std::string marker = "fixed sphere at (";
  const auto at = demo_err.find(marker);
  return at == std::string::npos ? std::nan("") : std::stod(demo_err.substr(at + marker.size()));
}

TEST(CouplingOverNetwork, ContactPenetrationIsForceOverTheSeriesStiffness) {
  // H1's transparency where the network is good (2 ms one way): the operator pushes the handle,
  // and the demo's free sphere with it, onto the fixed sphere (1 cm away along +x) with 2 N then
  // 4 N; at rest the handle is past the contact surface by F / K_series, K_series = 1 / (1 /
  // K_contact + 1 / k) with the demo's 2000 N/m and the coupling's k, within 10 %.
  with_retries("contact", [](int attempt) {
    // Without the demo's contact report: a reported contact stiffens the coupling along its
    // normal (J1), which contact_network_test measures.
    Scenario s("h1-contact-" + std::to_string(attempt), {"--delay-ms", "2"}, {"--no-contacts"});
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    const double surface = fixed_sphere_x(s.demo->err()) - 0.06;  // the two radii
    std::array<std::pair<double, double>, 2> rest{};
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string push = k == 0 ? "2" : "4";
      EXPECT_EQ(run_hmi(s, {"force", push, "0", "0", "0", "0", "0"}, 10s), 0);
      std::this_thread::sleep_for(2500ms);
      rest[k] = at_rest(s.recorder->records(), static_cast<std::size_t>(kCyclesPerSecond / 2));
    }
    EXPECT_EQ(run_hmi(s, {"zero-force"}, 10s), 0);
    if (s.core_failed_safe()) {
      return false;
    }
    const double k = s.stack.vp().gains[0];
    const double k_series = 1.0 / (1.0 / 2000.0 + 1.0 / k);
    const double pushed = -rest[1].second;
    const double penetration = rest[1].first - surface;
    const double rendered = (rest[1].second - rest[0].second) / (rest[0].first - rest[1].first);
    std::printf(
        "contact: k %.0f N/m, K_series %.0f N/m; under %.3f N the handle is %.3f mm past the "
        "surface (F / K_series %.3f mm); stiffness rendered between 2 and 4 N: %.0f N/m\n",
        k, k_series, pushed, penetration * 1e3, pushed / k_series * 1e3, rendered);
    EXPECT_NEAR(pushed, 4.0, 0.2) << "at rest, the handle renders the push";
    EXPECT_NEAR(penetration, pushed / k_series, 0.1 * pushed / k_series);
    EXPECT_NEAR(rendered, k_series, 0.1 * k_series);
    return true;
  });
}

TEST(CouplingOverNetwork, AWanderingHandGetsNoEnergyFromTheCouplingPort) {
  // A spring-damper hand (300 N/m, 5 N.s/m; the core's simulator) holds the handle and wanders
  // at random (2 cm per axis, 0.2-2 Hz) for 8 s, dragging the demo's free sphere, through 5 ms
  // one way with 10 % loss and +-2 ms jitter: the port between the controller and the hand puts
  // out no more than 1 mJ (H1; translation, the hand holds no torque), and nothing reaches the
  // saturation.
  with_retries("hand", [](int attempt) {
    Scenario s("h1-hand-" + std::to_string(attempt),
               {"--delay-ms", "5", "--loss", "0.1", "--jitter-ms", "2"}, {});
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 1s, coupled_at)) {
      return *done;
    }
    const std::string sequence = testing::TempDir() + "hand-" + s.stack.instance() + ".seq";
    { std::ofstream(sequence) << "0 0 0 0 0 0 0\n8 0 0 0 0 0 0\n"; }
    const std::uint64_t from_cycle = s.recorder->newest_cycle();
    EXPECT_EQ(run_hmi(s,
                      {"play", sequence, "--log", "-", "--hand", "300,5", "--wander", "0.02",
                       "--seed", "5"},
                      20s),
              0);
    std::remove(sequence.c_str());
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    double energy = 0.0;
    double largest = 0.0;
    double travel = 0.0;
    const std::size_t first = index_of(r, from_cycle);
    if (first >= r.size()) {
      ADD_FAILURE() << "nothing recorded while the hand played: " << s.diagnostics();
      return true;
    }
    const std::array<double, 3> origin = r[first].position;
    for (std::size_t i = first + 1; i < r.size(); ++i) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        energy += r[i].wrench[axis] * (r[i].position[axis] - r[i - 1].position[axis]);
      }
      largest = std::max(largest, r[i].force);
      travel =
          std::max(travel, std::hypot(r[i].position[0] - origin[0], r[i].position[1] - origin[1],
                                      r[i].position[2] - origin[2]));
    }
    std::printf("hand: the handle travelled up to %.1f mm; the port put out %.3f mJ; peak %.2f N\n",
                travel * 1e3, energy * 1e3, largest);
    EXPECT_GT(travel, 0.005) << "the hand moved the handle";
    EXPECT_LE(energy, 1e-3) << "the coupling port gave the hand at most 1 mJ";
    EXPECT_LT(largest, 34.0) << "never at the saturation";
    return true;
  });
}

struct LinkCase {
  const char* name;
  std::vector<std::string> impairment;
  /// Handle speed over 50 ms windows in the last 2 s (H1: 5 mm/s). At 20 ms one way with 10 %
  /// loss and +-2 ms jitter it was 2.6-7.5 mm/s (5 of 12 runs over 5 mm/s) while jitter moved
  /// the gains and the client's PC chattered the force; 0.4-0.8 mm/s in 8 runs since
  /// (2026-12-02; docs/control.md).
  double still_below = 0.005;
};

/// Names the case in test listings (GoogleTest would print its bytes, pointers included, and
/// the ctest names would change with every build). GoogleTest looks for this very name.
void PrintTo(const LinkCase& c, std::ostream* os) {  // NOLINT(readability-identifier-naming)
  *os << c.name;
}

class CouplingOverImpairedLink : public ::testing::TestWithParam<LinkCase> {};

TEST_P(CouplingOverImpairedLink, StaysStillWithoutSaturationOrSpeed) {
  const LinkCase& c = GetParam();
  with_retries(c.name, [&](int attempt) {
    Scenario s("h1-link-" + std::to_string(attempt), c.impairment);
    std::uint64_t coupled_at = 0;
    if (const auto done = couple_and_record(s, 8s, coupled_at)) {
      return *done;
    }
    const auto r = s.recorder->records();
    const std::size_t from = index_of(r, coupled_at);
    const std::size_t last_two = index_of(r, r.back().cycle - 2 * kCyclesPerSecond);
    // A link silent for 30 ms or more fades the weight the handle carries (docs/control.md), and
    // the handle moves: on this VM the relay, the bridge or the demo is held up that long now and
    // then (once in about ten runs, 2026-12-02). That transient belongs to the link-loss tests,
    // not to the stillness judged here: such an attempt is tried again, and counted.
    const std::uint64_t silent =
        longest_silence(r, index_of(r, r.back().cycle - 3 * kCyclesPerSecond), r.size());
    if (silent >= 30 * kCyclesPerSecond / 1000) {
      std::printf("%s: the link was silent for %llu cycles before or in the judged 2 s\n", c.name,
                  static_cast<unsigned long long>(silent));
      return false;
    }
    double largest = 0.0;
    for (std::size_t i = from; i < r.size(); ++i) {
      largest = std::max(largest, r[i].force);
    }
    const shm::VpPayload vp = s.stack.vp();
    const shm::VprPayload vpr = s.stack.vpr();  // with the bridge's measure of the link
    std::printf(
        "%s: loop %.1f ms, link one-way %.1f ms, jitter %.2f ms, loss %.1f %%, k %.0f N/m,"
        " peak force %.1f N, peak speed %.3f m/s, last 2 s %.4f m/s (50 ms windows),"
        " per cycle %.4f m/s\n",
        c.name, static_cast<double>(vp.loop_delay_ns) / 1e6,
        static_cast<double>(vpr.link_delay_ns) / 1e6, static_cast<double>(vpr.link_jitter_ns) / 1e6,
        vpr.link_loss_ppm / 1e4, vp.gains[0], largest, max_speed(r, from, r.size()),
        windowed_speed(r, last_two, r.size()), max_speed(r, last_two, r.size()));
    std::printf(
        "%s: channel energy, core end: %.4f J in, %.4f J out (after its PC); the client"
        " reports %.4f J in\n",
        c.name, vp.channel_energy_in, vp.channel_energy_out, vpr.client_energy_in);
    EXPECT_LE(vp.channel_energy_out, vpr.client_energy_in + 0.1)
        << "the core's end of the channel gives no more than the client put in";
    EXPECT_LT(std::hypot(vpr.object_twist[0], vpr.object_twist[1], vpr.object_twist[2]), 0.1)
        << "the client's object is at rest too";
    EXPECT_LT(largest, 34.0) << "never at the saturation";
    EXPECT_LT(windowed_speed(r, last_two, r.size()), c.still_below)
        << "oscillation below " << c.still_below
        << " m/s:" << around_fastest(r, last_two, r.size());
    EXPECT_LT(max_speed(r, last_two, r.size()), 0.1) << "no speed excursion";
    EXPECT_EQ(coupling_toggles(r, from), 0);
    EXPECT_GT(vp.loop_delay_ns, 0) << "the loop was measured";
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(
    H1, CouplingOverImpairedLink,
    ::testing::Values(LinkCase{"delay1ms", {"--delay-ms", "1"}},
                      LinkCase{"delay5ms_loss10", {"--delay-ms", "5", "--loss", "0.1"}},
                      LinkCase{"delay20ms_loss10_jitter2",
                               {"--delay-ms", "20", "--loss", "0.1", "--jitter-ms", "2"}}),
    [](const auto& p) { return std::string(p.param.name); });

/// Checks the release of the force after the last fresh sample before `lost_from` (a cycle at or
/// after which the link was cut), and the re-coupling after `back_from` (0: no return).
void expect_faded_and_recoupled(const std::vector<CycleRecord>& r, std::uint64_t lost_from,
                                std::uint64_t back_from) {
  std::printf("%zu records, cycles %llu..%llu, link cut at %llu, back at %llu\n", r.size(),
              static_cast<unsigned long long>(r.front().cycle),
              static_cast<unsigned long long>(r.back().cycle),
              static_cast<unsigned long long>(lost_from),
              static_cast<unsigned long long>(back_from));
  std::size_t first_stale = index_of(r, lost_from);
  while (first_stale < r.size() && !r[first_stale].stale()) {
    ++first_stale;
  }
  ASSERT_LT(first_stale, r.size()) << "the core saw the link go stale";
  // Stale means 5 ms without a new sample: the last fresh one came 5 ms earlier.
  const std::uint64_t last_fresh = r[first_stale].cycle - 5 * kCyclesPerSecond / 1000;
  const std::size_t by = index_of(r, last_fresh + 50 * kCyclesPerSecond / 1000);
  ASSERT_LT(by, r.size());
  // What may remain is the viscous hold of a disengaged session (20 N.s/m on the handle's
  // motion), which only brakes.
  EXPECT_LE(r[by].force, 20.0 * r[by].speed + 1e-6)
      << "the coupling at zero within 50 ms of the last fresh sample (cycle " << last_fresh
      << "), still " << r[by].force << " N at " << r[by].speed << " m/s";
  const std::size_t lost = index_of(r, last_fresh);
  EXPECT_LE(largest_force_step(r, lost, by + 1), kReleaseStep + 1e-6) << "no step over 1 N/ms";
  if (back_from == 0) {
    return;
  }
  std::size_t back = index_of(r, back_from);
  while (back < r.size() && r[back].stale()) {
    ++back;
  }
  ASSERT_LT(back, r.size()) << "fresh samples again";
  std::size_t coupled = back;
  while (coupled < r.size() && !(r[coupled].coupled() && r[coupled].force > 0.5)) {
    ++coupled;
  }
  ASSERT_LT(coupled, r.size()) << "re-coupled";
  EXPECT_LE(r[coupled].cycle - r[back].cycle, static_cast<std::uint64_t>(kCyclesPerSecond / 10))
      << "re-coupled within 100 ms of the link's return";
  // The handle drifts a little while disengaged (held by a viscous field only) and falls back
  // under the object's weight when the coupling returns: 0.11 m/s after 300 ms (2026-12-02).
  EXPECT_LT(max_speed(r, back, r.size()), 0.15) << "no speed excursion after the return";
  EXPECT_LE(largest_force_step(r, back, r.size()), 2.0 * kPeriodUs / 1000.0 + 0.5)
      << "back through the ramp and the rate limit";
}

class Blackout : public ::testing::TestWithParam<int> {};

TEST_P(Blackout, FadesTheForceAndTheSameSessionRecouplesAfterIt) {
  const int blackout_ms = GetParam();
  with_retries("blackout " + std::to_string(blackout_ms), [&](int attempt) {
    Scenario s("h1-bo" + std::to_string(blackout_ms) + "-" + std::to_string(attempt),
               {"--delay-ms", "1"});
    std::uint64_t coupled_at = 0;  // then 3 s for the sphere and the handle to come to rest
    if (const auto done = couple_and_record(s, 3s, coupled_at)) {
      return *done;
    }
    const std::uint64_t cut = s.recorder->newest_cycle();
    s.relay.toggle_blackout();
    std::this_thread::sleep_for(std::chrono::milliseconds(blackout_ms));
    const std::uint64_t back = s.recorder->newest_cycle();
    s.relay.toggle_blackout();
    std::this_thread::sleep_for(2s);
    if (s.core_failed_safe()) {
      return false;
    }
    expect_faded_and_recoupled(s.recorder->records(), cut, back);
    EXPECT_EQ(s.stack.link_stats().sessions_opened, 1U) << "the session survived";
    EXPECT_EQ(s.stack.link_stats().watchdog_expiries, 0U);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(H1, Blackout, ::testing::Values(100, 300, 2000));

TEST(LinkLoss, AKilledClientsForceFadesWithin50msWithoutAStep) {
  with_retries("client killed", [](int attempt) {
    Scenario s("h1-kill-" + std::to_string(attempt), {});
    std::uint64_t coupled_at = 0;  // then 3 s for the sphere and the handle to come to rest
    if (const auto done = couple_and_record(s, 3s, coupled_at)) {
      return *done;
    }
    const std::uint64_t cut = s.recorder->newest_cycle();
    s.demo->signal(SIGKILL);
    std::this_thread::sleep_for(4s);  // past the bridge's 3 s watchdog: the session ends too
    if (s.core_failed_safe()) {
      return false;
    }
    const auto r = s.recorder->records();
    expect_faded_and_recoupled(r, cut, 0);
    EXPECT_LE(largest_force_step(r, index_of(r, cut), r.size()), kReleaseStep + 1e-6)
        << "and nothing when the session ends";
    EXPECT_TRUE(ControllerStack::eventually(
        [&] { return s.stack.link_stats().watchdog_expiries == 1U; }, 3s))
        << "the bridge ended the session after its watchdog";
    return true;
  });
}

class FrozenBridge : public ::testing::TestWithParam<int> {};

TEST_P(FrozenBridge, FadesTheForceAndRecouplesWhenItThaws) {
  const int frozen_ms = GetParam();
  with_retries("bridge frozen " + std::to_string(frozen_ms), [&](int attempt) {
    Scenario s("h1-stop" + std::to_string(frozen_ms) + "-" + std::to_string(attempt), {});
    std::uint64_t coupled_at = 0;  // then 3 s for the sphere and the handle to come to rest
    if (const auto done = couple_and_record(s, 3s, coupled_at)) {
      return *done;
    }
    const std::uint64_t cut = s.recorder->newest_cycle();
    s.stack.bridge().signal(SIGSTOP);
    std::this_thread::sleep_for(std::chrono::milliseconds(frozen_ms));
    const std::uint64_t back = s.recorder->newest_cycle();
    s.stack.bridge().signal(SIGCONT);
    std::this_thread::sleep_for(2s);
    if (s.core_failed_safe()) {
      return false;
    }
    expect_faded_and_recoupled(s.recorder->records(), cut, back);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(H1, FrozenBridge, ::testing::Values(200, 2000));

}  // namespace
}  // namespace hapticctrl::test
