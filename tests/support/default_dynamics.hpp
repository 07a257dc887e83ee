#pragma once
/// The shipped default arm model's dynamics, loaded once per test binary.

#include "hapticctrl/rt_core/arm_dynamics.hpp"

namespace hapticctrl::test {

inline const rt_core::ArmDynamics& default_dynamics() {
  static const rt_core::ArmDynamics dynamics(
      arm_model::load_arm_model(arm_model::default_arm_model_path()));
  return dynamics;
}

}  // namespace hapticctrl::test
