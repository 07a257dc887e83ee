// Tests of cycle_gate.hpp: who may touch the arm and publish this cycle: the cycle-numbered token
// that keeps a late main SERVO from overwriting the commands of a newer cycle.
#include "hapticctrl/rt_core/cycle_gate.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

TEST(CycleGate, OnlyTheGrantedCycleEnters) {
  CycleGate gate;
  ASSERT_TRUE(gate.grant(5));
  EXPECT_FALSE(gate.enter(4));
  EXPECT_TRUE(gate.enter(5));
  EXPECT_FALSE(gate.enter(5)) << "one holder at a time";
  gate.leave(5);
  EXPECT_TRUE(gate.enter(5)) << "the same cycle may enter again (commit section)";
  gate.leave(5);
}

TEST(CycleGate, NewerGrantLocksOutALateTask) {
  CycleGate gate;
  gate.grant(10);
  ASSERT_TRUE(gate.enter(10));
  gate.leave(10);               // the main SERVO now computes without the gate
  ASSERT_TRUE(gate.grant(11));  // the degraded SERVO takes cycle 11
  EXPECT_FALSE(gate.enter(10)) << "late commit of cycle 10 is refused";
}

TEST(CycleGate, NoGrantWhileSomeoneIsInside) {
  CycleGate gate;
  gate.grant(1);
  ASSERT_TRUE(gate.enter(1));
  EXPECT_FALSE(gate.grant(2));
  gate.leave(1);
  EXPECT_TRUE(gate.grant(2));
}

TEST(CycleGate, ClosedGateAdmitsNobody) {
  CycleGate gate;
  gate.grant(3);
  ASSERT_TRUE(gate.close());
  EXPECT_TRUE(gate.closed());
  EXPECT_FALSE(gate.enter(3));
  EXPECT_FALSE(gate.grant(4));
}

}  // namespace
}  // namespace hapticctrl::rt_core
