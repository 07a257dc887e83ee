#pragma once
/// A small, known LCM log as hapticctrl-lcm would record it (instance "lab"): the input of the
/// CSV conversion test and of the Java decoding test.
#include <algorithm>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/cycle_stats_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/scene_t.hpp"

namespace hapticctrl::test {

inline constexpr int kSampleArmStates = 5;

template <typename M>
void log_message(lcm::LogFile& log, const std::string& channel, const M& m, std::int64_t t) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  lcm::LogEvent ev{};
  ev.timestamp = t;
  ev.channel = channel;
  ev.datalen = static_cast<std::int32_t>(b.size());
  ev.data = b.data();
  log.writeEvent(&ev);
}

/// Writes the sample log: 5 arm states (handle x = 0.1 * cycle m, operator fx = cycle N),
/// 2 cycle stats, 2 events, one demo scene, one message of another application and one
/// corrupted arm state.
/// The handle moves `x_step` metres along x per arm_state (0: it rests).
inline void write_sample_log(const std::string& path, double x_step = 0.1) {
  lcm::LogFile log(path, "w");
  if (!log.good()) {
    throw std::runtime_error("cannot write " + path);
  }
  std::int64_t t = 1'000'000;
  for (int cycle = 1; cycle <= kSampleArmStates; ++cycle) {
    hapticctrl_lcm::arm_state_t a{};
    a.utime = t;
    a.cycle = cycle;
    a.state_word = 1;
    a.core_state = 1;
    a.handle_pose[0] = x_step * cycle;
    a.handle_pose[6] = 1.0;
    a.operator_wrench[0] = cycle;
    a.rendered_wrench[2] = -0.5 * cycle;
    log_message(log, "hapticctrl.lab.arm_state", a, t);
    t += 10'000;
  }
  for (int i = 1; i <= 2; ++i) {
    hapticctrl_lcm::cycle_stats_t s{};
    s.utime = t;
    s.cycle = std::int64_t{100} * i;
    s.period_ns = 1'000'000;
    s.wake_latency.p99_ns = 90'000;
    const std::int64_t edges[12] = {2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000};
    std::copy(std::begin(edges), std::end(edges), s.histogram_edges_us);  // NOLINT(*-c-arrays)
    s.wake_histogram[5] = std::int64_t{60} * i;
    s.wake_histogram[6] = std::int64_t{30} * i;
    s.wake_histogram[12] = i;
    log_message(log, "hapticctrl.lab.cycle_stats", s, t);
    t += 100'000;
  }
  hapticctrl_lcm::event_t e{};
  e.utime = t;
  e.index = 1;
  e.cycle = 3;
  e.kind = "power";
  e.code = 1;
  e.text = "power on";
  log_message(log, "hapticctrl.lab.events", e, t);
  e.index = 2;
  e.cycle = 250;
  e.kind = "core_state";
  e.code = 2;
  e.value = 1;
  e.text = "fail-safe: 5 consecutive deadline misses, \"black box\" written";
  log_message(log, "hapticctrl.lab.events", e, t + 1);
  hapticctrl_lcm::scene_t scene{};
  scene.utime = t;
  scene.steps = 1234;
  scene.fixed_center[0] = 0.7;
  scene.mobile_pose[6] = 1.0;
  scene.contact_force[0] = -4.5;
  scene.answers_received = 1200;
  log_message(log, "hapticctrl.lab.scene", scene, t + 1);
  log_message(log, "other.application", e, t + 2);
  std::vector<std::uint8_t> junk{1, 2, 3};
  lcm::LogEvent bad{};
  bad.timestamp = t + 3;
  bad.channel = "hapticctrl.lab.arm_state";
  bad.datalen = 3;
  bad.data = junk.data();
  log.writeEvent(&bad);
}

}  // namespace hapticctrl::test
