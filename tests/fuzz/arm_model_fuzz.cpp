// libFuzzer target: the arm model parser (arm_model/models/*.arm). Any text either parses into a
// model whose every number is finite, or is refused with ArmModelError; anything else (another
// exception, a crash, a sanitizer report) is a finding. Seeds: the shipped model.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "hapticctrl/arm_model/arm_model.hpp"

namespace {

namespace rc = hapticctrl::arm_model;

bool finite(const rc::ArmModel& m) {
  bool ok = m.gravity.allFinite() && m.handle.allFinite() &&
            m.limits.workspace_center.allFinite() && m.limits.workspace_half_size.allFinite() &&
            std::isfinite(m.limits.force_peak) && std::isfinite(m.limits.torque_peak) &&
            std::isfinite(m.limits.force_rate);
  for (const rc::JointModel& j : m.joints) {
    ok = ok && j.origin.allFinite() && j.axis.allFinite() && j.com.allFinite() &&
         j.inertia.allFinite() && std::isfinite(j.mass) && std::isfinite(j.q_min) &&
         std::isfinite(j.q_max) && std::isfinite(j.viscous) && std::isfinite(j.coulomb) &&
         std::isfinite(j.rotor_inertia) && std::isfinite(j.torque_peak) &&
         std::isfinite(j.torque_continuous);
  }
  return ok;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const rc::ArmModel model = rc::parse_arm_model(text, "fuzz");
    if (!finite(model)) {
      __builtin_trap();  // the parser let a non-finite number through
    }
  } catch (const rc::ArmModelError&) {
    // refused, with a message: the expected outcome for almost every input
  }
  return 0;
}
