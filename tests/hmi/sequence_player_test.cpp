// Playing a force sequence on a real hapticctrl-core and logging the arm's response.
#include "hapticctrl/hmi/sequence_player.hpp"

#include <gtest/gtest.h>

#include <cmath>
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
  EXPECT_EQ(columns, 44U);
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

TEST(SequencePlayer, AWanderingHandMovesTheCoreSimulatedHandleAndLetsGoWithoutAStep) {
  // The hand (the core's simulator evaluates it) drags the powered, gravity-compensated handle
  // after its wandering anchor: the handle follows within centimetres, the logged operator force
  // is the hand's, and at the end the grip ramps out instead of dropping.
  ControllerStack stack("seqhand");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator op(stack.instance(), true);
  ASSERT_TRUE(op.send_and_wait(
      shm::CtrlCode::kPowerOn, [](const ControllerStatus& s) { return s.powered(); }, 2s));
  const WrenchSequence seq = WrenchSequence::parse("0 0 0 0 0 0 0\n2.5 0 0 0 0 0 0\n", "test");
  std::ostringstream log;
  const PlayResult r = play_sequence(op, seq, log, HandOptions{400.0, 8.0, 0.02, 3});
  ASSERT_FALSE(r.controller_stopped) << "a VM stall failed the core safe; rerun";
  std::size_t columns = 0;
  const auto rows = rows_of(log.str(), columns);
  ASSERT_GT(rows.size(), 100U);
  double anchor_travel = 0.0;
  double worst_lag = 0.0;
  double hand_force = 0.0;
  for (const auto& row : rows) {
    if (row[0] < 1.5) {
      continue;  // gripping and fading the wander in
    }
    const double lag = std::hypot(row[15] - row[40], row[16] - row[41], row[17] - row[42]);
    worst_lag = std::max(worst_lag, lag);
    anchor_travel =
        std::max(anchor_travel, std::hypot(row[40] - rows.front()[15], row[41] - rows.front()[16],
                                           row[42] - rows.front()[17]));
    hand_force = std::max(hand_force, std::hypot(row[9], row[10], row[11]));
    EXPECT_EQ(row[43], 400.0);
  }
  EXPECT_GT(anchor_travel, 0.003) << "the anchor wandered";
  EXPECT_LT(worst_lag, 0.02) << "the handle follows the hand";
  EXPECT_GT(hand_force, 0.1) << "the logged operator force is the hand's";
  EXPECT_EQ(op.hand().stiffness, 0.0) << "let go at the end";
  EXPECT_EQ(op.hand().damping, 0.0);
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
