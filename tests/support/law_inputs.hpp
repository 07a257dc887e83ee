#pragma once
// Inputs of one cycle of the servo law for its unit tests (tests/rt_core/servo_law*_test.cpp).
#include "hapticctrl/rt_core/servo_law.hpp"
#include "support/default_dynamics.hpp"

namespace hapticctrl::test {

using namespace std::chrono_literals;  // 1ms, 20ms: the law's times in its tests
using rt_core::ChainState;
using rt_core::ClientCommand;
using rt_core::ClientSample;
using rt_core::ServoInputs;
using rt_core::Vector6d;

inline const Vector6d kReady = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();

inline ServoInputs powered_at(const Vector6d& q) {
  ServoInputs in;
  in.dt = 1ms;
  in.logical.powered = true;
  in.measures.supply_on = true;
  in.measures.position = q;
  return in;
}

inline ChainState chain_at(const Vector6d& q) {
  ChainState s;
  default_dynamics().forward_kinematics(q, s);
  return s;
}

inline ClientSample virtmech_client(const std::array<double, 7>& object_pose) {
  ClientSample c;
  c.session_id = 1;
  c.command = ClientCommand::kVirtmech;
  c.object_attached = true;
  c.object_pose = object_pose;
  c.object_mass = 0.5;
  c.time_step = 1e-3;
  return c;
}

/// Powered at the ready pose, coupled (VIRTMECH) to an object `dx` ahead of the handle along x.
inline ServoInputs coupled_to_object_ahead(double dx) {
  ServoInputs in = powered_at(kReady);
  const ChainState s = chain_at(kReady);
  in.client = virtmech_client(
      {s.handle_position.x() + dx, s.handle_position.y(), s.handle_position.z(), 0, 0, 0, 1});
  in.client_valid = true;
  return in;
}

}  // namespace hapticctrl::test
