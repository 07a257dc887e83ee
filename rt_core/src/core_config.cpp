// Implements core_config.hpp: command line of `hapticctrl-core`, validated.
#include "hapticctrl/rt_core/core_config.hpp"

#include <stdexcept>

#include "hapticctrl/program/options.hpp"

namespace hapticctrl::rt_core {
namespace {

constexpr const char* kProgram = "hapticctrl-core";
constexpr const char* kDescription =
    "The hard-real-time core: the CLOCK, SERVO and degraded SERVO tasks with the simulated arm, "
    "serving the shared-memory regions of one instance.";

template <typename T>
T number(const std::string& option, const std::string& text, T lo, T hi) {
  return program::number_in<T>(option, text, lo, hi);
}

/// Every option, once: parse_core_args() and core_usage() both read these declarations.
void declare(program::Options& o, CoreConfig& c) {
  o.text("--instance", c.instance,
         "instance name (default \"default\"); its socket is NAME.sock in "
         "$HAPTICCTRL_RUNTIME_DIR, else /run/hapticctrl (root), else "
         "$XDG_RUNTIME_DIR/hapticctrl or /tmp/hapticctrl-UID");
  o.text("--group", c.group,
         "group whose members may attach (socket mode 0660; default: the core's group)");
  o.text("--model", c.model_path, "arm model file (default: the shipped Virtuose 6D class model)");
  o.custom(
      "--period-us", "N",
      [&c](const std::string& v) {
        c.period = std::chrono::microseconds(number<std::int64_t>("--period-us", v, 100, 10'000));
      },
      "cycle period, us [100..10000] (default 1000)");
  o.custom(
      "--duration", "S",
      [&c](const std::string& v) {
        c.duration = std::chrono::duration_cast<Duration>(
            std::chrono::duration<double>(number<double>("--duration", v, 0.0, 1e7)));
      },
      "stop after S seconds (default: run until stopped)");
  o.custom(
      "--rt", "enforce|warn|ignore",
      [&c](const std::string& v) { c.rt_policy = parse_rt_policy(v); },
      "real-time policy (default warn)");
  o.number("--priority", c.priority, 3, 98,
           "CLOCK SCHED_FIFO priority (SERVO N-1, degraded N-2; default 80)");
  o.custom(
      "--cpu", "N|-1|auto",
      [&c](const std::string& v) { c.cpu = v == "auto" ? -2 : number<int>("--cpu", v, -1, 1023); },
      "pin CLOCK and SERVO to CPU N (auto: last CPU; -1: no pinning)");
  o.flag("--json", c.json, "print the final statistics as JSON on stdout");
  o.text("--histogram", c.histogram_path,
         "write the wake-up latency histogram (cyclictest -h format)");
  o.text("--state-dir", c.state_dir,
         "where the core keeps what outlives it (its black boxes, the latched emergency stop): "
         "a directory only this user (or root) can write (default: the instance's runtime "
         "directory)");
  o.number<std::uint32_t>("--blackbox-keep", c.blackbox_keep, 1, 10000,
                          "the instance's newest black boxes kept in that directory (default 20)");
  o.flag("--allow-fault-injection", c.allow_fault_injection,
         "accept overrun injection requests through ctrl");
  o.custom(
      "--inject-overrun", "C:K",
      [&c](const std::string& v) {
        const auto colon = v.find(':');
        if (colon == std::string::npos) {
          throw std::invalid_argument("wants CYCLE:K, got '" + v + "'");
        }
        c.inject_at_cycle =
            number<std::uint64_t>("--inject-overrun", v.substr(0, colon), 1, 1ULL << 40);
        c.inject_cycles = number<std::uint32_t>("--inject-overrun", v.substr(colon + 1), 1, 1000);
        c.allow_fault_injection = true;
      },
      "make SERVO overrun for K cycles from cycle C (implies --allow-fault-injection)");
  o.number<std::uint32_t>("--miss-window", c.chronic.window_cycles, 1, DeadlineMonitor::kMaxWindow,
                          "cycles in the miss-rate window (default 1000)");
  o.number<std::uint32_t>("--trip-miss-ppm", c.chronic.trip_window_ppm, 0, 1'000'000,
                          "fail-safe when the window miss rate exceeds N ppm (default 0: report)");
  o.number<std::uint32_t>("--trip-bucket", c.chronic.trip_bucket, 0, 1U << 30,
                          "fail-safe when the leaky-bucket score exceeds N (default 0: report)");
  o.custom(
      "--sim-substep-us", "N",
      [&c](const std::string& v) {
        c.sim_substep =
            std::chrono::microseconds(number<std::int64_t>("--sim-substep-us", v, 10, 1000));
      },
      "simulator's longest integration sub-step, us [10..1000] (default 125: 0.28 % energy "
      "drift in 10 s); longer steps cost less CPU, for slow or instrumented builds, and are "
      "less accurate");
  o.flag("--benchmark-mode", c.benchmark_mode,
         "simulated arm only: a tripped miss rule (5 consecutive misses, chronic misses) is "
         "counted as a would-be fail-safe and the core runs on (a stall pauses the simulated "
         "arm); for measurements on machines that stall, never for an arm that moves");
  o.flag("--fresh-start", c.fresh_start,
         "this start is an operator's deliberate one (scripts/run.sh's first): a core before it "
         "that did not stop in order is said, and a client may power on; otherwise such a "
         "restart refuses a client's power-on until an operator powers the arm on");
}

}  // namespace

std::string core_usage() {
  return program::help_of<CoreConfig>(kProgram, kDescription, declare);
}

CoreConfig parse_core_args(const std::vector<std::string>& args) {
  CoreConfig c;
  c.show_help = !program::parse_into(c, args, kProgram, kDescription, declare);
  return c;
}

}  // namespace hapticctrl::rt_core
