// Playing a force sequence on a real hapticctrl-core and logging the arm's response.
#include "hapticctrl/hmi/sequence_player.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "support/controller_stack.hpp"

namespace hapticctrl::hmi {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

std::vector<std::vector<double>> rows_of(const std::string& csv, std::size_t& columns) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  columns = static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) {
      row.push_back(std::stod(f));
    }
    rows.push_back(row);
  }
  return rows;
}

TEST(SequencePlayer, PlaysTheWrenchAndLogsTheHandleMovingAlongIt) {
  ControllerStack stack("seq");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator op(stack.instance(), true);
  ASSERT_TRUE(op.send_and_wait(
      shm::CtrlCode::kPowerOn, [](const ControllerStatus& s) { return s.powered(); }, 2s));
  const WrenchSequence seq =
      WrenchSequence::parse("0 0 0 0 0 0 0\n0.2 6 0 0 0 0 0\n0.8 6 0 0 0 0 0\n", "test");
  std::ostringstream log;
  const PlayResult r = play_sequence(op, seq, log);
  EXPECT_FALSE(r.controller_stopped);
  EXPECT_GE(r.played_s, 0.8);
  std::size_t columns = 0;
  const auto rows = rows_of(log.str(), columns);
  EXPECT_EQ(log.str().rfind(sequence_log_header(), 0), 0U);
  EXPECT_EQ(columns, 34U);
  const auto cycles = static_cast<std::size_t>(800'000 / stack.period_us());
  ASSERT_GT(rows.size(), cycles / 2) << "about one row per controller cycle";
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), columns);
  }
  const auto& last = rows.back();
  EXPECT_NEAR(last[3], 6.0, 1e-9) << "requested fx at the end";
  EXPECT_GT(last[9], 3.0) << "the core applies the ramped wrench";
  EXPECT_GT(last[15] - rows.front()[15], 0.003) << "the handle moved along +x";
  EXPECT_TRUE(op.force().settled());
  EXPECT_EQ(op.force().applied(), shm::Vector6{}) << "released at the end";
}

TEST(SequencePlayer, NeedsTheForceRegion) {
  ControllerStack stack("seqnoforce");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator op(stack.instance(), false);
  std::ostringstream log;
  EXPECT_THROW((void)play_sequence(op, WrenchSequence::parse("0 1 0 0 0 0 0\n", "t"), log),
               HmiError);
}

}  // namespace
}  // namespace hapticctrl::hmi
