// What a scripted operator's hand does in hapticctrl-mujoco's scenes, through the real
// processes at 0, 5 and 20 ms one way (hapticctrl-netem): a lifted weight felt as m.g, the peg
// guided into its hole, the table felt at the scene's stiffness, a block pushed along the table.
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

/// Column `name` of a hapticctrl-hmi play log, from row `from_s` to `to_s` (its t_s).
std::vector<double> log_column(const std::string& path, const std::string& name, double from_s,
                               double to_s) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');) {
    header.push_back(cell);
  }
  const auto column =
      static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  std::vector<double> out;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      row.push_back(std::strtod(cell.c_str(), nullptr));
    }
    if (column < row.size() && row[0] >= from_s && row[0] < to_s) {
      out.push_back(row[column]);
    }
  }
  return out;
}

/// The greatest speed over 50-cycle windows of a play log's column of positions (m/s).
double fastest_along(const std::vector<double>& x) {
  double fastest = 0.0;
  for (std::size_t i = 0; i + 50 < x.size(); i += 50) {
    fastest = std::max(fastest, std::abs(x[i + 50] - x[i]) / (50.0 * kPeriodUs * 1e-6));
  }
  return fastest;
}

/// One run of a shipped scene through a `delay_ms` link (hapticctrl-netem) for `duration_s`, a
/// scripted operator's hand (`hand`: K,B) playing `sequence` (hapticctrl-hmi play lines) from 1 s
/// after the program is ready; the program's summary and the play log's columns after it.
class HandRun {
 public:
  HandRun(const std::string& tag, int attempt, int delay_ms, const std::string& scene,
          int duration_s, const std::string& sequence, const std::string& hand)
      : sequence_("/tmp/hapticctrl-" + tag + "-" + std::to_string(getpid()) + ".seq"),
        log_("/tmp/hapticctrl-" + tag + "-" + std::to_string(getpid()) + ".csv") {
    ControllerStack stack("mj-" + tag + std::to_string(attempt), kPeriodUs, {},
                          {"--benchmark-mode"});
    const Relay relay(stack.port(),
                      delay_ms > 0
                          ? std::vector<std::string>{"--delay-ms", std::to_string(delay_ms)}
                          : std::vector<std::string>{});
    EXPECT_TRUE(stack.ready()) << stack.diagnostics();
    SpawnedProcess mujoco(HAPTICCTRL_MUJOCO_BINARY,
                          {"--model", kScenes + "/" + scene + ".xml", "--server",
                           "127.0.0.1:" + std::to_string(relay.port()), "--headless", "--json",
                           "--no-lcm", "--duration", std::to_string(duration_s)});
    EXPECT_TRUE(ControllerStack::eventually(
        [&] { return mujoco.err().find("ready:") != std::string::npos; }, 10s));
    std::this_thread::sleep_for(1s);
    std::ofstream(sequence_) << sequence;
    EXPECT_EQ(run_hmi(stack, {"play", sequence_, "--hand", hand, "--log", log_}), 0);
    EXPECT_EQ(mujoco.wait(30s), 0) << mujoco.err();
    summary_ = mujoco.out();
    stalled_ = stack.telemetry().would_fail_safe > 0;
  }
  ~HandRun() {
    std::remove(sequence_.c_str());
    std::remove(log_.c_str());
  }
  HandRun(const HandRun&) = delete;
  HandRun& operator=(const HandRun&) = delete;

  [[nodiscard]] const std::string& summary() const { return summary_; }
  /// Column `name` of the play log over [from_s, to_s) of its time.
  [[nodiscard]] std::vector<double> column(const std::string& name, double from_s,
                                           double to_s) const {
    return log_column(log_, name, from_s, to_s);
  }
  /// Whether the machine took the core's or the engine's time (said; the run is tried again),
  /// or fewer than `least` cycles were logged over the judged window.
  [[nodiscard]] bool disturbed(const std::string& name, std::size_t logged,
                               std::size_t least) const {
    if (stalled_ || logged < least) {
      std::printf("%s: the machine stalled the core (%zu cycles logged): tried again\n",
                  name.c_str(), logged);
      return true;
    }
    return !engine_kept_real_time(name, summary_);
  }

 private:
  std::string sequence_;
  std::string log_;
  std::string summary_;
  bool stalled_ = false;
};

class HeavyLift : public ::testing::TestWithParam<int> {};

TEST_P(HeavyLift, TheLiftedWeightIsFeltAsMgAndTheHandleRests) {
  // The operator's hand (50 N/m, 5 N.s/m: soft enough to rise the 7 cm a 20 ms coupling
  // stretches under the weight) holds the handle and lifts with 15 N from 1 s on; over 5-7 s the
  // weight hangs clear of its shelf: the force rendered on the handle is m g = 7.85 N +- 5 %
  // (measured 2026-12-05: 7.848 N at 20 ms one way, the handle within 0.5 mm/s).
  const int delay_ms = GetParam();
  const std::string name = "heavy_lift_" + std::to_string(delay_ms) + "ms";
  with_retries(name, [&](int attempt) {
    const HandRun run("lift", attempt, delay_ms, "heavy_lift", 11,
                      "0 0 0 0 0 0 0\n1 0 0 15 0 0 0\n8 0 0 15 0 0 0\n", "50,5");
    const std::vector<double> felt = run.column("ren_fz", 5.0, 7.0);
    const std::vector<double> z = run.column("z", 5.0, 7.0);
    if (run.disturbed(name, felt.size(), 1000)) {
      return false;
    }
    double mean = 0.0;
    for (const double f : felt) {
      mean += f / static_cast<double>(felt.size());
    }
    const double fastest = fastest_along(z);  // 50-cycle windows
    const double mg = 0.8 * 9.81;
    std::printf("%s: felt %.3f N for m g %.3f N, handle at most %.2f mm/s\n", name.c_str(), -mean,
                mg, fastest * 1e3);
    EXPECT_NEAR(-mean, mg, 0.05 * mg) << "the weight is felt";
    EXPECT_LT(fastest, 0.005) << "the handle rests (50 ms windows)";
    EXPECT_EQ(json_number(run.summary(), "instabilities"), 0.0);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J3, HeavyLift, ::testing::Values(0, 5, 20),
                         [](const auto& p) { return std::to_string(p.param) + "ms_one_way"; });

class PegPath : public ::testing::TestWithParam<int> {};

TEST_P(PegPath, AScriptedOperatorGuidesThePegOntoTheAxisAndIntoTheHole) {
  // The operator's path, in forces (a hand of 100 N/m and 5 N.s/m holding the handle, its wrist
  // its rotation with 2 N.m/rad and 0.05 N.m.s/rad): from the
  // peg's start, 2 cm above the mouth and 4 mm off the axis along +x, lower it with 1 N while
  // drawing it 0.5 N toward the axis for 2 s, then push 3 N down to the end; the chamfer and the
  // hole's walls, felt through the arm, guide it in. It ends on the hole's floor (30 mm down,
  // its centre at z = 0), on the axis within the 1 mm clearance.
  const int delay_ms = GetParam();
  const std::string name = "peg_path_" + std::to_string(delay_ms) + "ms";
  with_retries(name, [&](int attempt) {
    const HandRun run("peg", attempt, delay_ms, "peg_in_hole", 8,
                      "0 0 0 0 0 0 0\n0.5 -0.5 0 -1 0 0 0\n2 -0.5 0 -1 0 0 0\n"
                      "2.5 0 0 -3 0 0 0\n7 0 0 -3 0 0 0\n",
                      "100,5,2,0.05");
    const std::vector<double> resting = run.column("z", 5.0, 6.5);
    if (run.disturbed(name, resting.size(), 1000)) {
      return false;
    }
#ifdef HAPTICCTRL_SANITIZED
    return true;  // instrumented: for memory and races, not the contact physics (ShippedScene)
#endif
    const std::vector<double> pose = json_numbers(run.summary(), "body_pose");
    EXPECT_EQ(pose.size(), 7U) << run.summary();
    if (pose.size() != 7) {
      return true;
    }
    std::printf("%s: the peg ends at (%.2f, %.2f, %.2f) mm, the handle at most %.2f mm/s\n",
                name.c_str(), pose[0] * 1e3, pose[1] * 1e3, pose[2] * 1e3,
                fastest_along(resting) * 1e3);
    EXPECT_LT(pose[2], 0.001) << "in the hole, on its floor";
    EXPECT_LT(std::hypot(pose[0], pose[1]), 0.001) << "on the axis";
    EXPECT_LT(fastest_along(resting), 0.005) << "the handle rests (50 ms windows)";
    EXPECT_EQ(json_number(run.summary(), "instabilities"), 0.0);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J3, PegPath, ::testing::Values(0, 5, 20),
                         [](const auto& p) { return std::to_string(p.param) + "ms_one_way"; });

class ContactStiffness : public ::testing::TestWithParam<int> {};

TEST_P(ContactStiffness, TheTableIsFeltAtTheScenesStiffnessClampedToTheDevice) {
  // The test box (0.5 kg) rests on its table; a scripted hand (100 N/m, 5 N.s/m) presses it down
  // with 2 N, then 8 N. The table's contact, 160 000 N/m in MuJoCo over the box's four corners
  // (docs/mujoco.md), is clamped to the shipped arm's 2000 N/m (arm_model/models/
  // virtuose6d_class.arm, max_stiffness): the felt stiffness, the rendered force's change over
  // the handle's between the two rests, is at least 0.9 of it at any delay (J2: 1988, 1988 and
  // 1987 N/m at 0, 5 and 20 ms one way, 2026-12-06).
  const int delay_ms = GetParam();
  const std::string name = "contact_stiffness_" + std::to_string(delay_ms) + "ms";
  with_retries(name, [&](int attempt) {
    const HandRun run("press", attempt, delay_ms, "test_box", 9,
                      "0 0 0 0 0 0 0\n1 0 0 -2 0 0 0\n3 0 0 -2 0 0 0\n4 0 0 -8 0 0 0\n"
                      "6 0 0 -8 0 0 0\n6.5 0 0 0 0 0 0\n",
                      "100,5");
    const auto mean = [](const std::vector<double>& v) {
      double m = 0.0;
      for (const double x : v) {
        m += x / static_cast<double>(v.size());
      }
      return m;
    };
    const std::vector<double> z_light = run.column("z", 2.0, 3.0);
    const std::vector<double> z_firm = run.column("z", 5.0, 6.0);
    const std::vector<double> f_light = run.column("ren_fz", 2.0, 3.0);
    const std::vector<double> f_firm = run.column("ren_fz", 5.0, 6.0);
    if (run.disturbed(name, std::min(z_light.size(), z_firm.size()), 500)) {
      return false;
    }
#ifdef HAPTICCTRL_SANITIZED
    return true;  // instrumented: for memory and races, not the contact physics (ShippedScene)
#endif
    const double pressed = mean(z_light) - mean(z_firm);
    const double felt = (mean(f_firm) - mean(f_light)) / pressed;
    std::printf("%s: %.3f mm deeper for %.3f N more: %.0f N/m felt\n", name.c_str(), pressed * 1e3,
                mean(f_firm) - mean(f_light), felt);
    EXPECT_GE(felt, 0.9 * 2000.0) << "the table is felt hard";
    EXPECT_EQ(json_number(run.summary(), "instabilities"), 0.0);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J3, ContactStiffness, ::testing::Values(0, 5, 20),
                         [](const auto& p) { return std::to_string(p.param) + "ms_one_way"; });

class BlockPush : public ::testing::TestWithParam<int> {};

TEST_P(BlockPush, TheHandPushesTheToolIntoTheBlockAndTheBlockSlidesAlongTheTable) {
  // The operator's hand (30 N/m, 3 N.s/m: an arm that follows the push) pushes 6 N along +x from
  // 0 to 1 s and holds it to 9 s; the tool slides over the table, meets the red block 2.5 cm
  // ahead and pushes it until the handle meets the workspace's wall, and the handle rests (81 mm,
  // 2026-12-06). Through 5 and 20 ms one way the tool now reaches the block, but pushes it 12 mm
  // in 2 runs of 3 at 5 ms and turns it 11-14 mm aside at 20 ms (docs/mujoco.md, Not yet): not
  // judged here until that is solved, and the straight push is not loosened for it.
  const int delay_ms = GetParam();
  const std::string name = "block_push_" + std::to_string(delay_ms) + "ms";
  with_retries(name, [&](int attempt) {
    const HandRun run("push", attempt, delay_ms, "table_blocks", 12,
                      "0 0 0 0 0 0 0\n1 6 0 0 0 0 0\n9 6 0 0 0 0 0\n9.5 0 0 0 0 0 0\n", "30,3");
    const std::vector<double> resting = run.column("x", 7.0, 9.0);
    if (run.disturbed(name, resting.size(), 1000)) {
      return false;
    }
#ifdef HAPTICCTRL_SANITIZED
    return true;  // instrumented: for memory and races, not the contact physics (ShippedScene)
#endif
    const std::vector<double> block = json_numbers(run.summary(), "block_red");
    EXPECT_EQ(block.size(), 3U) << run.summary();
    if (block.size() != 3) {
      return true;  // judged: no summary
    }
    const double slid = block[0] - 0.06;
    std::printf(
        "%s: the red block slid %.1f mm (%.2f mm aside), the handle at most %.2f mm/s "
        "at the end\n",
        name.c_str(), slid * 1e3, block[1] * 1e3, fastest_along(resting) * 1e3);
    EXPECT_GT(slid, 0.02) << "the block is pushed along the table";
    EXPECT_LT(std::abs(block[1]), 0.01) << "straight ahead";
    EXPECT_NEAR(block[2], 0.02, 1e-3) << "on the table";
    EXPECT_LT(fastest_along(resting), 0.005) << "the handle rests at the end (50 ms windows)";
    EXPECT_EQ(json_number(run.summary(), "instabilities"), 0.0);
    return true;
  });
}

INSTANTIATE_TEST_SUITE_P(J3, BlockPush, ::testing::Values(0),
                         [](const auto& p) { return std::to_string(p.param) + "ms_one_way"; });

}  // namespace
}  // namespace hapticctrl::test
