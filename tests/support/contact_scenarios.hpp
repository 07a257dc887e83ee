#pragma once
// Test support of the end-to-end contact tests (J1 contact_network_test.cpp, J2
// local_contact_network_test.cpp): the demo on a stiff wall, the operator through hapticctrl-hmi,
// and what a test reads of the cycle records (the force and speed over a span, the handle's
// position, the energy the port put into the hand).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "support/network_scenario.hpp"

namespace hapticctrl::test {

/// hapticctrl-hmi on the scenario's instance, run to its end (bounded).
inline int run_hmi(const Scenario& s, std::vector<std::string> args, std::chrono::seconds bound) {
  args.insert(args.begin(), {"--instance", s.stack.instance()});
  SpawnedProcess hmi(HAPTICCTRL_HMI_BINARY, args);
  return hmi.wait(bound);
}

/// The demo with its sphere on a wall `toward` of the handle, stiff and barely damped.
inline std::vector<std::string> wall_demo(double stiffness, const std::string& toward,
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
inline std::vector<std::string> with(std::vector<std::string> args,
                                     const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

/// Mean rendered force along `axis` and the windowed speed over records [from, to).
struct Judged {
  double force = 0.0;
  double speed = 0.0;
  int saturated = 0;
};

inline Judged judge(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to,
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

struct WallCase {
  const char* name;
  double stiffness;
  std::vector<std::string> impairment;
};

// NOLINTNEXTLINE(readability-identifier-naming): GoogleTest's name
inline void PrintTo(const WallCase& c, std::ostream* os) {
  *os << c.name;
}

/// The energy the port put out into the hand over records [from, to): the rendered force's
/// work on the handle's travel (positive: the device pushed the hand).
inline double port_energy(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to) {
  double energy = 0.0;
  for (std::size_t i = from + 1; i < std::min(to, r.size()); ++i) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      energy += r[i].wrench[axis] * (r[i].position[axis] - r[i - 1].position[axis]);
    }
  }
  return energy;
}

/// Mean handle position along `axis` over records [from, to).
inline double mean_position(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to,
                            std::size_t axis) {
  to = std::min(to, r.size());
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) {
    sum += r[i].position[axis];
  }
  return to > from ? sum / static_cast<double>(to - from) : std::nan("");
}

/// Waits until an IMPEDANCE client's wrenches flow (powered, the client fresh), then 0.5 s more:
/// pushed before, the handle went 7 cm into the wall before its first report arrived (100 ms
/// one way). nullopt: they flow; otherwise the attempt's verdict (false: retry, the machine).
inline std::optional<bool> wait_for_wrenches(Scenario& s) {
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

/// A 10 N push judged: the force felt and the speed over the push's 2nd and 3rd second, with the
/// records for a failure's report.
struct JudgedPush {
  Judged judged;
  std::vector<CycleRecord> records;
  std::size_t from = 0;
  std::size_t to = 0;
};

/// Pushes `force_x` N along x through the force region for 3 s and judges the last 2; nullopt
/// when the machine disturbed the attempt (the core failed safe, or the link was held up 30 ms
/// or more in the judged window), which with_retries then tries again.
inline std::optional<JudgedPush> push_and_judge(Scenario& s, double force_x, const char* name) {
  const std::uint64_t pushed_at = s.recorder->newest_cycle();
  EXPECT_EQ(run_hmi(s, {"force", std::to_string(force_x), "0", "0", "0", "0", "0"}, 10s), 0);
  std::this_thread::sleep_for(3s);
  if (s.core_failed_safe()) {
    return std::nullopt;
  }
  JudgedPush p;
  p.records = s.recorder->records();
  p.from = index_of(p.records, pushed_at + kCyclesPerSecond);
  p.to = index_of(p.records, pushed_at + 3 * kCyclesPerSecond);
  if (longest_silence(p.records, p.from, p.to) >= 30 * kCyclesPerSecond / 1000) {
    std::printf("%s: the link was held up in the judged window: tried again\n", name);
    return std::nullopt;
  }
  p.judged = judge(p.records, p.from, p.to, 0);
  return p;
}

}  // namespace hapticctrl::test
