// Implements control_ingest.hpp: a session's control frames, in order, into its VPr.
#include "hapticctrl/udp_bridge/control_ingest.hpp"

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::udp_bridge {

void ControlIngest::reset() noexcept {
  have_sequence_ = false;
  sequence_high_ = 0;
  link_.reset();
  have_energy_ = false;
  energy_in_total_ = 0.0;
}

bool ControlIngest::admit(std::uint32_t sequence) noexcept {
  if (have_sequence_ && !protocol::sequence_newer(sequence, last_sequence_)) {
    return false;
  }
  if (have_sequence_) {
    const std::uint32_t step = sequence - last_sequence_;  // modulo 2^32
    sequence_high_ += step;
    link_.add_arrival(step - 1);
  } else {
    sequence_high_ = sequence;
  }
  have_sequence_ = true;
  last_sequence_ = sequence;
  return true;
}

void ControlIngest::take(const hcp_frame& in, TimePoint now, shm::VprPayload& vpr) noexcept {
  if (in.body.type == HCP_CONTROL_CONTACT) {
    take_contact(in.body.hcp_body_u.contact, now, vpr);  // a contact is not a new object sample
  } else {
    take_sample(in, now, vpr);
  }
}

namespace {

/// A joint frame is the command of `frame_mode`: it counts once that mode is in force.
void mark_joint_command(shm::CommandType frame_mode, shm::VprPayload& vpr) noexcept {
  if (vpr.command_type == static_cast<std::uint32_t>(frame_mode)) {
    vpr.flags |= shm::vpr_flags::kJointCommand;
  }
}

}  // namespace

void ControlIngest::take_sample(const hcp_frame& in, TimePoint now, shm::VprPayload& vpr) noexcept {
  vpr.sample_time_ns = 0;
  vpr.echo_cycle = 0;
  const hcp_body& b = in.body;
  switch (b.type) {
    case HCP_CONTROL_OBJECT:
      protocol::from_wire(b.hcp_body_u.object.pose, vpr.object_pose);
      protocol::from_wire(b.hcp_body_u.object.twist, vpr.object_twist);
      break;
    case HCP_CONTROL_OBJECT_TIMED:
      take_timed_object(b.hcp_body_u.timed, now, vpr);
      break;
    case HCP_CONTROL_WRENCH_TIMED:
      protocol::from_wire(b.hcp_body_u.wrench_timed.wrench, vpr.impedance_wrench);
      take_timing(b.hcp_body_u.wrench_timed.answer_echo, b.hcp_body_u.wrench_timed.energy_in, now,
                  vpr);
      break;
    case HCP_CONTROL_JOINT_TARGET:
      protocol::from_wire(b.hcp_body_u.joint_target.position, vpr.joint_target);
      protocol::from_wire(b.hcp_body_u.joint_target.speed, vpr.joint_speed);
      mark_joint_command(shm::CommandType::kArticular, vpr);
      break;
    case HCP_CONTROL_JOINT_TORQUE:
      protocol::from_wire(b.hcp_body_u.joint_torque.torque, vpr.joint_torque);
      mark_joint_command(shm::CommandType::kArticularImpedance, vpr);
      break;
    default:  // CONTROL_WRENCH
      protocol::from_wire(b.hcp_body_u.wrench.wrench, vpr.impedance_wrench);
      break;
  }
  const LinkFigures figures = link();
  vpr.link_delay_ns = to_ns(figures.delay);
  vpr.link_jitter_ns = to_ns(figures.jitter);
  vpr.link_loss_ppm = figures.loss_ppm;
  vpr.client_sequence = sequence_high_;
  vpr.client_time_ns = in.header.sender_time_ns;
}

void ControlIngest::take_contact(const hcp_control_contact& c, TimePoint now,
                                 shm::VprPayload& vpr) noexcept {
  // The decoder checked the slot word and the values (values.cpp).
  const protocol::ContactSlots slots = protocol::contact_slots(c.slots);
  vpr.contact_count = slots.count;
  ++vpr.contact_frames;
  for (std::size_t i = slots.count; i < shm::kMaxContacts; ++i) {
    vpr.contacts[i] = shm::ContactSlot{};  // slots at and above the count are empty
  }
  if (slots.count == 0) {
    return;
  }
  shm::ContactSlot& to = vpr.contacts[slots.slot];
  const hcp_contact& from = c.contact;
  protocol::from_wire(from.point, to.point);
  protocol::from_wire(from.normal, to.normal);
  to.distance = static_cast<double>(from.distance);
  to.stiffness = static_cast<double>(from.stiffness);
  to.damping = static_cast<double>(from.damping);
  protocol::from_wire(from.friction, to.friction);
  // An IMPEDANCE client has no object (its surfaces are for the handle's point): the identity.
  to.object_pose = vpr.command_type == static_cast<std::uint32_t>(shm::CommandType::kImpedance)
                       ? shm::Pose7{0, 0, 0, 0, 0, 0, 1}
                       : vpr.object_pose;
  to.received_time_ns = to_ns(now);
  const SampleTiming timing =
      LinkEstimator::time_sample(protocol::unpack_answer_echo(c.answer_echo), *answers_, now);
  to.sample_time_ns = timing.measured ? to_ns(timing.sample_time) : 0;
}

void ControlIngest::take_timed_object(const hcp_control_object_timed& o, TimePoint now,
                                      shm::VprPayload& vpr) noexcept {
  // The decoder checked the packed rotation (values.cpp): it unpacks.
  const protocol::Quaternion q = protocol::unpack_rotation({o.rotation[0], o.rotation[1]})
                                     .value_or(protocol::Quaternion{0, 0, 0, 1});
  for (std::size_t i = 0; i < 3; ++i) {
    vpr.object_pose[i] = static_cast<double>(o.position[i]);
    vpr.object_pose[i + 3] = q[i];
  }
  vpr.object_pose[6] = q[3];
  protocol::from_wire(o.twist, vpr.object_twist);
  take_timing(o.answer_echo, o.energy_in, now, vpr);
}

void ControlIngest::take_timing(std::uint32_t answer_echo, std::uint32_t energy_in_uj,
                                TimePoint now, shm::VprPayload& vpr) noexcept {
  // The client's cumulative energy, modulo 2^32 uJ: add up the differences, but not one that is
  // not physical (kMaxEnergyStepUj).
  const std::uint32_t step_uj = energy_in_uj - energy_in_last_;
  if (have_energy_ && step_uj <= kMaxEnergyStepUj) {
    energy_in_total_ += static_cast<double>(step_uj) * 1e-6;
  }
  have_energy_ = true;
  energy_in_last_ = energy_in_uj;
  vpr.client_energy_in = energy_in_total_;
  const SampleTiming timing =
      LinkEstimator::time_sample(protocol::unpack_answer_echo(answer_echo), *answers_, now);
  link_.add(timing);
  if (timing.measured) {
    vpr.sample_time_ns = to_ns(timing.sample_time);
    vpr.echo_cycle = timing.echo_cycle;
  }
}

}  // namespace hapticctrl::udp_bridge
