#pragma once
/// @file core_config.hpp
/// Command line of `hapticctrl-core`, validated. Setup code: throws std::invalid_argument with a
/// message that names the option.

#include <cstdint>
#include <string>
#include <vector>

#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/rt_core/deadline_monitor.hpp"
#include "hapticctrl/rt_core/rt_preflight.hpp"

namespace hapticctrl::rt_core {

struct CoreConfig {
  std::string instance = "default";
  std::string group;                               ///< shm group (mode 0660)
  std::string model_path;                          ///< arm model file (empty: the shipped default)
  Duration period = std::chrono::milliseconds(1);  ///< 100 µs .. 10 ms
  Duration duration{0};                            ///< 0: run until stopped
  RtPolicy rt_policy = RtPolicy::kWarn;
  int priority = 80;           ///< CLOCK; SERVO = priority - 1, degraded = priority - 2
  int cpu = -2;                ///< -2: auto (last CPU), -1: none, >= 0: that CPU
  bool json = false;           ///< print final statistics as JSON on stdout
  std::string histogram_path;  ///< write the wake-up histogram (cyclictest format)
  /// What outlives the process (the black box on fail-safe, the latched emergency stop): a
  /// directory only this user (or root) can write; empty: the instance's runtime directory
  /// (shm::creator_runtime_directory()).
  std::string state_dir;
  std::uint32_t blackbox_keep = 20;    ///< the instance's newest black boxes kept there
  bool allow_fault_injection = false;  ///< accept ctrl kInjectOverrun
  std::uint64_t inject_at_cycle = 0;   ///< --inject-overrun CYCLE:K (0: none)
  std::uint32_t inject_cycles = 0;
  ChronicMissConfig chronic;
  Duration sim_substep =
      std::chrono::microseconds(125);  ///< simulator's longest integration sub-step
  bool benchmark_mode = false;         ///< miss rules counted, not acted on (simulated arm)
  bool fresh_start = false;  ///< an operator's deliberate start: no restart awaits the operator
  bool show_help = false;
};

/// Parses argv. Throws std::invalid_argument for anything wrong.
CoreConfig parse_core_args(const std::vector<std::string>& args);

/// The --help text.
std::string core_usage();

}  // namespace hapticctrl::rt_core
