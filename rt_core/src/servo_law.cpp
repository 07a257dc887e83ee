#include "hapticctrl/rt_core/servo_law.hpp"

namespace hapticctrl::rt_core {

void ServoLaw::compute(const ServoInputs& in, bool /*degraded*/, ServoOutputs& out) noexcept {
  out.coupling_wrench.setZero();
  out.commands.enable = in.logical.powered && in.measures.supply_on;
  if (!out.commands.enable) {
    out.commands.torque.setZero();
    return;
  }
  out.commands.torque = -damping_.cwiseProduct(in.measures.velocity);
}

}  // namespace hapticctrl::rt_core
