// Implements client_session.hpp's control frames: the object state (plain or timed, with the
// answer echo and the channel's energy), the IMPEDANCE wrench, the joint commands and the
// contacts, each checked before it leaves. The handshake, answers and reliable frames are in
// client_session.cpp.
#include <algorithm>
#include <cmath>

#include "client_session.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::client {

std::optional<hcp_frame> ClientSession::checked_control(hcp_frame frame) const noexcept {
  if (!open_ || protocol::check_control(frame.body)) {
    return std::nullopt;
  }
  return frame;
}

std::optional<hcp_frame> ClientSession::joint_target_frame(const Joints6& position,
                                                           const Joints6& speed,
                                                           TimePoint now) noexcept {
  if ((features_ & HCP_FEATURE_JOINT_CONTROL) == 0) {
    return std::nullopt;
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_JOINT_TARGET, token_, next_control_sequence(), to_ns(now));
  protocol::to_wire(position, f.body.hcp_body_u.joint_target.position);
  protocol::to_wire(speed, f.body.hcp_body_u.joint_target.speed);
  return checked_control(f);
}

std::optional<hcp_frame> ClientSession::joint_torque_frame(const Joints6& torque,
                                                           TimePoint now) noexcept {
  if ((features_ & HCP_FEATURE_JOINT_CONTROL) == 0) {
    return std::nullopt;
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_JOINT_TORQUE, token_, next_control_sequence(), to_ns(now));
  protocol::to_wire(torque, f.body.hcp_body_u.joint_torque.torque);
  return checked_control(f);
}

std::optional<hcp_frame> ClientSession::object_frame(const Pose7& pose, const Vector6& twist,
                                                     TimePoint now) noexcept {
  // Not a rotation: refused in both frame forms (packing would have normalised it silently).
  const double norm_sq =
      pose[3] * pose[3] + pose[4] * pose[4] + pose[5] * pose[5] + pose[6] * pose[6];
  if (!open_ || !(std::abs(norm_sq - 1.0) <= protocol::kMaxQuaternionError)) {
    return std::nullopt;
  }
  if ((features_ & HCP_FEATURE_TIMING) != 0) {
    return checked_control(timed_object_frame(pose, twist, now));
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_OBJECT, token_, next_control_sequence(), to_ns(now));
  protocol::to_wire(pose, f.body.hcp_body_u.object.pose);
  protocol::to_wire(twist, f.body.hcp_body_u.object.twist);
  return checked_control(f);
}

/// Protocol 1.1: the object state with an echo of the newest answer, from which the bridge
/// measures the link and the core the coupling loop (docs/protocol.md).
hcp_frame ClientSession::timed_object_frame(const Pose7& pose, const Vector6& twist,
                                            TimePoint now) noexcept {
  // The step the application just took, under the wrench it got (at most 0.1 s counted).
  if (last_object_send_ != kNotYet) {
    const double dt = std::min(0.1, to_seconds(now - last_object_send_));
    // How long the application may have held one wrench: its step, the time since the last
    // send, or the controller's cycles meanwhile (the demo integrates one step per cycle).
    const double cycles =
        static_cast<double>(latest_.cycle - std::min(latest_.cycle, last_send_cycle_)) *
        to_seconds(period_);
    passivity_.on_step(twist, dt, std::max({dt, time_step_, std::min(0.1, cycles)}), now);
  }
  last_object_send_ = now;
  last_send_cycle_ = latest_.cycle;
  object_pose_ = pose;
  object_twist_ = twist;
  have_object_ = true;
  if (local() && latest_.valid) {
    close_locally();  // the wrench for the next step, on the state just sent
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_OBJECT_TIMED, token_, next_control_sequence(), to_ns(now));
  hcp_control_object_timed& o = f.body.hcp_body_u.timed;
  for (std::size_t i = 0; i < 3; ++i) {
    o.position[i] = static_cast<float>(pose[i]);
  }
  const protocol::PackedRotation r = protocol::pack_rotation({pose[3], pose[4], pose[5], pose[6]});
  o.rotation[0] = r[0];
  o.rotation[1] = r[1];
  protocol::to_wire(twist, o.twist);
  o.answer_echo = answer_echo(now);
  o.energy_in = passivity_.energy_in_uj();
  return f;
}

std::uint32_t ClientSession::answer_echo(TimePoint now) const noexcept {
  return protocol::pack_answer_echo(latest_.cycle, to_ns(now) - latest_.received_ns, latest_.valid);
}

std::optional<hcp_frame> ClientSession::wrench_frame(const Vector6& wrench,
                                                     TimePoint now) noexcept {
  if (!local()) {
    hcp_frame f =
        protocol::make_frame(HCP_CONTROL_WRENCH, token_, next_control_sequence(), to_ns(now));
    protocol::to_wire(wrench, f.body.hcp_body_u.wrench.wrench);
    return checked_control(f);
  }
  // Protocol 1.3: the wrench held since the last one pushed the handle image; the image gives
  // way along it when the channel gave this end more than the controller put in.
  if (last_wrench_send_ != kNotYet) {
    const double dt = std::min(0.1, to_seconds(now - last_wrench_send_));
    passivity_.on_image_step(held_wrench_, channel_twist_, dt);
  }
  last_wrench_send_ = now;
  held_wrench_ = wrench;
  if (latest_.valid) {
    close_locally();
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_WRENCH_TIMED, token_, next_control_sequence(), to_ns(now));
  hcp_control_wrench_timed& w = f.body.hcp_body_u.wrench_timed;
  protocol::to_wire(wrench, w.wrench);
  w.answer_echo = answer_echo(now);
  w.energy_in = passivity_.energy_in_uj();
  return checked_control(f);
}

ContactResult ClientSession::set_contacts(std::span<const Contact> contacts) noexcept {
  if (!local()) {
    return ContactResult::kUnsupported;
  }
  return contacts_.set(contacts, local_.max_contact_stiffness);
}

std::optional<hcp_frame> ClientSession::contact_frame_due(TimePoint now) noexcept {
  if (!open_ || !local()) {
    return std::nullopt;
  }
  const std::optional<ContactSend> send = contacts_.due(now);
  if (!send) {
    return std::nullopt;
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_CONTACT, token_, next_control_sequence(), to_ns(now));
  hcp_control_contact& c = f.body.hcp_body_u.contact;
  c.slots = send->slots;
  c.answer_echo = answer_echo(now);
  c.contact = send->contact;
  return checked_control(f);
}

}  // namespace hapticctrl::client
