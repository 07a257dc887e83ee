// Implements demo_input.hpp: what the user applies to the mobile sphere, from the keyboard or from
// a script.
#include "hapticctrl/demo/demo_input.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace hapticctrl::demo {
namespace {

InputResult add(AppliedWrench& a, std::size_t axis, double amount) noexcept {
  const double limit = axis < 3 ? kMaxAppliedForce : kMaxAppliedTorque;
  a.wrench[axis] = std::clamp(a.wrench[axis] + amount, -limit, limit);
  return InputResult::kChanged;
}

void set_part(AppliedWrench& a, std::size_t first, const ScriptEvent& e) noexcept {
  a.wrench[first] = e.x;
  a.wrench[first + 1] = e.y;
  a.wrench[first + 2] = e.z;
}

/// One script line (comment stripped, not blank). Throws with `where` ("file:line: ") first.
ScriptEvent parse_event(const std::string& content, const std::string& where) {
  std::istringstream fields(content);
  ScriptEvent e;
  std::string action;
  if (!(fields >> e.t)) {
    throw std::invalid_argument(where + "expected 't action [values]'");
  }
  if (!(fields >> action)) {
    throw std::invalid_argument(where + "missing action (push, twist, release, quit, obstacle)");
  }
  const bool with_values = action == "push" || action == "twist" || action == "obstacle";
  if (action == "push") {
    e.kind = ScriptEvent::Kind::kPush;
  } else if (action == "twist") {
    e.kind = ScriptEvent::Kind::kTwist;
  } else if (action == "release") {
    e.kind = ScriptEvent::Kind::kRelease;
  } else if (action == "quit") {
    e.kind = ScriptEvent::Kind::kQuit;
  } else if (action == "obstacle") {
    e.kind = ScriptEvent::Kind::kObstacle;
  } else {
    throw std::invalid_argument(where + "unknown action '" + action + "'");
  }
  if (with_values && !(fields >> e.x >> e.y >> e.z)) {
    throw std::invalid_argument(where + action + " needs three numbers");
  }
  std::string extra;
  if (fields >> extra) {
    throw std::invalid_argument(where + "unexpected '" + extra + "'");
  }
  const double limit = e.kind == ScriptEvent::Kind::kPush       ? kMaxAppliedForce
                       : e.kind == ScriptEvent::Kind::kObstacle ? kMaxObstacleMove
                                                                : kMaxAppliedTorque;
  if (!std::isfinite(e.t) || e.t < 0.0 || !std::isfinite(e.x) || !std::isfinite(e.y) ||
      !std::isfinite(e.z) || std::abs(e.x) > limit || std::abs(e.y) > limit ||
      std::abs(e.z) > limit) {
    throw std::invalid_argument(
        where + "values must be finite, t >= 0, |force| <= " + std::to_string(kMaxAppliedForce) +
        " N, |torque| <= " + std::to_string(kMaxAppliedTorque) +
        " N.m, |obstacle move| <= " + std::to_string(kMaxObstacleMove) + " m");
  }
  return e;
}

}  // namespace

InputResult apply_demo_key(int key, AppliedWrench& a) noexcept {
  switch (key) {
    case 'x':
    case 'y':
    case 'z':
      return add(a, static_cast<std::size_t>(key - 'x'), a.force_step);
    case 'X':
    case 'Y':
    case 'Z':
      return add(a, static_cast<std::size_t>(key - 'X'), -a.force_step);
    case 'u':
    case 'v':
    case 'w':
      return add(a, 3 + static_cast<std::size_t>(key - 'u'), a.torque_step);
    case 'U':
    case 'V':
    case 'W':
      return add(a, 3 + static_cast<std::size_t>(key - 'U'), -a.torque_step);
    case '0':
      a.wrench = {};
      return InputResult::kChanged;
    case 'q':
    case 'Q':
      return InputResult::kQuit;
    default:
      return InputResult::kNone;
  }
}

DemoScript DemoScript::parse(const std::string& text, const std::string& source) {
  DemoScript script;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string content = line.substr(0, line.find('#'));
    if (content.find_first_not_of(" \t\r") == std::string::npos) {
      continue;  // blank or comment
    }
    const std::string where = source + ":" + std::to_string(number) + ": ";
    const ScriptEvent e = parse_event(content, where);
    if (!script.events_.empty() && e.t <= script.events_.back().t) {
      throw std::invalid_argument(where + "times must increase strictly");
    }
    script.events_.push_back(e);
  }
  return script;
}

DemoScript DemoScript::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument("cannot read script '" + path + "'");
  }
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

InputResult DemoScript::advance(double t, AppliedWrench& applied,
                                std::array<double, 3>& obstacle_move) noexcept {
  InputResult result = InputResult::kNone;
  for (; next_ < events_.size() && events_[next_].t <= t; ++next_) {
    const ScriptEvent& e = events_[next_];
    switch (e.kind) {
      case ScriptEvent::Kind::kPush:
        set_part(applied, 0, e);
        break;
      case ScriptEvent::Kind::kTwist:
        set_part(applied, 3, e);
        break;
      case ScriptEvent::Kind::kRelease:
        applied.wrench = {};
        break;
      case ScriptEvent::Kind::kObstacle:
        obstacle_move[0] += e.x;
        obstacle_move[1] += e.y;
        obstacle_move[2] += e.z;
        break;
      case ScriptEvent::Kind::kQuit:
        return InputResult::kQuit;
    }
    result = InputResult::kChanged;
  }
  return result;
}

}  // namespace hapticctrl::demo
