// hapticctrl-mujoco through the real processes: the core (1 ms, benchmark mode: a VM stall is
// counted, not failed safe), the UDP bridge and the program on every shipped scene with a
// scripted push; and its error paths. What a hand does in the scenes: mujoco_hand_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mujoco_runs.hpp"
#include "support/controller_stack.hpp"
#include "support/json_fields.hpp"
#include "support/machine_retries.hpp"
#include "support/network_scenario.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

class ShippedScene : public ::testing::TestWithParam<SceneCase> {};

TEST_P(ShippedScene, KeepsRealTimeStaysStableAndReportsItsContacts) {
  const SceneCase& c = GetParam();
  retry_what_the_machine_disturbed(c.name(), 3, [&](int attempt) {
    ControllerStack stack("mj-" + c.name() + std::to_string(attempt), kPeriodUs, {},
                          {"--benchmark-mode"});
    EXPECT_TRUE(stack.ready()) << stack.diagnostics();
    const std::string summary = run_scene(stack, c);
    if (summary.empty()) {
      return true;  // judged: the expectations above failed
    }
    EXPECT_EQ(json_number(summary, "instabilities"), 0.0) << "MuJoCo never reset the state";
    EXPECT_NE(summary.find("\"contacts_supported\":true"), std::string::npos);
    EXPECT_NE(summary.find("\"powered\":true"), std::string::npos);
#ifdef HAPTICCTRL_SANITIZED
    // Instrumented, the run is for memory and races: the 10 ms core and the slowed loop are not
    // the timing or the contact physics the plain build judges.
    return true;
#endif
    if (!engine_kept_real_time(c.name(), summary)) {
      return false;
    }
    EXPECT_GE(json_number(summary, "steps_per_second"),
              0.95 * json_number(summary, "model_steps_per_second"))
        << "the engine keeps real time";
    const std::string scene = c.scene;
    const std::vector<double> pose = json_numbers(summary, "body_pose");
    EXPECT_EQ(pose.size(), 7U);
    if (scene == "peg_in_hole" && pose.size() == 7) {
      EXPECT_LT(pose[2], 0.005) << "pushed 3 N down, the peg is in the hole (floor 30 mm down)";
      EXPECT_LT(std::hypot(pose[0], pose[1]), 0.001) << "on the hole's axis";
    }
    if (scene == "test_box") {
      const std::vector<double> f = json_numbers(summary, "contact_force");
      EXPECT_NEAR(f.size() == 3 ? f[2] : 0.0, 0.5 * 9.81 + 2.0, 0.5) << "its weight and the push";
    }
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(
    J3, ShippedScene,
    ::testing::Values(SceneCase{"test_box", {"0", "0", "-2", "0", "0", "0"}},
                      SceneCase{"peg_in_hole", {"0", "0", "-3", "0", "0", "0"}, 1.5, 5.0},
                      SceneCase{"peg_in_hole", {"0", "0", "-3", "0", "0", "0"}, 1.5, 5.0, 5},
                      SceneCase{"peg_in_hole", {"0", "0", "-3", "0", "0", "0"}, 1.5, 5.0, 20},
                      SceneCase{"table_blocks", {}}, SceneCase{"door_latch", {}},
                      SceneCase{"heavy_lift", {}}),
    [](const auto& p) { return p.param.name(); });

/// The program's exit status and its words, run with `args` (no controller needed).
std::pair<int, std::string> run_alone(const std::vector<std::string>& args) {
  SpawnedProcess mujoco(HAPTICCTRL_MUJOCO_BINARY, args);
  const int status = mujoco.wait(20s);
  return {status, mujoco.err()};
}

TEST(MujocoProgram, AModelMujocoRefusesExits64WithItsOwnWords) {
  const std::string path = "/tmp/hapticctrl-mujoco-bad-" + std::to_string(getpid()) + ".xml";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("<mujoco><worldbody><geom type=\"box\" size=\"0.1 0.1\"/></worldbody></mujoco>", f);
    std::fclose(f);
  }
  const auto [status, err] = run_alone({"--model", path, "--headless"});
  std::remove(path.c_str());
  EXPECT_EQ(status, 64);
  EXPECT_NE(err.find("size"), std::string::npos) << err;
  const auto [missing, missing_err] = run_alone({"--model", "/nonexistent.xml"});
  EXPECT_EQ(missing, 64);
  EXPECT_NE(missing_err.find("/nonexistent.xml"), std::string::npos) << missing_err;
}

TEST(MujocoProgram, ABodyThatIsNotFreeOrNoModelIsAUsageError) {
  const auto [status, err] = run_alone({"--model", kScenes + "/test_box.xml", "--body", "fixture"});
  EXPECT_EQ(status, 64);
  EXPECT_NE(err.find("is not free"), std::string::npos) << err;
  EXPECT_EQ(run_alone({}).first, 64);
  const auto [help, help_text] = run_alone({"--help"});
  EXPECT_EQ(help, 0);
}

}  // namespace
}  // namespace hapticctrl::test
