// Tests of demo_report.hpp: what the demo tells its user: one CSV row per step (--log), a status
// line, and the JSON summary at the end (--json).
#include "hapticctrl/demo/demo_report.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "support/json_fields.hpp"

namespace hapticctrl::demo {
namespace {

SphereScene touching_scene() {
  SceneConfig config;
  config.fixed_center = {0.1, 0.0, 0.2};
  SphereState start;
  start.position = {0.1 + 0.059, 0.0, 0.2};  // 1 mm into the fixed sphere
  return {config, start};
}

client::StateSnapshot snapshot() {
  client::StateSnapshot s;
  s.valid = true;
  s.cycle = 4242;
  s.state_word = 1;  // powered
  s.coupling_wrench = {1.5, 0, -2, 0, 0, 0.25};
  s.handle_pose = {0.6, 0.01, 0.2, 0, 0, 0, 1};
  return s;
}

std::size_t count_of(const std::string& text, char c) {
  std::size_t n = 0;
  for (const char x : text) {
    n += x == c ? 1U : 0U;
  }
  return n;
}

/// What `print` writes to a FILE*, as a string.
template <typename Print>
std::string printed(Print print) {
  FILE* f = std::tmpfile();
  print(f);
  std::rewind(f);
  std::string text(4096, '\0');
  text.resize(std::fread(text.data(), 1, text.size(), f));
  std::fclose(f);
  return text;
}

TEST(DemoReport, EveryLogRowHasTheHeadersColumns) {
  std::ostringstream log;
  write_log_header(log);
  AppliedWrench applied;
  applied.wrench[2] = -3.0;
  write_log_row(log, 0.5, snapshot(), touching_scene(), applied);
  std::istringstream lines(log.str());
  std::string header;
  std::string row;
  ASSERT_TRUE(std::getline(lines, header));
  ASSERT_TRUE(std::getline(lines, row));
  EXPECT_EQ(count_of(header, ','), 30U) << "31 columns";
  EXPECT_EQ(count_of(row, ','), count_of(header, ',')) << row;
  EXPECT_EQ(row.rfind("0.5,4242,1,0.159,0,0.2,", 0), 0U) << row;
  EXPECT_NE(row.find(",1.5,0,-2,0,0,0.25,0,0,-3,0,0,0,0.6,0.01,0.2"), std::string::npos) << row;
}

TEST(DemoReport, TheSummaryIsOneJsonLineWithTheRunsFigures) {
  client::LinkStatistics link;
  link.answers_received = 1000;
  link.answers_lost = 3;
  link.rtt_mean_us = 850.0;
  const std::string json = printed([&](FILE* f) {
    print_summary_json(f, snapshot(), touching_scene(), link, 77, 2, "duration");
  });
  EXPECT_EQ(count_of(json, '\n'), 1U);
  EXPECT_EQ(test::json_number(json, "steps"), 77.0);
  EXPECT_EQ(test::json_number(json, "reconnects"), 2.0);
  EXPECT_EQ(test::json_number(json, "answers_lost"), 3.0);
  EXPECT_EQ(test::json_number(json, "rtt_mean_us"), 850.0);
  EXPECT_NEAR(test::json_number(json, "penetration"), 0.001, 1e-9);
  EXPECT_NE(json.find("\"ended\":\"duration\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"powered\":true"), std::string::npos) << json;
}

TEST(DemoReport, TheStatusLineSaysPowerAndEndsAsAsked) {
  const std::string line =
      printed([&](FILE* f) { print_status(f, 1.25, snapshot(), touching_scene(), "\r"); });
  EXPECT_EQ(line.rfind("t   1.25 s  powered ", 0), 0U) << line;
  EXPECT_EQ(line.back(), '\r');
}

}  // namespace
}  // namespace hapticctrl::demo
