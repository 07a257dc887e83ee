// The verdicts a client draws from one StateSnapshot: is the session over, and did the
// controller leave in order (end too) or fail (connect to the next controller).
#include "hapticctrl/client/types.hpp"

#include <gtest/gtest.h>

#include <string_view>

namespace hapticctrl::client {
namespace {

StateSnapshot snapshot(std::uint32_t core_state, std::uint32_t state_word = 0,
                       std::uint32_t stop_reason = 0) {
  StateSnapshot s;
  s.valid = true;
  s.core_state = core_state;
  s.state_word = state_word;
  s.stop_reason = stop_reason;
  return s;
}

TEST(StateSnapshot, RunningSessionIsNotOver) {
  const auto s = snapshot(core_states::kRunning);
  EXPECT_FALSE(s.session_over());
  EXPECT_FALSE(s.stopped_in_order());
  EXPECT_EQ(std::string_view{s.ending()}, "session closed");
}

TEST(StateSnapshot, OperatorStopEndsTheClientToo) {
  for (const auto state : {core_states::kStopping, core_states::kStopped}) {
    const auto s = snapshot(state);
    EXPECT_TRUE(s.session_over());
    EXPECT_TRUE(s.stopped_in_order());
    EXPECT_EQ(std::string_view{s.ending()}, "controller stopped");
  }
}

TEST(StateSnapshot, FailSafeIsOverButNotInOrder) {
  const auto by_bit = snapshot(core_states::kRunning, state_bits::kFailSafe);
  EXPECT_TRUE(by_bit.session_over());
  EXPECT_FALSE(by_bit.stopped_in_order());
  EXPECT_EQ(std::string_view{by_bit.ending()}, "controller failed safe");
  // A controller that failed safe and then stopped still did not stop in order.
  const auto then_stopped = snapshot(core_states::kStopped, state_bits::kFailSafe);
  EXPECT_TRUE(then_stopped.session_over());
  EXPECT_FALSE(then_stopped.stopped_in_order());
  EXPECT_TRUE(snapshot(core_states::kFailSafe).session_over());
}

TEST(StateSnapshot, LostControllerIsNotAnOrderlyStop) {
  const auto s = snapshot(core_states::kStopped, 0, stop_reasons::kControllerLost);
  EXPECT_TRUE(s.session_over());
  EXPECT_FALSE(s.stopped_in_order());
  EXPECT_EQ(std::string_view{s.ending()}, "controller lost (killed or crashed)");
}

}  // namespace
}  // namespace hapticctrl::client
