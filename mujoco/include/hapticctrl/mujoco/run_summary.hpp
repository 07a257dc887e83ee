#pragma once
/// @file run_summary.hpp
/// What hapticctrl-mujoco says of a run at its end (`--json`): the held body, the contact
/// force, the coupling wrench, how the engine kept real time (steps per second against the
/// model's, CPU per step), the contacts reported, and where the scene's other bodies and joints
/// ended. Setup code (allocates); not for a real-time loop.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::mujoco {

/// The engine's CPU time per step (this thread's clock).
struct EngineLoad {
  std::uint64_t steps = 0;
  std::int64_t cpu_ns = 0;
  std::int64_t cpu_max_ns = 0;
  void add(std::int64_t ns) noexcept;
  [[nodiscard]] double mean_us() const noexcept;
};

struct RunSummary {
  std::string ended;  ///< why the run ended ("duration", "signal", "quit", ...)
  std::string body;
  double mass = 0.0;      ///< kg
  double timestep = 0.0;  ///< s
  client::Pose7 body_pose{0, 0, 0, 0, 0, 0, 1};
  std::array<double, 3> contact_force{};  ///< N, on the body from its contacts
  client::Vector6 coupling_wrench{};
  std::uint64_t steps = 0;
  double steps_per_second = 0.0;
  std::uint64_t steps_dropped = 0;  ///< after stalls (real_time_steps.hpp)
  std::uint64_t steps_paused = 0;   ///< while the link was silent
  std::uint64_t catch_ups = 0;
  EngineLoad load;
  std::uint64_t contact_reports = 0;
  bool contacts_supported = true;
  int instabilities = 0;
  std::uint64_t reconnections = 0;
  bool powered = false;
  bool gripping = false;
  std::vector<std::pair<std::string, std::array<double, 3>>> bodies;  ///< the other free ones
  std::vector<std::pair<std::string, double>> joints;                 ///< hinges and slides
};

/// The summary as one JSON object (one line, no newline).
[[nodiscard]] std::string summary_json(const RunSummary& s);

}  // namespace hapticctrl::mujoco
