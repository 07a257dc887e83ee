#pragma once
/// @file demo_input.hpp
/// What the user applies to the mobile sphere, from the keyboard or from a script.
///
/// Keys: x y z push along +x +y +z by the force step, X Y Z along -x -y -z; u v w and U V W
/// twist about the axes by the torque step; 0 releases (zero wrench); q quits.
///
/// Script file: one event per line, `t action values`, t in seconds from the start, strictly
/// increasing; `#` comments. Actions: `push fx fy fz` (N, client frame), `twist tx ty tz`
/// (N.m), `release`, `quit`, and `obstacle dx dy dz`, which moves the obstacle at once by that
/// much (m, client frame, each at most kMaxObstacleMove): a surface that jumps (J2). A push or
/// twist holds until the next event changes it.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::demo {

/// Largest force (N) and torque (N.m) the user may apply to the sphere.
inline constexpr double kMaxAppliedForce = 50.0;
inline constexpr double kMaxAppliedTorque = 2.0;
/// Largest move of the obstacle in one script event, per axis (m).
inline constexpr double kMaxObstacleMove = 0.1;

struct AppliedWrench {
  client::Vector6 wrench{};
  double force_step = 1.0;    ///< N per key press
  double torque_step = 0.02;  ///< N.m per key press
};

enum class InputResult { kNone, kChanged, kQuit };

/// One key press. Allocation-free.
InputResult apply_demo_key(int key, AppliedWrench& applied) noexcept;

struct ScriptEvent {
  enum class Kind { kPush, kTwist, kRelease, kQuit, kObstacle };
  double t = 0.0;
  Kind kind = Kind::kRelease;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

class DemoScript {
 public:
  /// Throws std::invalid_argument naming `source`, the line and what is wrong.
  static DemoScript parse(const std::string& text, const std::string& source);
  static DemoScript load(const std::string& path);

  /// Applies every event due by `t` (seconds from the start): wrenches to `applied`, obstacle
  /// moves added to `obstacle_move` (m). Returns kQuit once a quit event is due, kChanged if
  /// either changed. Allocation-free.
  InputResult advance(double t, AppliedWrench& applied,
                      std::array<double, 3>& obstacle_move) noexcept;
  [[nodiscard]] const std::vector<ScriptEvent>& events() const noexcept { return events_; }

 private:
  std::vector<ScriptEvent> events_;
  std::size_t next_ = 0;
};

}  // namespace hapticctrl::demo
