// hapticctrl-core: the hard-real-time core process.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/rt_core/arm_dynamics.hpp"
#include "hapticctrl/rt_core/arm_simulator.hpp"
#include "hapticctrl/rt_core/black_box.hpp"
#include "hapticctrl/rt_core/core_config.hpp"
#include "hapticctrl/rt_core/core_report.hpp"
#include "hapticctrl/rt_core/estop_latch.hpp"
#include "hapticctrl/rt_core/executive.hpp"
#include "hapticctrl/rt_core/restart_marker.hpp"
#include "hapticctrl/rt_core/rt_preflight.hpp"
#include "hapticctrl/rt_core/servo.hpp"
#include "hapticctrl/rt_core/threaded_servo_tasks.hpp"
#include "hapticctrl/shm/names.hpp"
#include "hapticctrl/shm/rendezvous.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace {

using namespace hapticctrl;
using namespace hapticctrl::rt_core;

std::atomic<bool> g_signal_stop{false};

/// Says that a miss rule tripped on a stall of the machine, and how long: scripts/run.sh starts
/// the demo again at a longer period on this (J5), never on a fail-safe the software caused.
std::string stall_text(Duration tripped_by_stall) {
  if (tripped_by_stall <= Duration{0}) {
    return "";
  }
  char text[96];
  std::snprintf(text, sizeof text, ", on a stall of the machine (the clock woke %.1f ms late)",
                std::chrono::duration<double, std::milli>(tripped_by_stall).count());
  return text;
}
static_assert(std::atomic<bool>::is_always_lock_free, "used from a signal handler");

/// The latch keeper polls this often: a core killed this long after the stop latched may lose
/// it (the window is documented in docs/rt_core.md).
constexpr auto kLatchPoll = std::chrono::milliseconds(2);

/// Makes the latch file agree with the emergency-stop bit of the last published VP. Returns
/// false when the file could not be written or removed (said on stderr if `say_failure`).
bool follow_latch(EstopLatchFile& latch, const shm::Segment& segment, bool say_failure = true) {
  shm::VpPayload vp;
  if (!segment.region<shm::RegionId::kVp>().read(vp).ok()) {
    return true;  // nothing published yet
  }
  try {
    latch.follow((vp.state_word & shm::state_bits::kEmergencyStop) != 0);
    return true;
  } catch (const std::exception& e) {
    if (say_failure) {
      std::cerr << "hapticctrl-core: the emergency stop's latch file: " << e.what() << "\n";
    }
    return false;
  }
}

/// Keeps the latch file in step with the state the cycle publishes (VP's state word), so that a
/// core killed after the stop latched leaves it latched for the next one. A plain thread: its
/// file I/O never touches the cycle, which only publishes VP.
std::jthread start_latch_keeper(EstopLatchFile& latch, const shm::Segment& segment) {
  return std::jthread([&latch, &segment](const std::stop_token& stop) {
    bool failing = false;  // said once per run of failures, not every 2 ms
    while (!stop.stop_requested()) {
      failing = !follow_latch(latch, segment, !failing);
      std::this_thread::sleep_for(kLatchPoll);
    }
  });
}

void on_stop_signal(int /*signal*/) {
  g_signal_stop.store(true, std::memory_order_release);
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

/// auto: the last CPU (CLOCK and SERVO share it; see docs/rt_core.md for the measurement). A
/// CPU the machine does not have is a usage error (it was ignored, while the log said "cpu 64").
int resolve_cpu(int requested) {
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  if (requested == -2) {
    return cpus >= 2 ? static_cast<int>(cpus - 1) : -1;
  }
  if (requested >= cpus) {
    throw std::invalid_argument("--cpu " + std::to_string(requested) + ": this machine has " +
                                std::to_string(cpus) + " CPU(s), 0.." + std::to_string(cpus - 1));
  }
  return requested;
}

int run_core(const CoreConfig& config) {
  // Before the segment exists: a stop signal must always run the stop sequence, never the
  // default action that would leave the segment behind.
  install_signal_handlers();
  const RtReport rt = rt_preflight(config.rt_policy, config.priority);
  if (config.rt_policy == RtPolicy::kWarn) {
    std::cerr << "hapticctrl-core: " << rt.summary() << "\n";
  }
  const bool fifo = rt.fifo_granted;
  const int cpu = resolve_cpu(config.cpu);
  std::ofstream histogram;  // opened now: a path that cannot be written fails before the run
  if (!config.histogram_path.empty()) {
    histogram.open(config.histogram_path);
    if (!histogram) {
      throw std::runtime_error("cannot write the histogram '" + config.histogram_path + "'");
    }
  }

  const std::string model_path =
      config.model_path.empty() ? default_arm_model_path() : config.model_path;
  const ArmDynamics dynamics(load_arm_model(model_path));
  if (const GravityDemand g = gravity_demand(dynamics); g.share > 1.0) {
    throw ArmModelError("arm model '" + model_path + "': holding the arm against gravity needs " +
                        std::to_string(static_cast<int>(g.share * 100.0)) + " % of joint " +
                        std::to_string(g.joint + 1) +
                        "'s peak torque at some pose: it cannot be gravity-compensated");
  }
  shm::Segment segment = shm::Segment::create(
      {.instance = config.instance, .group = config.group, .period_ns = to_ns(config.period)});
  // Checked now, not at the fail-safe: a directory others could plant a link in is refused at
  // start, with the reason (J4).
  const PrivateDirectory state_directory(config.state_dir.empty() ? shm::creator_runtime_directory()
                                                                  : config.state_dir);
  EstopLatchFile estop_latch(state_directory, config.instance);
  RestartMarker restart_marker(state_directory, config.instance);
  const Vector6d ready_pose = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();
  SimulatorOptions sim_options;
  sim_options.max_substep = to_seconds(config.sim_substep);
  SimulatedArm arm(dynamics, sim_options, ready_pose, &segment.region<shm::RegionId::kForce>());
  ServoShared shared(
      arm, segment.ctrl_reader(),
      ServoRegions{&segment.region<shm::RegionId::kVpr>(), &segment.writable<shm::RegionId::kVp>(),
                   &segment.writable<shm::RegionId::kPosition>()},
      config.allow_fault_injection, {config.inject_at_cycle, config.inject_cycles});
  if (estop_latch.left_latched()) {
    shared.state.logical.estop = true;  // before any task runs
    std::cerr << "hapticctrl-core: the emergency stop is still latched ("
              << (estop_latch.left_note().empty() ? "left by an earlier core"
                                                  : estop_latch.left_note())
              << "): power-on is refused until an operator resets it\n";
  }
  if (restart_marker.left_by_earlier()) {
    shared.state.logical.awaiting_operator = !config.fresh_start;  // before any task runs
    std::cerr << "hapticctrl-core: the core before this one did not stop in order ("
              << (restart_marker.left_note().empty() ? "killed, crashed or failed safe"
                                                     : restart_marker.left_note())
              << (config.fresh_start
                      ? "): this start is an operator's own (--fresh-start)\n"
                      : "): a client's power-on is refused until an operator powers the arm on\n");
  }
  ServoTask main_task(shared, TaskRole::kMain, ServoLaw(dynamics));
  ServoTask degraded_task(shared, TaskRole::kDegraded, ServoLaw(dynamics));
  BlackBox black_box(static_cast<std::size_t>(std::chrono::seconds(2) / config.period),
                     &segment.writable<shm::RegionId::kBlackBox>());
  RealClock clock;

  // Before the real-time placement of this thread: the keeper inherits no priority or CPU.
  std::jthread latch_keeper = start_latch_keeper(estop_latch, segment);
  // The degraded SERVO is left free to run on any CPU, so that it can still run when the main
  // SERVO hogs the shared CPU.
  ThreadedServoTasks tasks(clock, main_task, degraded_task, shared.overrun, config.period,
                           ThreadPlacement{fifo ? config.priority - 1 : 0, cpu},
                           ThreadPlacement{fifo ? config.priority - 2 : 0, -1});
  const bool placed = place_current_thread(ThreadPlacement{fifo ? config.priority : 0, cpu}) &&
                      tasks.placement_applied(TaskRole::kMain) &&
                      tasks.placement_applied(TaskRole::kDegraded);
  if (!placed) {
    const std::string what = "the real-time threads could not all be placed (CPU " +
                             std::to_string(cpu) + ", SCHED_FIFO " +
                             (fifo ? std::to_string(config.priority) : std::string("off")) + ")";
    if (config.rt_policy == RtPolicy::kEnforce) {
      throw std::runtime_error(what);
    }
    std::cerr << "hapticctrl-core: warning: " << what << "\n";
  }

  ExecutiveConfig exec_config;
  exec_config.period = config.period;
  exec_config.duration = config.duration;
  exec_config.telemetry_every = static_cast<std::uint32_t>(
      std::max<std::int64_t>(1, std::chrono::milliseconds(20) / config.period));
  exec_config.chronic = config.chronic;
  exec_config.rt_mode = rt.mode();
  exec_config.ride_through_misses = config.benchmark_mode;
  Executive executive(exec_config, clock, tasks, shared, arm,
                      ExecutiveOutputs{&segment.header_for_writing(),
                                       &segment.writable<shm::RegionId::kTelemetry>(),
                                       &segment.region<shm::RegionId::kPosition>(),
                                       &segment.writable<shm::RegionId::kEvents>()},
                      black_box);
  std::cerr << "hapticctrl-core: instance '" << config.instance << "' running, period "
            << std::chrono::duration_cast<std::chrono::microseconds>(config.period).count()
            << " us, rt mode " << shm::rt_mode_name(static_cast<std::uint32_t>(rt.mode()))
            << ", cpu " << cpu << "\n";
  if (config.benchmark_mode) {
    std::cerr << "hapticctrl-core: BENCHMARK MODE: missed deadlines are counted as would-be "
                 "fail-safes and never stop the core (simulated arm only)\n";
  }

  const ExecutiveResult result = executive.run(&g_signal_stop);
  const shm::TelemetryPayload final_figures = executive.telemetry();
  latch_keeper.request_stop();
  latch_keeper.join();
  follow_latch(estop_latch, segment);  // the state of the last cycle
  if (!result.fail_safe) {
    try {
      restart_marker.stopped_in_order();
    } catch (const std::exception& e) {
      std::cerr << "hapticctrl-core: the restart marker: " << e.what() << "\n";
    }
  }

  std::string black_box_path;
  if (result.fail_safe) {
    try {
      black_box_path = store_black_box(black_box, state_directory, config.instance, getpid(),
                                       config.blackbox_keep);
    } catch (const std::exception& e) {
      std::cerr << "hapticctrl-core: could not write the black box: " << e.what() << "\n";
    }
  }
  if (histogram.is_open()) {
    executive.wake_latency().write_cyclictest_format(histogram);
    histogram.flush();
    if (!histogram) {
      std::cerr << "hapticctrl-core: could not write the histogram '" << config.histogram_path
                << "'\n";
    }
  }
  segment.close();  // fail-safe step 5: release the regions
  if (config.json) {
    std::cout << telemetry_json(final_figures) << '\n' << std::flush;
  }
  if (result.fail_safe) {
    std::cerr << "hapticctrl-core: FAIL-SAFE after cycle " << final_figures.cycle << ": "
              << shm::stop_reason_name(static_cast<std::uint32_t>(result.reason))
              << stall_text(result.tripped_by_stall)
              << " (motors inhibited, supply off, client told)"
              << (black_box_path.empty() ? "" : "; black box: " + black_box_path) << "\n";
    return 3;
  }
  std::cerr << "hapticctrl-core: stopped after " << final_figures.cycle
            << " cycles: " << shm::stop_reason_name(static_cast<std::uint32_t>(result.reason))
            << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<CoreConfig>(
      "hapticctrl-core", argc, argv,
      [](const std::vector<std::string>& args, CoreConfig& c) {
        c = parse_core_args(args);
        return !c.show_help;
      },
      &core_usage, [](const CoreConfig& c) { return run_core(c); });
}
