// The servo law's joint-space modes (J6): the inputs of the joint law (joint_law.hpp) from the
// cycle's, and what it did into the outputs.
#include "hapticctrl/rt_core/servo_law.hpp"

namespace hapticctrl::rt_core {

Vector6d ServoLaw::joint_space(const ServoInputs& in, double engage, double rate, double dt,
                               ServoOutputs& out) noexcept {
  JointLawInputs j;
  j.client = &in.client;
  j.q = in.measures.position;
  j.qd = in.measures.velocity;
  j.inertia = dynamics_->mass_matrix(chain_).diagonal();
  // The engagement follows the link's fade down and the brake to zero, and ramps back after
  // them: the joints get the fade, the brake and the ramp as the handle's coupling does.
  j.share = engage;
  j.rate = rate;
  j.dt = dt;
  const JointLawResult result = joints_.torque(j, memory_.joints);
  out.saturated = out.saturated || result.saturated;
  counters_.joint_passivity_active += result.guarded ? 1U : 0U;
  return result.torque;
}

}  // namespace hapticctrl::rt_core
