// Tests of demo_input.hpp: what the user applies to the mobile sphere, from the keyboard or from a
// script.
#include "hapticctrl/demo/demo_input.hpp"

#include <gtest/gtest.h>

#include <array>
#include <stdexcept>

namespace hapticctrl::demo {
namespace {

TEST(DemoInput, KeysPushTwistReleaseAndQuit) {
  AppliedWrench a;
  EXPECT_EQ(apply_demo_key('x', a), InputResult::kChanged);
  EXPECT_EQ(apply_demo_key('Y', a), InputResult::kChanged);
  EXPECT_EQ(apply_demo_key('w', a), InputResult::kChanged);
  EXPECT_EQ(a.wrench, (client::Vector6{1, -1, 0, 0, 0, 0.02}));
  for (int i = 0; i < 100; ++i) {
    apply_demo_key('z', a);
  }
  EXPECT_DOUBLE_EQ(a.wrench[2], kMaxAppliedForce);
  EXPECT_EQ(apply_demo_key('0', a), InputResult::kChanged);
  EXPECT_EQ(a.wrench, client::Vector6{});
  EXPECT_EQ(apply_demo_key('k', a), InputResult::kNone);
  EXPECT_EQ(apply_demo_key('q', a), InputResult::kQuit);
}

TEST(DemoInput, ScriptEventsApplyWhenDue) {
  DemoScript s = DemoScript::parse(
      "# push the sphere sideways, twist it, let go\n"
      "0.5 push 0 3 0\n1.0 twist 0 0 0.05   # about z\n\n2.0 release\n"
      "2.2 obstacle -0.005 0 0\n2.3 obstacle 0 0 0.001\n3.0 quit\n",
      "script");
  ASSERT_EQ(s.events().size(), 6U);
  AppliedWrench a;
  std::array<double, 3> moved{};
  EXPECT_EQ(s.advance(0.4, a, moved), InputResult::kNone);
  EXPECT_EQ(s.advance(1.2, a, moved), InputResult::kChanged);
  EXPECT_EQ(a.wrench, (client::Vector6{0, 3, 0, 0, 0, 0.05}));
  EXPECT_EQ(s.advance(1.5, a, moved), InputResult::kNone) << "each event applies once";
  EXPECT_EQ(s.advance(2.5, a, moved), InputResult::kChanged);
  EXPECT_EQ(a.wrench, client::Vector6{});
  EXPECT_EQ(moved, (std::array<double, 3>{-0.005, 0, 0.001})) << "the moves due add up";
  EXPECT_EQ(s.advance(3.0, a, moved), InputResult::kQuit);
}

TEST(DemoInput, BadScriptsAreRefusedWithTheLine) {
  auto error = [](const std::string& text) {
    try {
      (void)DemoScript::parse(text, "s");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("push 1 2 3\n"), "s:1: expected 't action [values]'");
  EXPECT_EQ(error("1.0\n"), "s:1: missing action (push, twist, release, quit, obstacle)");
  EXPECT_EQ(error("1.0 jump\n"), "s:1: unknown action 'jump'");
  EXPECT_EQ(error("1.0 push 1 2\n"), "s:1: push needs three numbers");
  EXPECT_EQ(error("1.0 release now\n"), "s:1: unexpected 'now'");
  EXPECT_EQ(error("2 release\n1 release\n"), "s:2: times must increase strictly");
  EXPECT_NE(error("1 push 500 0 0\n").find("s:1: values must be finite"), std::string::npos);
  EXPECT_NE(error("1 twist 0 0 5\n").find("|torque|"), std::string::npos);
  EXPECT_NE(error("1 obstacle 0.2 0 0\n").find("|obstacle move| <= 0.1"), std::string::npos);
  EXPECT_THROW((void)DemoScript::load("/nonexistent/script"), std::invalid_argument);
}

}  // namespace
}  // namespace hapticctrl::demo
