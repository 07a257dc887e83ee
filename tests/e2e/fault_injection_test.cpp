// Fault injection with every process real on loopback: processes killed at random moments and
// restarted, the core killed under its bridges, a bridge frozen longer than the watchdog, and a
// shared-memory writer that breaks every rule. Throughout, the forces on the handle may change
// by no more than their rate limits allow, and the core keeps its cycle.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/rt_core/arm_model.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "support/controller_stack.hpp"
#include "support/lcm_monitor.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

/// 4 ms as in the demo's end-to-end tests (a 10 ms VM stall must cost fewer than five misses);
/// instrumented builds run the behaviour tests' 10 ms cycle.
#ifdef HAPTICCTRL_SANITIZED
constexpr int kPeriodUs = ControllerStack::kDefaultPeriodUs;
#else
constexpr int kPeriodUs = 4000;
#endif
constexpr double kPeriodS = kPeriodUs * 1e-6;

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// Follows every cycle of a core from a thread and keeps the largest change, per cycle, of the
/// wrench the motors put on the handle (coupling, norm) and of the operator's wrench (per axis),
/// and whether the core ever left its running state.
class ForceStepWatch {
 public:
  explicit ForceStepWatch(const shm::Segment& segment)
      : segment_(segment), thread_([this] { follow(); }) {}
  ForceStepWatch(const ForceStepWatch&) = delete;
  ForceStepWatch& operator=(const ForceStepWatch&) = delete;
  ~ForceStepWatch() { stop(); }

  void stop() {
    running_ = false;
    if (thread_.joinable()) {
      thread_.join();
    }
  }
  [[nodiscard]] double largest_coupling_step() const { return coupling_step_; }
  [[nodiscard]] double largest_operator_step() const { return operator_step_; }
  [[nodiscard]] bool left_running() const { return left_running_; }
  [[nodiscard]] std::uint64_t cycles() const { return cycles_; }

 private:
  void follow() {
    const auto& vp = segment_.region<shm::RegionId::kVp>();
    const auto& position = segment_.region<shm::RegionId::kPosition>();
    shm::PositionPayload last;
    bool have_last = false;
    while (running_) {
      vp.wait_for_publish(vp.sequence_word(), 50ms);
      shm::PositionPayload p;
      if (!position.read(p).ok() || (have_last && p.cycle == last.cycle)) {
        continue;
      }
      if (p.core_state != static_cast<std::uint32_t>(shm::CoreState::kRunning)) {
        left_running_ = true;
      }
      if (have_last && p.cycle > last.cycle) {
        const auto gap = static_cast<double>(p.cycle - last.cycle);
        const double coupling = std::hypot(p.coupling_wrench[0] - last.coupling_wrench[0],
                                           p.coupling_wrench[1] - last.coupling_wrench[1],
                                           p.coupling_wrench[2] - last.coupling_wrench[2]);
        coupling_step_ = std::max(coupling_step_.load(), coupling / gap);
        for (std::size_t i = 0; i < 3; ++i) {
          const double step = std::abs(p.operator_wrench[i] - last.operator_wrench[i]) / gap;
          operator_step_ = std::max(operator_step_.load(), step);
        }
        ++cycles_;
      }
      last = p;
      have_last = true;
    }
  }

  const shm::Segment& segment_;
  std::atomic<bool> running_{true};
  std::atomic<double> coupling_step_{0.0};
  std::atomic<double> operator_step_{0.0};
  std::atomic<bool> left_running_{false};
  std::atomic<std::uint64_t> cycles_{0};
  std::thread thread_;
};

/// The largest change per cycle the core's rate limiter lets the coupling force make [N].
double coupling_step_limit() {
  return rt_core::load_arm_model(rt_core::default_arm_model_path()).limits.force_rate * kPeriodS;
}
/// The same for the operator's force, ramped by the HMI (per axis) [N].
double operator_step_limit() {
  return shm::ForceLimits{}.force_rate * kPeriodS;
}
constexpr double kRounding = 1e-9;

shm::TelemetryPayload telemetry_of(const ControllerStack& stack) {
  shm::TelemetryPayload t;
  stack.segment().region<shm::RegionId::kTelemetry>().read(t);
  return t;
}

bool coupled(const ControllerStack& stack) {
  return (stack.vp().state_word & shm::state_bits::kCoupled) != 0;
}

/// The number after `marker` in the last line of `text` that has it (NaN if none).
double last_number_after(const std::string& text, const std::string& marker) {
  const auto at = text.rfind(marker);
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + marker.size()));
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[v.size() / 2];
}

// Each start_* (re)starts a process in `p` (killing the one it held, if any).
void start_lcm_bridge(std::optional<SpawnedProcess>& p, const ControllerStack& stack,
                      const std::string& url) {
  p.reset();
  p.emplace(HAPTICCTRL_LCM_BINARY,
            std::vector<std::string>{"--instance", stack.instance(), "--lcm-url", url});
}

void start_demo(std::optional<SpawnedProcess>& p, const ControllerStack& stack) {
  p.reset();
  p.emplace(HAPTICCTRL_DEMO_BINARY,
            std::vector<std::string>{"--server", "127.0.0.1:" + std::to_string(stack.port()),
                                     "--headless"});
}

/// A minute of operator force changing every 0.25 s to a random push of up to 6 N per axis.
std::string write_random_force_sequence(std::mt19937& rng) {
  const std::string path = "/tmp/hapticctrl-fault-" + std::to_string(getpid()) + ".seq";
  std::ofstream out(path);
  std::uniform_real_distribution<double> force(-6.0, 6.0);
  for (int i = 0; i < 240; ++i) {
    out << i * 0.25 << ' ' << force(rng) << ' ' << force(rng) << ' ' << force(rng)
        << " 0 0 0\n";
  }
  return path;
}

void start_player(std::optional<SpawnedProcess>& p, const ControllerStack& stack,
                  const std::string& sequence) {
  p.reset();
  p.emplace(HAPTICCTRL_HMI_BINARY,
            std::vector<std::string>{"--instance", stack.instance(), "play", sequence});
}

TEST(FaultInjection, SoftRealTimeProcessesKilledAtRandomMomentsComeBackWithoutAForceStep) {
  ControllerStack stack("fi-soft", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string url = unique_lcm_url();
  LcmMonitor monitor(url, stack.instance());
  const unsigned seed = 20261201;
  std::mt19937 rng(seed);
  const std::string sequence = write_random_force_sequence(rng);
  std::optional<SpawnedProcess> lcm;
  std::optional<SpawnedProcess> demo;
  std::optional<SpawnedProcess> player;
  start_lcm_bridge(lcm, stack, url);
  start_demo(demo, stack);
  ASSERT_TRUE(ControllerStack::eventually([&] { return coupled(stack); }, 10s)) << demo->err();
  start_player(player, stack, sequence);
  ForceStepWatch watch(stack.segment());
  const std::uint64_t misses_before = telemetry_of(stack).misses_total;

  // Each victim comes back by being started again; the demo also when its bridge was killed
  // (a client does not reconnect on its own: a new session re-couples the sphere wherever it is).
  const auto restart_demo = [&] {
    demo->wait(5s);  // it leaves once its bridge is silent for 500 ms
    start_demo(demo, stack);
    EXPECT_TRUE(ControllerStack::eventually([&] { return coupled(stack); }, 10s)) << demo->err();
  };
  const std::array<const char*, 4> names{"hapticctrl-udp", "hapticctrl-lcm", "hapticctrl-demo",
                                         "hapticctrl-hmi play"};
  std::uniform_int_distribution<std::size_t> victim_of(0, 3);
  std::uniform_int_distribution<int> pause_ms(100, 600);
  for (int round = 0; round < 8; ++round) {
    std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms(rng)));
    const std::size_t victim = victim_of(rng);
    SCOPED_TRACE(std::string("round ") + std::to_string(round) + ": SIGKILL " + names[victim] +
                 " (seed " + std::to_string(seed) + ")");
    switch (victim) {
      case 0:
        stack.bridge().signal(SIGKILL);
        stack.bridge().wait(5s);
        stack.start_bridge();
        restart_demo();
        break;
      case 1: {
        lcm->signal(SIGKILL);
        lcm->wait(5s);
        start_lcm_bridge(lcm, stack, url);
        const int seen = monitor.arm_states;
        EXPECT_TRUE(monitor.pump_until([&] { return monitor.arm_states > seen + 10; }, 5s))
            << lcm->err();
        break;
      }
      case 2:
        demo->signal(SIGKILL);
        restart_demo();
        break;
      default: {
        player->signal(SIGKILL);
        player->wait(5s);
        start_player(player, stack, sequence);
        EXPECT_TRUE(ControllerStack::eventually([&] {
          const auto writer = stack.segment().writer_of(shm::RegionId::kForce);
          return writer && writer->pid == player->pid();
        })) << player->err();
        break;
      }
    }
  }
  watch.stop();
  std::remove(sequence.c_str());
  const shm::TelemetryPayload t = telemetry_of(stack);
  std::printf("%llu cycles watched; largest steps per cycle: coupling %.4f N (limit %.4f), "
              "operator %.4f N (limit %.4f); deadline misses %llu\n",
              static_cast<unsigned long long>(watch.cycles()), watch.largest_coupling_step(),
              coupling_step_limit(), watch.largest_operator_step(), operator_step_limit(),
              static_cast<unsigned long long>(t.misses_total - misses_before));
  EXPECT_GT(watch.cycles(), 100U);
  EXPECT_LE(watch.largest_coupling_step(), coupling_step_limit() + kRounding);
  EXPECT_LE(watch.largest_operator_step(), operator_step_limit() + kRounding);
  EXPECT_FALSE(watch.left_running()) << stack.diagnostics();
  EXPECT_EQ(t.core_state, static_cast<std::uint32_t>(shm::CoreState::kRunning));
  // A VM stall on this machine can cost a miss or two (never five in a row: the core would
  // have failed safe, which left_running() reports); killing a process must not cost more.
  EXPECT_LE(t.misses_total - misses_before, 4U);
  EXPECT_GT(t.ctrl_accepted, 0U);
}

TEST(FaultInjection, AKilledCoreIsToldToClientAndLcmWithinMillisecondsAndTheNextCoreIsServed) {
  ControllerStack stack("fi-core", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string url = unique_lcm_url();
  LcmMonitor monitor(url, stack.instance());
  std::optional<SpawnedProcess> lcm;
  start_lcm_bridge(lcm, stack, url);
  std::vector<double> client_ms;
  std::vector<double> udp_heartbeat_ms;
  std::vector<double> lcm_heartbeat_ms;
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    client::ConnectOptions options;
    options.connect_timeout = 5s;  // the bridge attaches to a new core within 100 ms
    client::Connection c({"127.0.0.1", stack.port()}, options);
    client::StateSnapshot s;
    ASSERT_TRUE(c.wait_for_answer(0, 2s, s));
    ASSERT_TRUE(monitor.pump_until([&] { return monitor.arm_states > 0; }, 5s)) << lcm->err();
    const std::size_t events_before = monitor.events_copy().size();

    const std::int64_t killed_at = monotonic_ns();
    stack.core().signal(SIGKILL);
    stack.core().wait(5s);
    ASSERT_TRUE(ControllerStack::eventually([&] { return !c.is_open(); }, 2s));
    s = c.snapshot();
    EXPECT_EQ(s.core_state, static_cast<std::uint32_t>(shm::CoreState::kStopped));
    EXPECT_EQ(s.stop_reason, static_cast<std::uint32_t>(shm::StopReason::kCoreLost));
    EXPECT_FALSE(s.powered());
    client_ms.push_back(static_cast<double>(s.received_ns - killed_at) * 1e-6);
    EXPECT_THROW(c.set_power(true), client::ClientError);

    ASSERT_TRUE(monitor.pump_until(
        [&] {
          const auto events = monitor.events_copy();
          return events.size() > events_before && events.back().index == 0;
        },
        2s));
    const auto gone = monitor.events_copy().back();
    EXPECT_EQ(gone.kind, "core_state");
    EXPECT_EQ(gone.value, static_cast<std::int64_t>(shm::StopReason::kCoreLost)) << gone.text;
    lcm_heartbeat_ms.push_back(last_number_after(gone.text, "bridge "));
    const std::string said = "noticed ";
    ASSERT_TRUE(ControllerStack::eventually([&] {
      return count_of(stack.bridge().err(), said) == static_cast<std::size_t>(round) + 1;
    })) << stack.bridge().err();
    udp_heartbeat_ms.push_back(last_number_after(stack.bridge().err(), said));

    stack.start_core();  // replaces the segment the killed core left
    ASSERT_TRUE(stack.ready()) << stack.diagnostics();
    EXPECT_EQ(stack.core().err().find("already running"), std::string::npos);
  }
  const auto print = [](const char* what, const std::vector<double>& v) {
    std::printf("%s:", what);
    for (const double x : v) {
      std::printf(" %.2f", x);
    }
    std::printf(" ms\n");
  };
  print("SIGKILL to the client's last answer", client_ms);
  print("last heartbeat to the UDP bridge noticing", udp_heartbeat_ms);
  print("last heartbeat to the LCM bridge noticing", lcm_heartbeat_ms);
  // The median: one VM stall of several milliseconds (seen on this machine) must not decide.
  // Heartbeat ages include up to one period (the core beats once per cycle).
  EXPECT_LE(median(client_ms), 10.0);
  EXPECT_LE(median(udp_heartbeat_ms), 10.0 + kPeriodUs * 1e-3);
  EXPECT_LE(median(lcm_heartbeat_ms), 10.0 + kPeriodUs * 1e-3);
}

}  // namespace
}  // namespace hapticctrl::test
