#pragma once
/// A mock ArmIo for tests: records what the servo asks and lets a test script the sensors.

#include <vector>

#include "hapticctrl/rt_core/arm_io.hpp"

namespace hapticctrl::test {

class MockArm final : public rt_core::ArmIo {
 public:
  bool get_measures(rt_core::ArmMeasures& out) noexcept override {
    ++reads;
    out = measures;
    out.supply_on = supply;
    return !fail_reads;
  }
  void send_commands(const rt_core::ArmCommands& commands, hapticctrl::TimePoint now,
                     hapticctrl::Duration dt) noexcept override {
    last = commands;
    last_now = now;
    last_dt = dt;
    ++sends;
    if (commands.enable) {
      ++enabled_sends;
    }
  }
  void set_supply(bool on) noexcept override {
    supply = on;
    ++supply_switches;
  }

  rt_core::ArmMeasures measures;
  bool supply = false;
  bool fail_reads = false;
  rt_core::ArmCommands last;
  hapticctrl::TimePoint last_now;
  hapticctrl::Duration last_dt{0};
  int reads = 0;
  int sends = 0;
  int enabled_sends = 0;
  int supply_switches = 0;
};

}  // namespace hapticctrl::test
