#pragma once
/// The test side of LCM: subscribes to what hapticctrl-lcm publishes for one instance, counts
/// and keeps it, and sends HMI commands.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <vector>

#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/cycle_stats_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/hmi_command_t.hpp"

namespace hapticctrl::test {

using namespace std::chrono_literals;

/// A fresh loopback-only LCM URL (ttl=0) per call, per test process.
inline std::string unique_lcm_url() {
  static int counter = 0;
  return "udpm://239.255.76.67:" + std::to_string(7700 + (getpid() % 200) * 4 + counter++ % 4) +
         "?ttl=0";
}

/// A monitor on the test side: counts and keeps what hapticctrl-lcm publishes.
struct LcmMonitor {
  lcm::LCM lcm;
  std::string prefix;
  std::atomic<int> arm_states{0};
  std::atomic<int> cycle_stats{0};
  std::atomic<std::int32_t> last_state_word{0};
  std::vector<hapticctrl_lcm::event_t> events;
  std::mutex events_mutex;

  LcmMonitor(const std::string& url, const std::string& instance)
      : lcm(url), prefix("hapticctrl." + instance + ".") {
    // Raw subscriptions decoded here: Debian LCM 1.3.1's typed member-function subscription
    // trips UBSan inside its own header.
    lcm.subscribeFunction(prefix + "arm_state",
                          &LcmMonitor::raw<hapticctrl_lcm::arm_state_t, &LcmMonitor::on_arm>, this);
    lcm.subscribeFunction(prefix + "cycle_stats",
                          &LcmMonitor::raw<hapticctrl_lcm::cycle_stats_t, &LcmMonitor::on_stats>,
                          this);
    lcm.subscribeFunction(prefix + "events",
                          &LcmMonitor::raw<hapticctrl_lcm::event_t, &LcmMonitor::on_event>, this);
  }
  template <typename M,
            void (LcmMonitor::*Handler)(const lcm::ReceiveBuffer*, const std::string&, const M*)>
  static void raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel, LcmMonitor* self) {
    M m{};
    if (m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0) {
      (self->*Handler)(rbuf, channel, &m);
    }
  }
  void on_arm(const lcm::ReceiveBuffer*, const std::string&, const hapticctrl_lcm::arm_state_t* m) {
    ++arm_states;
    last_state_word = m->state_word;
  }
  void on_stats(const lcm::ReceiveBuffer*, const std::string&,
                const hapticctrl_lcm::cycle_stats_t*) {
    ++cycle_stats;
  }
  void on_event(const lcm::ReceiveBuffer*, const std::string&, const hapticctrl_lcm::event_t* m) {
    const std::lock_guard lock(events_mutex);
    events.push_back(*m);
  }
  /// Handles incoming messages for `duration`.
  void pump(std::chrono::milliseconds duration) {
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
      lcm.handleTimeout(10);
    }
  }
  template <typename Predicate>
  bool pump_until(Predicate p, std::chrono::milliseconds timeout = 3s) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end && !p()) {
      lcm.handleTimeout(10);
    }
    return p();
  }
  void send(std::int32_t code) {
    hapticctrl_lcm::hmi_command_t c{};
    c.command = code;
    c.origin = "hapticctrl tests";
    lcm.publish(prefix + "hmi_command", &c);
  }
  std::vector<hapticctrl_lcm::event_t> events_copy() {
    const std::lock_guard lock(events_mutex);
    return events;
  }
  bool saw_event(const std::string& text) {
    const std::lock_guard lock(events_mutex);
    for (const auto& e : events) {
      if (e.text == text) {
        return true;
      }
    }
    return false;
  }
};

}  // namespace hapticctrl::test
