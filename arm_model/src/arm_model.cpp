// Implements arm_model.hpp: the arm model: a 6-revolute-joint serial chain with link inertias,
// joint limits, friction, motor limits and encoders, read from a documented text file
// (docs/arm_model.md).
#include "hapticctrl/arm_model/arm_model.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#ifndef HAPTICCTRL_DEFAULT_ARM_MODEL
#define HAPTICCTRL_DEFAULT_ARM_MODEL "arm_model/models/virtuose6d_class.arm"
#endif

namespace hapticctrl::arm_model {
namespace {

/// Longest length any part of a desktop haptic arm can have (m): a link, an offset, the
/// workspace's half size or centre.
constexpr double kMaxLength = 2.0;

struct Entry {
  std::vector<double> numbers;
  std::string text;
  int line = 0;
};

/// section -> key -> entry
using Sections = std::map<std::string, std::map<std::string, Entry>>;

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) {
    return "";
  }
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

class Parser {
 public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(int line, const std::string& where, const std::string& message) const {
    std::ostringstream out;
    out << source_;
    if (line > 0) {
      out << ":" << line;
    }
    out << ": " << where << ": " << message;
    throw ArmModelError(out.str());
  }

  Sections split(const std::string& text) {
    Sections sections;
    std::istringstream in(text);
    std::string raw;
    std::string section = "model";
    int line_no = 0;
    while (std::getline(in, raw)) {
      ++line_no;
      const std::string line = trim(raw.substr(0, raw.find('#')));
      if (line.empty()) {
        continue;
      }
      if (line.front() == '[') {
        if (line.back() != ']') {
          fail(line_no, line, "section header must end with ']'");
        }
        section = trim(line.substr(1, line.size() - 2));
        if (sections.count(section) != 0) {
          fail(line_no, "[" + section + "]", "section appears twice");
        }
        sections[section];
        continue;
      }
      const auto eq = line.find('=');
      if (eq == std::string::npos) {
        fail(line_no, line, "expected 'key = value'");
      }
      const std::string key = trim(line.substr(0, eq));
      Entry entry;
      entry.text = trim(line.substr(eq + 1));
      entry.line = line_no;
      std::istringstream values(entry.text);
      std::string token;
      bool numeric = true;
      while (values >> token) {
        char* end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0') {
          numeric = false;
          break;
        }
        entry.numbers.push_back(v);
      }
      if (!numeric) {
        entry.numbers.clear();
      }
      if (sections[section].count(key) != 0) {
        fail(line_no, where(section, key), "given twice");
      }
      sections[section][key] = entry;
    }
    return sections;
  }

  static std::string where(const std::string& section, const std::string& key) {
    return "[" + section + "] " + key;
  }

  const Entry& get(const Sections& s, const std::string& section, const std::string& key) const {
    used_.emplace(section, key);
    const auto sec = s.find(section);
    if (sec == s.end()) {
      fail(0, "[" + section + "]", "section missing");
    }
    const auto it = sec->second.find(key);
    if (it == sec->second.end()) {
      fail(0, where(section, key), "missing");
    }
    return it->second;
  }

  std::vector<double> numbers(const Sections& s, const std::string& section, const std::string& key,
                              std::size_t count) const {
    const Entry& e = get(s, section, key);
    if (e.numbers.size() != count) {
      fail(e.line, where(section, key),
           "expected " + std::to_string(count) + " number(s), got '" + e.text + "'");
    }
    for (const double v : e.numbers) {
      if (!std::isfinite(v)) {
        fail(e.line, where(section, key), "must be finite");
      }
    }
    return e.numbers;
  }

  double positive(const Sections& s, const std::string& section, const std::string& key,
                  bool allow_zero = false) const {
    const double v = numbers(s, section, key, 1)[0];
    if (v < 0.0 || (!allow_zero && v == 0.0)) {
      fail(get(s, section, key).line, where(section, key),
           std::string("must be ") + (allow_zero ? ">= 0" : "> 0") + ", got " +
               get(s, section, key).text);
    }
    return v;
  }

  /// "min max" with min < max.
  std::pair<double, double> range(const Sections& s, const std::string& section,
                                  const std::string& key) const {
    const auto v = numbers(s, section, key, 2);
    if (!(v[0] < v[1])) {
      fail(get(s, section, key).line, where(section, key), "min must be below max");
    }
    return {v[0], v[1]};
  }

  /// Two values, both > 0 (linear and angular).
  std::pair<double, double> positive_pair(const Sections& s, const std::string& section,
                                          const std::string& key) const {
    const auto v = numbers(s, section, key, 2);
    if (!(v[0] > 0.0 && v[1] > 0.0)) {
      fail(get(s, section, key).line, where(section, key), "both values must be > 0");
    }
    return {v[0], v[1]};
  }

  Vector3d vec3(const Sections& s, const std::string& section, const std::string& key) const {
    const auto v = numbers(s, section, key, 3);
    return {v[0], v[1], v[2]};
  }

  /// A value that must also lie within what such an arm can physically be (H3: a gravity of
  /// 1000 m/s^2 was accepted and powered the handle to 41 m/s).
  double at_most(const Sections& s, const std::string& section, const std::string& key,
                 double value, double bound, const char* unit) const {
    if (value > bound) {
      fail(get(s, section, key).line, where(section, key),
           "must be at most " + number_text(bound) + " " + unit + ", got " +
               get(s, section, key).text);
    }
    return value;
  }

  /// Every key read, every section known: anything else is a typo or another format.
  void reject_unknown(const Sections& s) const {
    for (const auto& [section, keys] : s) {
      const bool known = std::any_of(used_.begin(), used_.end(),
                                     [&name = section](const auto& u) { return u.first == name; });
      if (!known) {
        fail(keys.empty() ? 0 : keys.begin()->second.line, "[" + section + "]", "unknown section");
      }
      for (const auto& [key, entry] : keys) {
        if (used_.count({section, key}) == 0) {
          fail(entry.line, where(section, key), "unknown key");
        }
      }
    }
  }

  Vector3d axis(const Sections& s, const std::string& section) const {
    const Entry& e = get(s, section, "axis");
    if (e.text == "x" || e.text == "X") {
      return Vector3d::UnitX();
    }
    if (e.text == "y" || e.text == "Y") {
      return Vector3d::UnitY();
    }
    if (e.text == "z" || e.text == "Z") {
      return Vector3d::UnitZ();
    }
    Vector3d v = vec3(s, section, "axis");
    if (std::abs(v.norm() - 1.0) > 1e-6) {
      fail(e.line, where(section, "axis"),
           "must be x, y, z or a unit vector, got '" + e.text + "'");
    }
    return v;
  }

 private:
  static std::string number_text(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }

  std::string source_;
  mutable std::set<std::pair<std::string, std::string>> used_;
};

}  // namespace

ArmModel parse_arm_model(const std::string& text, const std::string& source) {
  Parser p(source);
  const Sections s = p.split(text);
  ArmModel m;
  const Entry& format = p.get(s, "model", "format");
  if (format.text != "1") {
    p.fail(format.line, "format", "unsupported format '" + format.text + "' (this build reads 1)");
  }
  m.name = p.get(s, "model", "name").text;
  m.gravity = p.vec3(s, "model", "gravity");
  p.at_most(s, "model", "gravity", m.gravity.norm(), 20.0, "m/s^2 in magnitude");
  for (int i = 0; i < kJoints; ++i) {
    const std::string sec = "joint " + std::to_string(i + 1);
    JointModel& j = m.joints[static_cast<std::size_t>(i)];
    j.origin = p.vec3(s, sec, "origin");
    p.at_most(s, sec, "origin", j.origin.norm(), kMaxLength, "m from the previous joint");
    j.axis = p.axis(s, sec);
    j.mass = p.at_most(s, sec, "mass", p.positive(s, sec, "mass"), 20.0, "kg");
    j.com = p.vec3(s, sec, "com");
    p.at_most(s, sec, "com", j.com.norm(), kMaxLength, "m from the joint");
    const Vector3d principal = p.vec3(s, sec, "inertia");
    p.at_most(s, sec, "inertia", principal.maxCoeff(), 5.0, "kg.m^2");
    if ((principal.array() < 0.0).any()) {
      p.fail(p.get(s, sec, "inertia").line, "[" + sec + "] inertia",
             "principal moments must be >= 0");
    }
    j.inertia = principal.asDiagonal();
    std::tie(j.q_min, j.q_max) = p.range(s, sec, "limits");
    p.at_most(s, sec, "limits", std::max(-j.q_min, j.q_max), 2.0 * std::numbers::pi, "rad");
    j.viscous =
        p.at_most(s, sec, "viscous", p.positive(s, sec, "viscous", true), 10.0, "N.m.s/rad");
    j.coulomb = p.at_most(s, sec, "coulomb", p.positive(s, sec, "coulomb", true), 10.0, "N.m");
    j.rotor_inertia = p.at_most(s, sec, "rotor_inertia", p.positive(s, sec, "rotor_inertia", true),
                                1.0, "kg.m^2");
    j.torque_peak =
        p.at_most(s, sec, "torque_peak", p.positive(s, sec, "torque_peak"), 200.0, "N.m");
    j.torque_continuous = p.positive(s, sec, "torque_continuous");
    if (j.torque_continuous > j.torque_peak) {
      p.fail(p.get(s, sec, "torque_continuous").line, "[" + sec + "] torque_continuous",
             "must not exceed torque_peak");
    }
    const double counts = p.positive(s, sec, "encoder_counts");
    if (counts != std::floor(counts) || counts < 16 || counts > (1 << 24)) {
      p.fail(p.get(s, sec, "encoder_counts").line, "[" + sec + "] encoder_counts",
             "must be a whole number in [16, 2^24]");
    }
    j.encoder_counts = static_cast<int>(counts);
  }
  m.handle = p.vec3(s, "handle", "origin");
  p.at_most(s, "handle", "origin", m.handle.norm(), kMaxLength, "m from joint 6");
  std::tie(m.limits.coupled_j23_min, m.limits.coupled_j23_max) =
      p.range(s, "limits", "coupled_j2_j3");
  m.limits.force_peak = p.at_most(s, "limits", "force_peak", p.positive(s, "limits", "force_peak"),
                                  100.0, "N (the operator's own limit)");
  m.limits.force_continuous = p.positive(s, "limits", "force_continuous");
  m.limits.torque_peak =
      p.at_most(s, "limits", "torque_peak", p.positive(s, "limits", "torque_peak"), 10.0, "N.m");
  m.limits.torque_continuous = p.positive(s, "limits", "torque_continuous");
  std::tie(m.limits.max_stiffness_linear, m.limits.max_stiffness_angular) =
      p.positive_pair(s, "limits", "max_stiffness");
  p.at_most(s, "limits", "max_stiffness", m.limits.max_stiffness_linear, 1e4, "N/m (linear)");
  p.at_most(s, "limits", "max_stiffness", m.limits.max_stiffness_angular, 100.0,
            "N.m/rad (angular)");
  std::tie(m.limits.max_damping_linear, m.limits.max_damping_angular) =
      p.positive_pair(s, "limits", "max_damping");
  p.at_most(s, "limits", "max_damping", m.limits.max_damping_linear, 200.0, "N.s/m (linear)");
  p.at_most(s, "limits", "max_damping", m.limits.max_damping_angular, 2.0, "N.m.s/rad (angular)");
  m.limits.max_speed =
      p.at_most(s, "limits", "max_speed", p.positive(s, "limits", "max_speed"), 5.0, "m/s");
  m.limits.force_rate =
      p.at_most(s, "limits", "force_rate", p.positive(s, "limits", "force_rate"), 1e5, "N/s");
  m.limits.workspace_center = p.vec3(s, "limits", "workspace_center");
  p.at_most(s, "limits", "workspace_center", m.limits.workspace_center.norm(), kMaxLength, "m");
  m.limits.workspace_half_size = p.vec3(s, "limits", "workspace_half_size");
  p.at_most(s, "limits", "workspace_half_size", m.limits.workspace_half_size.maxCoeff(), kMaxLength,
            "m");
  if ((m.limits.workspace_half_size.array() <= 0.0).any()) {
    p.fail(p.get(s, "limits", "workspace_half_size").line, "[limits] workspace_half_size",
           "must be > 0 on every axis");
  }
  m.limits.workspace_stiffness =
      p.at_most(s, "limits", "workspace_stiffness",
                p.positive(s, "limits", "workspace_stiffness", true), 1e4, "N/m");
  if (m.limits.force_continuous > m.limits.force_peak) {
    p.fail(0, "[limits] force_continuous", "must not exceed force_peak");
  }
  p.reject_unknown(s);
  return m;
}

ArmModel load_arm_model(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw ArmModelError("cannot read arm model file '" + path + "'");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_arm_model(buffer.str(), path);
}

std::string default_arm_model_path() {
  return HAPTICCTRL_DEFAULT_ARM_MODEL;
}

}  // namespace hapticctrl::arm_model
