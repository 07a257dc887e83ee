// hapticctrl-lcm: telemetry out (arm state, coupling, cycle and bridge statistics, events) and
// HMI traffic in (commands, operator force) between a running hapticctrl-core and LCM.
//
// Threads: a publisher thread blocks on VP publishes (one per controller cycle), reads the
// regions it needs into local copies and publishes what is due; this thread runs LCM's receive
// loop and the HMI force ramp. The core never waits for either. Exit: 0 on signal or --duration,
// 64 usage, 1 error.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/lcm_bridge/hmi_input.hpp"
#include "hapticctrl/lcm_bridge/lcm_bridge_config.hpp"
#include "hapticctrl/lcm_bridge/messages.hpp"
#include "hapticctrl/lcmtypes/regions.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/shm/core_watch.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace {

using hapticctrl::Duration;
using hapticctrl::MonotonicClock;
using hapticctrl::TimePoint;
using hapticctrl::lcm_bridge::Channels;
using hapticctrl::lcm_bridge::HmiInput;
using hapticctrl::lcm_bridge::LcmBridgeConfig;
namespace shm = hapticctrl::shm;
namespace lb = hapticctrl::lcm_bridge;
namespace lcmtypes = hapticctrl::lcmtypes;

std::atomic<bool> g_stop{false};
void on_signal(int /*sig*/) {
  g_stop.store(true);
}

/// LCM's utime of a moment on the monotonic clock (microseconds).
std::int64_t utime_of(TimePoint t) {
  return hapticctrl::to_ns(t) / 1000;
}

std::int64_t wall_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

struct PublishCounters {
  std::atomic<std::uint64_t> arm_state{0};
  std::atomic<std::uint64_t> cycle_stats{0};
  std::atomic<std::uint64_t> events{0};
  std::atomic<std::uint64_t> events_lost{0};
};

/// The bridge's own event (index 0: not from the core's sequence) when the core is gone.
hapticctrl_lcm::event_t core_gone_event(const shm::CoreWatch& watch, TimePoint now) {
  const shm::Event e{0,
                     watch.last_cycle(),
                     hapticctrl::to_ns(now),
                     shm::EventKind::kCoreState,
                     static_cast<std::uint32_t>(shm::CoreState::kStopped),
                     watch.stop_reason()};
  auto m = lb::to_event(e, 0, now, wall_now_us());
  char noticed[96];  // NOLINT(*-avoid-c-arrays)
  std::snprintf(noticed, sizeof noticed,
                " (noticed by the LCM bridge %.1f ms after its last heartbeat)",
                hapticctrl::to_seconds(watch.heartbeat_age_at_loss()) * 1e3);
  m.text += noticed;
  return m;
}

/// Publishes what is due after each controller cycle, until `running` clears or the core is
/// gone (then publishes that as an event and sets `core_gone`).
void publish_loop(const shm::Segment& seg, lcm::LCM& lcm, const Channels& ch,
                  const LcmBridgeConfig& config, const std::atomic<bool>& running,
                  std::atomic<bool>& core_gone, PublishCounters& counters) {
  const auto& vp_cell = seg.region<shm::RegionId::kVp>();
  shm::EventReader events(seg.region<shm::RegionId::kEvents>(), true);
  const Duration arm_every =
      config.arm_rate_hz > 0.0 ? hapticctrl::from_seconds(1.0 / config.arm_rate_hz) : Duration{};
  const Duration stats_every = hapticctrl::from_seconds(1.0 / config.stats_rate_hz);
  TimePoint next_arm{};
  TimePoint next_stats{};
  std::uint64_t lost_reported = 0;
  shm::CoreWatch watch(seg);
  while (running.load(std::memory_order_relaxed)) {
    const shm::CoreWatch::Wake wake = watch.wait();
    const TimePoint now = MonotonicClock::now();
    // Arm state after a cycle only (a silent 2 ms wake of the watch is no new state); statistics
    // by the clock; the regions are read only for what is due.
    const bool arm_due = wake == shm::CoreWatch::Wake::kCycle && now >= next_arm;
    const bool stats_due = now >= next_stats;
    // A region torn by a writer preempted in the middle of a write (the UDP bridge writes VPR
    // at normal priority) is published at the next wake, never as the payload's defaults.
    shm::TelemetryPayload telemetry;
    const bool telemetry_ok =
        (arm_due || stats_due) && seg.region<shm::RegionId::kTelemetry>().read(telemetry).ok();
    if (arm_due && telemetry_ok) {
      shm::PositionPayload position;
      shm::VpPayload vp;
      shm::VprPayload vpr;  // never written: no client yet, and its defaults say so
      if (seg.region<shm::RegionId::kPosition>().read(position).ok() && vp_cell.read(vp).ok() &&
          seg.region<shm::RegionId::kVpr>().read(vpr).status != shm::ReadStatus::kTorn) {
        next_arm =
            arm_every == Duration{} ? TimePoint{} : std::max(next_arm + arm_every, now - arm_every);
        auto arm = lcmtypes::to_arm_state(position, utime_of(now));
        lcm.publish(ch.arm_state, &arm);
        auto coupling = lb::to_coupling(vp, vpr, telemetry, now, utime_of(now));
        lcm.publish(ch.coupling, &coupling);
        counters.arm_state.fetch_add(1, std::memory_order_relaxed);
      }
    }
    if (stats_due && telemetry_ok) {
      next_stats = now + stats_every;
      auto stats = lcmtypes::to_cycle_stats(telemetry, utime_of(now));
      lcm.publish(ch.cycle_stats, &stats);
      counters.cycle_stats.fetch_add(1, std::memory_order_relaxed);
      shm::LinkStatsPayload link;
      if (seg.region<shm::RegionId::kLinkStats>().read(link).ok()) {
        auto bridge = lcmtypes::to_bridge_stats(link, utime_of(now));
        lcm.publish(ch.bridge_stats, &bridge);
      }
    }
    events.poll([&](const shm::Event& e) {
      auto m = lb::to_event(e, events.lost() - lost_reported, MonotonicClock::now(), wall_now_us());
      lost_reported = events.lost();
      lcm.publish(ch.events, &m);
      counters.events.fetch_add(1, std::memory_order_relaxed);
    });
    counters.events_lost.store(events.lost(), std::memory_order_relaxed);
    if (wake == shm::CoreWatch::Wake::kCoreGone) {  // after the core's own last events
      auto m = core_gone_event(watch, now);
      lcm.publish(ch.events, &m);
      counters.events.fetch_add(1, std::memory_order_relaxed);
      std::fprintf(stderr, "hapticctrl-lcm: controller '%s': %s\n", seg.instance().c_str(),
                   m.text.c_str());
      core_gone.store(true);
      return;
    }
  }
}

/// Serves one controller until it goes away, the bridge is told to stop, or `end` passes.
void run_attached(shm::Segment& seg, lcm::LCM& lcm, const Channels& ch,
                  const LcmBridgeConfig& config, TimePoint end, PublishCounters& counters,
                  lb::HmiSettings& settings, std::string& hmi_json) {
  HmiInput hmi(settings, &seg.ctrl_writer(),
               settings.allow_remote_commands ? &seg.writable<shm::RegionId::kForce>() : nullptr);
  auto command_sub = lcm.subscribeFunction(
      ch.hmi_command,
      +[](const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/, HmiInput* input) {
        input->on_command(rbuf->data, rbuf->data_size, MonotonicClock::now());
      },
      &hmi);
  auto force_sub = lcm.subscribeFunction(
      ch.hmi_force,
      +[](const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/, HmiInput* input) {
        input->on_force(rbuf->data, rbuf->data_size, MonotonicClock::now());
      },
      &hmi);
  std::atomic<bool> publishing{true};
  std::atomic<bool> core_gone{false};
  std::thread publisher(
      [&] { publish_loop(seg, lcm, ch, config, publishing, core_gone, counters); });
  while (!g_stop.load() && !core_gone.load()) {
    lcm.handleTimeout(2);
    const TimePoint now = MonotonicClock::now();
    hmi.tick(now);
    if (now >= end) {
      g_stop.store(true);
    }
  }
  publishing.store(false);
  publisher.join();
  lcm.unsubscribe(command_sub);
  lcm.unsubscribe(force_sub);
  hmi_json = shm::counters_json(hmi.counters());
}

int run(const LcmBridgeConfig& config) {
  lcm::LCM lcm(config.lcm_url);
  if (!lcm.good()) {
    throw std::runtime_error("cannot open LCM at '" + config.lcm_url + "'");
  }
  const Channels ch = Channels::of(config.instance);
  lb::HmiSettings settings;
  settings.allow_remote_commands = config.allow_remote_commands;
  PublishCounters counters;
  std::string hmi_json = "\"commands_applied\":0";
  const TimePoint end = hapticctrl::end_after(config.duration_s);
  std::fprintf(stderr, "hapticctrl-lcm: instance '%s' on %s, channels %s.*, remote commands %s\n",
               config.instance.c_str(), config.lcm_url.c_str(),
               ("hapticctrl." + config.instance).c_str(),
               config.allow_remote_commands ? "enabled" : "disabled (emergency stop only)");
  bool said_waiting = false;
  while (!g_stop.load()) {
    std::optional<shm::Segment> seg = shm::Segment::try_attach(
        config.instance, shm::RemoteCommands::attach_options(config.allow_remote_commands));
    if (seg) {
      said_waiting = false;
      run_attached(*seg, lcm, ch, config, end, counters, settings, hmi_json);
      continue;
    }
    if (!said_waiting) {
      std::fprintf(stderr, "hapticctrl-lcm: no controller for instance '%s' yet; waiting\n",
                   config.instance.c_str());
      said_waiting = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (MonotonicClock::now() >= end) {
      g_stop.store(true);
    }
  }
  if (config.json) {
    std::printf(
        "{\"arm_state\":%llu,\"cycle_stats\":%llu,\"events\":%llu,\"events_lost\":%llu,%s}\n",
        static_cast<unsigned long long>(counters.arm_state.load()),
        static_cast<unsigned long long>(counters.cycle_stats.load()),
        static_cast<unsigned long long>(counters.events.load()),
        static_cast<unsigned long long>(counters.events_lost.load()), hmi_json.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<LcmBridgeConfig>(
      "hapticctrl-lcm", argc, argv,
      [](const std::vector<std::string>& args, LcmBridgeConfig& c) {
        c = LcmBridgeConfig::parse(args);
        return !c.help;
      },
      &LcmBridgeConfig::usage,
      [](const LcmBridgeConfig& c) {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return run(c);
      });
}
