// hapticctrl-dds: the controller's arm state out as ROS 2 topics over DDS (Cyclone DDS), and
// commands and the operator wrench in, so a ROS 2 node on another machine sees the arm without
// any hapticctrl package (docs/ros2.md).
//
// Threads: a publisher thread blocks on VP publishes (one per controller cycle), reads the
// regions it needs into local copies and writes what is due; this thread waits on the command
// readers and ramps the operator wrench. The core never waits for either. Exit: 0 on signal or
// --duration, 64 usage, 1 error.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/dds_bridge/commands.hpp"
#include "hapticctrl/dds_bridge/dds_bridge_config.hpp"
#include "hapticctrl/dds_bridge/endpoints.hpp"
#include "hapticctrl/dds_bridge/graph.hpp"
#include "hapticctrl/dds_bridge/messages.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/shm/core_watch.hpp"
#include "hapticctrl/shm/names.hpp"
#include "hapticctrl/shm/remote_commands.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace {

namespace shm = hapticctrl::shm;
namespace db = hapticctrl::dds_bridge;
using hapticctrl::Duration;
using hapticctrl::MonotonicClock;
using hapticctrl::TimePoint;
using hapticctrl::dds_bridge::DdsBridgeConfig;
using hapticctrl::dds_bridge::Endpoints;

std::atomic<bool> g_stop{false};
void on_signal(int /*sig*/) {
  g_stop.store(true);
}

struct PublishCounters {
  std::atomic<std::uint64_t> arm_samples{0};  ///< each: pose, two wrenches, joint states
  std::atomic<std::uint64_t> diagnostics{0};
  std::atomic<std::uint64_t> write_errors{0};
};

void write(dds_entity_t writer, const void* sample, PublishCounters& counters) {
  if (dds_write(writer, sample) < 0) {
    counters.write_errors.fetch_add(1, std::memory_order_relaxed);
  }
}

/// What the publisher thread owns: the messages it fills in place, and its schedule.
struct Publisher {
  Publisher(const DdsBridgeConfig& config, const std::string& frame)
      : arm(frame),
        diagnostics("hapticctrl-core", config.instance, frame),
        arm_every(config.rate_hz > 0.0 ? hapticctrl::from_seconds(1.0 / config.rate_hz)
                                       : Duration{}),
        diagnostics_every(hapticctrl::from_seconds(1.0 / config.diagnostics_rate_hz)) {}
  db::ArmMessages arm;
  db::DiagnosticsMessage diagnostics;
  Duration arm_every;
  Duration diagnostics_every;
};

/// Writes what is due after each controller cycle, until `running` clears or the core is gone
/// (then writes a last, STALE diagnostics and sets `core_gone`).
void publish_loop(const shm::Segment& seg, const Endpoints& ep, Publisher& pub,
                  const std::atomic<bool>& running, std::atomic<bool>& core_gone,
                  PublishCounters& counters) {
  TimePoint next_arm{};
  TimePoint next_diagnostics{};
  shm::CoreWatch watch(seg);
  shm::TelemetryPayload telemetry;
  while (running.load(std::memory_order_relaxed)) {
    const shm::CoreWatch::Wake wake = watch.wait();
    const TimePoint now = MonotonicClock::now();
    if (wake == shm::CoreWatch::Wake::kCycle && now >= next_arm) {
      next_arm = pub.arm_every == Duration{}
                     ? TimePoint{}
                     : std::max(next_arm + pub.arm_every, now - pub.arm_every);
      shm::PositionPayload position;
      const shm::ReadResult r = seg.region<shm::RegionId::kPosition>().read(position);
      if (r.ok()) {
        pub.arm.fill(position, r.publish_time_ns);
        write(ep.handle_pose, &pub.arm.pose, counters);
        write(ep.rendered_wrench, &pub.arm.rendered_wrench, counters);
        write(ep.operator_wrench, &pub.arm.operator_wrench, counters);
        write(ep.joint_states, &pub.arm.joints, counters);
        counters.arm_samples.fetch_add(1, std::memory_order_relaxed);
      }
    }
    const bool gone = wake == shm::CoreWatch::Wake::kCoreGone;
    if (now >= next_diagnostics || gone) {
      next_diagnostics = now + pub.diagnostics_every;
      const shm::ReadResult r = seg.region<shm::RegionId::kTelemetry>().read(telemetry);
      pub.diagnostics.fill(telemetry, !gone,
                           r.ok() && !gone ? r.publish_time_ns : hapticctrl::to_ns(now));
      write(ep.diagnostics, &pub.diagnostics.array, counters);
      counters.diagnostics.fetch_add(1, std::memory_order_relaxed);
    }
    if (gone) {
      std::fprintf(stderr, "hapticctrl-dds: controller '%s' is gone (%s); waiting for the next\n",
                   seg.instance().c_str(), shm::stop_reason_name(watch.stop_reason()));
      core_gone.store(true);
      return;
    }
  }
}

/// Serves one controller until it goes away, the bridge is told to stop, or `end` passes.
/// Returns the counters of the commands this attachment applied.
std::string run_attached(shm::Segment& seg, const Endpoints& ep, Publisher& pub,
                         dds_entity_t waitset, const DdsBridgeConfig& config, TimePoint end,
                         PublishCounters& counters) {
  shm::RemoteCommandSettings settings;
  settings.allow_remote_commands = config.allow_remote_commands;
  shm::RemoteCommands remote(
      settings, &seg.ctrl_writer(),
      config.allow_remote_commands ? &seg.writable<shm::RegionId::kForce>() : nullptr);
  std::atomic<bool> publishing{true};
  std::atomic<bool> core_gone{false};
  std::thread publisher([&] { publish_loop(seg, ep, pub, publishing, core_gone, counters); });
  while (!g_stop.load() && !core_gone.load()) {
    dds_waitset_wait(waitset, nullptr, 0, DDS_MSECS(2));
    const TimePoint now = MonotonicClock::now();
    hapticctrl::ros2types::take_each<std_msgs_msg_dds__String_>(
        ep.command, [&](const auto& m) { remote.command(db::command_of(m), now); });
    hapticctrl::ros2types::take_each<geometry_msgs_msg_dds__WrenchStamped_>(
        ep.operator_wrench_command, [&](const auto& m) { remote.force(db::wrench_of(m), now); });
    remote.tick(now);
    if (now >= end) {
      g_stop.store(true);
    }
  }
  publishing.store(false);
  publisher.join();
  return shm::counters_json(remote.counters());
}

int run(const DdsBridgeConfig& config) {
  const std::uint32_t domain = config.domain();
  hapticctrl::ros2types::Participant participant(domain);
  const Endpoints ep(participant, config.ros_namespace);
  const hapticctrl::dds_bridge::GraphAnnouncement node(participant, ep, config.ros_namespace);
  const dds_entity_t waitset = participant.waitset_for({ep.command, ep.operator_wrench_command});
  Publisher pub(config, hapticctrl::ros2types::base_frame(config.ros_namespace));
  PublishCounters counters;
  std::string commands_json = "\"commands_applied\":0";
  const TimePoint end = hapticctrl::end_after(config.duration_s);
  std::fprintf(stderr,
               "hapticctrl-dds: instance '%s', DDS domain %u, ROS 2 namespace %s, remote "
               "commands %s\n",
               config.instance.c_str(), domain, config.ros_namespace.c_str(),
               config.allow_remote_commands ? "enabled" : "disabled (emergency stop only)");
  bool said_waiting = false;
  while (!g_stop.load()) {
    std::optional<shm::Segment> seg = shm::Segment::try_attach(
        config.instance, shm::RemoteCommands::attach_options(config.allow_remote_commands));
    if (seg) {
      said_waiting = false;
      commands_json = run_attached(*seg, ep, pub, waitset, config, end, counters);
      continue;
    }
    if (!said_waiting) {
      std::fprintf(stderr, "hapticctrl-dds: no controller for instance '%s' yet; waiting\n",
                   config.instance.c_str());
      said_waiting = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (MonotonicClock::now() >= end) {
      g_stop.store(true);
    }
  }
  if (config.json) {
    std::printf("{\"arm_samples\":%llu,\"diagnostics\":%llu,\"write_errors\":%llu,%s}\n",
                static_cast<unsigned long long>(counters.arm_samples.load()),
                static_cast<unsigned long long>(counters.diagnostics.load()),
                static_cast<unsigned long long>(counters.write_errors.load()),
                commands_json.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<DdsBridgeConfig>(
      "hapticctrl-dds", argc, argv,
      [](const std::vector<std::string>& args, DdsBridgeConfig& c) {
        c = DdsBridgeConfig::parse(args);
        return !c.help;
      },
      &DdsBridgeConfig::usage,
      [](const DdsBridgeConfig& c) {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return run(c);
      });
}
