#pragma once
// Test support of the servo law's contact and surface tests: a wall at the object, cycles run
// with the clock advancing (and the contacts refreshed as a client sending them does), a hand
// pressing along x, a trace of the force along x, and an IMPEDANCE client on a surface.
#include <algorithm>
#include <array>
#include <cmath>

#include "support/law_inputs.hpp"

namespace hapticctrl::test {

using rt_core::ServoInputs;
using rt_core::ServoLaw;
using rt_core::ServoOutputs;

/// A surface at the object that pushes it along -x (the object rests against it from -x).
inline rt_core::ClientContact wall_at(const std::array<double, 7>& object_pose, double stiffness,
                                      TimePoint received) {
  rt_core::ClientContact c;
  c.point = {object_pose[0], object_pose[1], object_pose[2]};
  c.normal = {-1.0, 0.0, 0.0};
  c.distance = 0.0;
  c.stiffness = stiffness;
  c.object_pose = object_pose;
  c.received = received;
  return c;
}

/// Runs `cycles` cycles of 1 ms from `in`, with the clock advancing, and returns the last output.
inline ServoOutputs run(ServoLaw& law, ServoInputs& in, int cycles) {
  ServoOutputs out;
  for (int k = 0; k < cycles; ++k) {
    in.now += in.dt;
    law.compute(in, false, out);
  }
  return out;
}

/// Runs `cycles` cycles with every contact refreshed every cycle (as a client sending them does).
inline ServoOutputs run_on_contacts(ServoLaw& law, ServoInputs& in, int cycles) {
  ServoOutputs out;
  for (int k = 0; k < cycles; ++k) {
    for (std::size_t i = 0; i < in.client.contact_count; ++i) {
      in.client.contacts[i].received = in.now + in.dt;
    }
    out = run(law, in, 1);
  }
  return out;
}

/// Moves the handle `dx` along x through the Jacobian, in steps of at most 0.5 mm of one cycle
/// each with the contacts refreshed (a hand pressing at 0.5 m/s at most), and returns how far it
/// went (forward kinematics). The measured velocity stays zero: no damping is in the figures.
inline double press_along_x(ServoLaw& law, ServoInputs& in, double dx) {
  const double start = chain_at(in.measures.position).handle_position.x();
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(dx) / 5e-4)));
  for (int k = 0; k < steps; ++k) {
    const rt_core::Matrix6d jacobian = default_dynamics().jacobian(chain_at(in.measures.position));
    rt_core::Vector6d move = rt_core::Vector6d::Zero();
    move.x() = dx / steps;
    in.measures.position += jacobian.colPivHouseholderQr().solve(move);
    for (std::size_t i = 0; i < in.client.contact_count; ++i) {
      in.client.contacts[i].received = in.now + in.dt;
    }
    run(law, in, 1);
  }
  return chain_at(in.measures.position).handle_position.x() - start;
}

/// The handle's force along x over cycles of 1 ms: its extremes and largest step per cycle.
struct ForceTrace {
  double least = 1e9;
  double most = -1e9;
  double largest_step = 0.0;
  double last = 0.0;
  void add(double f, bool first) {
    least = std::min(least, f);
    most = std::max(most, f);
    if (!first) {
      largest_step = std::max(largest_step, std::abs(f - last));
    }
    last = f;
  }
};

/// An IMPEDANCE client (protocol 1.3) that reports a 2000 N/m surface (mu_s 0.5, mu_d 0.4)
/// whose normal is -x, with the handle's point `depth` inside it, and pushes `client_push`
/// along x itself.
inline ServoInputs impedance_on_surface(double depth, double client_push) {
  ServoInputs in = powered_at(kReady);
  const rt_core::ChainState s = chain_at(kReady);
  in.client.session_id = 1;
  in.client.command = rt_core::ClientCommand::kImpedance;
  in.client.time_step = 1e-3;
  in.client.impedance_wrench = {client_push, 0, 0, 0, 0, 0};
  in.client_valid = true;
  in.new_sample = true;
  in.client.contact_count = 1;
  rt_core::ClientContact& c = in.client.contacts[0];
  c.point = {s.handle_position.x() - depth, s.handle_position.y(), s.handle_position.z()};
  c.normal = {-1.0, 0.0, 0.0};
  c.stiffness = 2000.0;
  c.friction = {0.5, 0.4};
  return in;
}

}  // namespace hapticctrl::test
