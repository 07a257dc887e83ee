// Tests of logical_state.hpp: the controller's logical state (power, emergency stop, stop request,
// fault injection) and the interpretation of ctrl commands.
#include "hapticctrl/rt_core/logical_state.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

shm::CtrlCommand cmd(shm::CtrlCode code, std::uint32_t arg = 0) {
  return shm::CtrlCommand{0, 0, code, arg, 0};
}

TEST(LogicalState, StartsUnpoweredAndPowerOnEnables) {
  LogicalState s;
  EXPECT_EQ(s.state_word() & shm::state_bits::kPowered, 0U);
  CommandInterpreter interp(false);
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kPowerOn), s));
  EXPECT_TRUE(s.powered);
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kPowerOff), s));
  EXPECT_FALSE(s.powered);
}

TEST(LogicalState, EmergencyStopLatchesUntilResetAndResetDoesNotPowerOn) {
  LogicalState s;
  CommandInterpreter interp(false);
  interp.apply(cmd(shm::CtrlCode::kPowerOn), s);
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kEmergencyStop), s));
  EXPECT_FALSE(s.powered);
  EXPECT_FALSE(interp.apply(cmd(shm::CtrlCode::kPowerOn), s)) << "refused while latched";
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kEmergencyReset), s));
  EXPECT_FALSE(s.powered);
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kPowerOn), s));
  EXPECT_NE(s.state_word() & shm::state_bits::kPowered, 0U);
}

TEST(LogicalState, AfterARestartOnlyAnOperatorPowersOnThenClientsMayAgain) {
  LogicalState s;
  s.awaiting_operator = true;  // the core before did not stop in order
  EXPECT_NE(s.state_word() & shm::state_bits::kAwaitingOperator, 0U);
  CommandInterpreter interp(false);
  EXPECT_FALSE(interp.apply(cmd(shm::CtrlCode::kPowerOn, shm::kPowerOnByClient), s))
      << "a client may not power a restarted controller on";
  EXPECT_FALSE(s.powered);
  EXPECT_FALSE(interp.apply(cmd(shm::CtrlCode::kPowerOn, 7), s)) << "an unknown requester";
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kPowerOn, shm::kPowerOnByOperator), s));
  EXPECT_TRUE(s.powered);
  EXPECT_EQ(s.state_word() & shm::state_bits::kAwaitingOperator, 0U) << "acknowledged";
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kPowerOff), s));
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kPowerOn, shm::kPowerOnByClient), s))
      << "once acknowledged, a client powers on as before";
}

TEST(LogicalState, StopRequestBlocksPowerOn) {
  LogicalState s;
  CommandInterpreter interp(false);
  EXPECT_TRUE(interp.apply(cmd(shm::CtrlCode::kStop), s));
  EXPECT_NE(s.state_word() & shm::state_bits::kStopping, 0U);
  EXPECT_FALSE(interp.apply(cmd(shm::CtrlCode::kPowerOn), s));
}

TEST(LogicalState, FaultInjectionOnlyWhenAllowedAndBounded) {
  LogicalState s;
  EXPECT_FALSE(CommandInterpreter(false).apply(cmd(shm::CtrlCode::kInjectOverrun, 5), s));
  CommandInterpreter allowed(true);
  EXPECT_FALSE(allowed.apply(cmd(shm::CtrlCode::kInjectOverrun, 0), s));
  EXPECT_FALSE(allowed.apply(cmd(shm::CtrlCode::kInjectOverrun, 100000), s));
  EXPECT_TRUE(allowed.apply(cmd(shm::CtrlCode::kInjectOverrun, 5), s));
  EXPECT_EQ(s.pending_overrun_cycles, 5U);
}

TEST(LogicalState, UnknownCodesAreRejected) {
  LogicalState s;
  EXPECT_FALSE(CommandInterpreter(true).apply(cmd(static_cast<shm::CtrlCode>(99)), s));
  EXPECT_FALSE(CommandInterpreter(true).apply(cmd(shm::CtrlCode::kNone), s));
}

}  // namespace
}  // namespace hapticctrl::rt_core
