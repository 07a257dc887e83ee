// The offline analysis path: a recorded LCM log to CSV per channel, and the PNG plots.
#include "hapticctrl/lcm_bridge/log_csv.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "support/sample_log.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("hapticctrl-csv-" + std::to_string(getpid()));
  TempDir() { fs::create_directories(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() { fs::remove_all(path); }
};

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

TEST(LogCsv, EveryChannelGetsItsCsvWithTheExpectedColumns) {
  TempDir dir;
  const std::string log = (dir.path / "run.lcmlog").string();
  test::write_sample_log(log);
  const CsvReport report = log_to_csv(log, dir.path.string());
  EXPECT_EQ(report.skipped, 1U) << "the other application's channel";
  EXPECT_EQ(report.undecodable, 1U) << "the corrupted arm state";
  EXPECT_EQ(report.rows.at("hapticctrl.lab.arm_state.csv"), 5U);

  const auto arm = lines_of(dir.path / "hapticctrl.lab.arm_state.csv");
  ASSERT_EQ(arm.size(), 6U);
  // The columns are the position region's field table (shm/payload_fields.hpp).
  EXPECT_EQ(arm[0].rfind("utime,cycle,state_word,core_state,joint_position_1,", 0), 0U) << arm[0];
  EXPECT_NE(arm[0].find(",handle_pose_x,handle_pose_y,handle_pose_z,handle_pose_qx,"),
            std::string::npos);
  EXPECT_NE(arm[0].find(",operator_wrench_x,"), std::string::npos);
  EXPECT_NE(arm[0].find(",rendered_wrench_rz"), std::string::npos);
  EXPECT_EQ(std::count(arm[0].begin(), arm[0].end(), ','), 4 + 6 * 3 + 7 + 6 * 3 - 1);
  EXPECT_EQ(std::count(arm[3].begin(), arm[3].end(), ','),
            std::count(arm[0].begin(), arm[0].end(), ','));

  const auto stats = lines_of(dir.path / "hapticctrl.lab.cycle_stats.csv");
  ASSERT_EQ(stats.size(), 3U);
  EXPECT_NE(stats[0].find(",wake_latency_p99_ns,"), std::string::npos);
  EXPECT_NE(stats[0].find(",wake_histogram_0_2us,"), std::string::npos);
  EXPECT_NE(stats[0].find(",wake_histogram_10000us_plus"), std::string::npos);

  const auto events = lines_of(dir.path / "hapticctrl.lab.events.csv");
  ASSERT_EQ(events.size(), 3U);
  EXPECT_EQ(events[0], "utime,index,cycle,time_ns,kind,code,value,text,lost_before");
  EXPECT_NE(events[2].find("\"fail-safe: 5 consecutive deadline misses, \"\"black box\"\" "
                           "written\""),
            std::string::npos)
      << "text is quoted CSV";

  // The demo's scene has its CSV too, as docs/lcm.md says of every channel (H5: it was dropped).
  const auto scene = lines_of(dir.path / "hapticctrl.lab.scene.csv");
  ASSERT_EQ(scene.size(), 2U);
  EXPECT_EQ(scene[0].rfind("utime,steps,fixed_x,fixed_y,fixed_z,fixed_radius,mobile_x,", 0), 0U)
      << scene[0];
  EXPECT_NE(scene[0].find(",contact_fx,contact_fy,contact_fz,penetration,applied_x,"),
            std::string::npos);
  EXPECT_EQ(std::count(scene[1].begin(), scene[1].end(), ','),
            std::count(scene[0].begin(), scene[0].end(), ','));
  EXPECT_NE(scene[1].find(",1234,0.7,"), std::string::npos) << scene[1];
}

TEST(LogCsv, AMissingLogIsAClearError) {
  EXPECT_THROW(log_to_csv("/nonexistent/run.lcmlog", "/tmp"), std::runtime_error);
}

/// Runs scripts/plot_log.sh on `log`; returns what it printed.
std::vector<std::string> plot(const TempDir& dir, const std::string& log, const std::string& out) {
  const std::string printed = (dir.path / "printed.txt").string();
  const std::string cmd = std::string(HAPTICCTRL_SOURCE_DIR) + "/scripts/plot_log.sh " + log + " " +
                          out + " --build " + HAPTICCTRL_BINARY_DIR + " >" + printed;
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return lines_of(printed);
}

/// The x-y panel's window the script printed: x0, x1, y0, y1 (m).
std::optional<std::array<double, 4>> xy_window(const std::vector<std::string>& printed) {
  std::array<double, 4> w{};
  for (const std::string& line : printed) {
    if (std::sscanf(line.c_str(), "x-y window: x %lf..%lf m, y %lf..%lf m", &w[0], &w[1], &w[2],
                    &w[3]) == 4) {
      return w;
    }
  }
  return std::nullopt;
}

bool have_gnuplot() {
  return std::system("command -v gnuplot >/dev/null") == 0;
}

TEST(LogCsv, ThePlotScriptWritesThePngs) {
  if (!have_gnuplot()) {
    GTEST_SKIP() << "gnuplot not installed (scripts/setup.sh installs gnuplot-nox)";
  }
  TempDir dir;
  const std::string log = (dir.path / "run.lcmlog").string();
  test::write_sample_log(log);
  const std::string out = (dir.path / "out").string();
  const auto window = xy_window(plot(dir, log, out));
  for (const char* png : {"hapticctrl.lab.handle_trajectory.png", "hapticctrl.lab.forces.png",
                          "hapticctrl.lab.latency_histogram.png"}) {
    const fs::path p = fs::path(out) / png;
    ASSERT_TRUE(fs::exists(p)) << p;
    EXPECT_GT(fs::file_size(p), 1000U) << p;
  }
  // The sample path is straight along x (y stays 0): the x-y panel shows it in a square window
  // around it (H5: autoscaled, y spread over nothing and its labels ran together).
  ASSERT_TRUE(window) << "the script says which window it drew";
  const auto [x0, x1, y0, y1] = *window;
  EXPECT_NEAR(x1 - x0, y1 - y0, 1e-3) << "square";
  EXPECT_LE(x0, 0.1);
  EXPECT_GE(x1, 0.1 * test::kSampleArmStates);
  EXPECT_LT(y0, 0.0);
  EXPECT_GT(y1, 0.0);
}

TEST(LogCsv, AHandleAtRestGetsA2cmWindow) {
  if (!have_gnuplot()) {
    GTEST_SKIP() << "gnuplot not installed (scripts/setup.sh installs gnuplot-nox)";
  }
  TempDir dir;
  const std::string log = (dir.path / "rest.lcmlog").string();
  test::write_sample_log(log, 0.0);
  const auto window = xy_window(plot(dir, log, (dir.path / "out").string()));
  ASSERT_TRUE(window);
  EXPECT_NEAR((*window)[1] - (*window)[0], 0.02, 1e-4);
  EXPECT_NEAR((*window)[3] - (*window)[2], 0.02, 1e-4);
}

}  // namespace
}  // namespace hapticctrl::lcm_bridge
