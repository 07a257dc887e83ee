// Tests of panel_keys.hpp: the operator panel's keyboard, apart from the screen so that it is
// unit-tested: a key and the panel's force state give an action and the new force state.
#include "hapticctrl/hmi/panel_keys.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::hmi {
namespace {

constexpr double kMaxForce = 100.0;
constexpr double kMaxTorque = 10.0;

KeyResult press(int key, PanelForce& f) {
  return apply_key(key, f, kMaxForce, kMaxTorque);
}

TEST(PanelKeys, CommandKeysMapToCtrlCodes) {
  PanelForce f;
  EXPECT_EQ(press('p', f).command, shm::CtrlCode::kPowerOn);
  EXPECT_EQ(press('o', f).command, shm::CtrlCode::kPowerOff);
  EXPECT_EQ(press(' ', f).command, shm::CtrlCode::kEmergencyStop);
  EXPECT_EQ(press('e', f).command, shm::CtrlCode::kEmergencyStop);
  EXPECT_EQ(press('r', f).command, shm::CtrlCode::kEmergencyReset);
  EXPECT_EQ(press('p', f).action, PanelAction::kCommand);
  EXPECT_EQ(press('S', f).action, PanelAction::kAskStop) << "stop asks first";
  EXPECT_EQ(press('q', f).action, PanelAction::kQuit);
  EXPECT_EQ(press('?', f).action, PanelAction::kNone);
}

TEST(PanelKeys, CommandFeedbackSaysWhatToExpectAndWhyNot) {
  using shm::CtrlCode;
  namespace bits = shm::state_bits;
  EXPECT_STREQ(command_feedback(CtrlCode::kPowerOn, bits::kEmergencyStop),
               "power on refused: the emergency stop is latched (r resets it)");
  EXPECT_STREQ(command_feedback(CtrlCode::kPowerOn, 0), "power on requested");
  EXPECT_STREQ(command_feedback(CtrlCode::kPowerOn, bits::kPowered), "already powered");
  EXPECT_STREQ(command_feedback(CtrlCode::kPowerOn, bits::kAwaitingOperator),
               "power on requested (the operator's acknowledgement of the restart)");
  EXPECT_STREQ(command_feedback(CtrlCode::kPowerOff, 0), "already unpowered");
  EXPECT_STREQ(command_feedback(CtrlCode::kEmergencyReset, 0), "no emergency stop to reset");
  EXPECT_STREQ(command_feedback(CtrlCode::kEmergencyReset, bits::kEmergencyStop),
               "emergency stop reset requested (p powers on again)");
  EXPECT_STREQ(command_feedback(CtrlCode::kEmergencyStop, bits::kPowered),
               "emergency stop latched");
}

TEST(PanelKeys, PushesAlongTheChosenAxisByTheStep) {
  PanelForce f;
  EXPECT_EQ(press('+', f).action, PanelAction::kForce);
  EXPECT_DOUBLE_EQ(f.wrench[0], 2.0);
  press('3', f);
  press('-', f);
  press('-', f);
  EXPECT_DOUBLE_EQ(f.wrench[2], -4.0);
  press('6', f);
  press(']', f);
  press('+', f);
  EXPECT_DOUBLE_EQ(f.wrench[5], 0.2) << "torque axes use the torque step, doubled by ]";
  press('0', f);
  EXPECT_EQ(f.wrench, shm::Vector6{}) << "0 releases every axis";
}

TEST(PanelKeys, StepsAndWrenchStayWithinBounds) {
  PanelForce f;
  for (int i = 0; i < 20; ++i) {
    press(']', f);
  }
  EXPECT_DOUBLE_EQ(f.force_step, 32.0);
  EXPECT_DOUBLE_EQ(f.torque_step, 1.6);
  for (int i = 0; i < 10; ++i) {
    press('+', f);
  }
  EXPECT_DOUBLE_EQ(f.wrench[0], kMaxForce);
  for (int i = 0; i < 40; ++i) {
    press('[', f);
  }
  EXPECT_DOUBLE_EQ(f.force_step, 0.125);
  press('9', f);
  EXPECT_EQ(f.axis, 0U) << "only 1-6 choose an axis";
}

}  // namespace
}  // namespace hapticctrl::hmi
