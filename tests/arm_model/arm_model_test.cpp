// Tests of arm_model.hpp: the arm model: a 6-revolute-joint serial chain with link inertias, joint
// limits, friction, motor limits and encoders, read from a documented text file
// (docs/arm_model.md).
#include "hapticctrl/arm_model/arm_model.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace hapticctrl::arm_model {
namespace {

std::string default_text() {
  std::ifstream in(default_arm_model_path());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Replaces the first line starting with `key` inside `section` by `replacement`.
std::string edit(std::string text, const std::string& section, const std::string& key,
                 const std::string& replacement) {
  const auto sec = text.find("[" + section + "]");
  const auto pos = text.find("\n" + key, sec == std::string::npos ? 0 : sec);
  const auto end = text.find('\n', pos + 1);
  return text.replace(pos + 1, end - pos - 1, replacement);
}

void expect_error(const std::string& text, const std::string& message) {
  try {
    parse_arm_model(text, "test.arm");
    FAIL() << "expected: " << message;
  } catch (const ArmModelError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr(message)) << e.what();
  }
}

TEST(ArmModel, DefaultModelLoads) {
  const ArmModel m = load_arm_model(default_arm_model_path());
  EXPECT_EQ(m.name, "virtuose6d-class");
  EXPECT_DOUBLE_EQ(m.joints[1].origin.z(), 0.25);
  EXPECT_EQ(m.joints[3].axis, Vector3d::UnitX());
  EXPECT_DOUBLE_EQ(m.limits.force_peak, 35.0);
  EXPECT_DOUBLE_EQ(m.handle.x(), 0.06);
  EXPECT_EQ(m.joints[0].encoder_counts, 262144);
}

TEST(ArmModel, ErrorsNameTheFileLineAndField) {
  const std::string text = default_text();
  expect_error(edit(text, "joint 3", "mass", "mass = -1"), "[joint 3] mass: must be > 0");
  expect_error(edit(text, "joint 2", "limits", "limits = 1 -1"),
               "[joint 2] limits: min must be below max");
  expect_error(edit(text, "joint 1", "axis", "axis = 1 1 0"),
               "[joint 1] axis: must be x, y, z or a unit vector");
  expect_error(edit(text, "joint 4", "com", "com = 0 0"), "[joint 4] com: expected 3 number(s)");
  expect_error(edit(text, "joint 5", "torque_continuous", "torque_continuous = 9"),
               "[joint 5] torque_continuous: must not exceed torque_peak");
  expect_error(edit(text, "joint 6", "encoder_counts", "encoder_counts = 12.5"),
               "[joint 6] encoder_counts");
  expect_error(edit(text, "limits", "force_rate", "force_rate = nan"), "[limits] force_rate");
  expect_error(edit(text, "model", "format", "format = 2"), "unsupported format '2'");
  expect_error(edit(text, "limits", "max_stiffness", "max_stiffness = -5 20"),
               "[limits] max_stiffness: both values must be > 0");
  expect_error(edit(text, "limits", "coupled_j2_j3", "coupled_j2_j3 = 1 1"),
               "[limits] coupled_j2_j3: min must be below max");
  expect_error(edit(text, "joint 2", "inertia", "# gone"), "[joint 2] inertia: missing");
  expect_error(text + "\n[joint 1]\n", "section appears twice");
  expect_error("format = 1\nthis is not a key value line\n", "test.arm:2");
}

TEST(ArmModel, ValuesBeyondAPhysicalArmAndUnknownKeysAreRefusedWithTheLine) {
  // H3: a gravity of 1000 m/s^2 was accepted (and powered the handle to 41 m/s); so were
  // unknown keys and sections, where a typo silently kept a default.
  const std::string text = default_text();
  expect_error(edit(text, "model", "gravity", "gravity = 0 0 -1000"),
               "[model] gravity: must be at most 20 m/s^2 in magnitude");
  expect_error(edit(text, "joint 2", "mass", "mass = 500"),
               "[joint 2] mass: must be at most 20 kg");
  expect_error(edit(text, "joint 3", "origin", "origin = 30 0 0"), "[joint 3] origin");
  expect_error(edit(text, "joint 1", "limits", "limits = -20 20"),
               "[joint 1] limits: must be at most 6.28319 rad");
  expect_error(edit(text, "limits", "max_speed", "max_speed = 50"),
               "[limits] max_speed: must be at most 5 m/s");
  expect_error(edit(text, "limits", "force_peak", "force_peak = 500"), "[limits] force_peak");
  expect_error(edit(text, "limits", "max_stiffness", "max_stiffness = 1e6 20"),
               "[limits] max_stiffness: must be at most 10000 N/m");
  expect_error(edit(text, "joint 4", "viscous", "viscous = 0.005\nviscosity = 0.1"),
               "[joint 4] viscosity: unknown key");
  expect_error(text + "\n[joint 7]\nmass = 1\n", "[joint 7]: unknown section");
  expect_error(text + "\n[joint 7]\nmass = 1\n", "test.arm:");
}

TEST(ArmModel, UnreadableFileIsAClearError) {
  EXPECT_THROW(load_arm_model("/nonexistent/model.arm"), ArmModelError);
}

}  // namespace
}  // namespace hapticctrl::arm_model
