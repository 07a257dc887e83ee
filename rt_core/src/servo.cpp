// Implements servo.hpp: the SERVO task's steps (docs/rt_core.md, *The cycle*): read measures, build
// the logical state from ctrl, exchange with the protocol regions, run the law, send commands,
// publish VP and position.
#include "hapticctrl/rt_core/servo.hpp"

#include "hapticctrl/base/realtime.hpp"

#include <cmath>

namespace hapticctrl::rt_core {
namespace {

template <std::size_t N>
HAPTICCTRL_RT bool all_finite(const std::array<double, N>& values) noexcept {
  for (const double v : values) {
    if (!std::isfinite(v)) {
      return false;
    }
  }
  return true;
}

/// A frame pose's rotation must be a unit quaternion (1 % tolerance for float clients).
HAPTICCTRL_RT bool unit_quaternion(const shm::Pose7& pose) noexcept {
  const double norm_sq =
      pose[3] * pose[3] + pose[4] * pose[4] + pose[5] * pose[5] + pose[6] * pose[6];
  return std::abs(norm_sq - 1.0) <= 0.02;
}

/// A contact slot is usable if its numbers are finite, its normal a unit vector (2 %) and its
/// stiffness positive and at most `max_stiffness`, the stiffest the device renders.
HAPTICCTRL_RT bool contact_valid(const shm::ContactSlot& c, double max_stiffness) noexcept {
  double norm_sq = 0.0;
  for (const double n : c.normal) {
    norm_sq += n * n;
  }
  return all_finite(c.point) && all_finite(c.normal) && all_finite(c.friction) &&
         all_finite(c.object_pose) && unit_quaternion(c.object_pose) &&
         std::abs(norm_sq - 1.0) <= 0.02 && std::isfinite(c.distance) && std::isfinite(c.damping) &&
         c.damping >= 0.0 && c.stiffness > 0.0 && c.stiffness <= max_stiffness &&
         c.friction[0] >= 0.0 && c.friction[1] >= 0.0;
}

/// A client sample is usable only if every number in it is finite and in a sane range.
HAPTICCTRL_RT bool client_sample_valid(const shm::VprPayload& s) noexcept {
  return s.command_type <= static_cast<std::uint32_t>(shm::CommandType::kArticularImpedance) &&
         all_finite(s.object_pose) && all_finite(s.object_twist) && all_finite(s.joint_target) &&
         all_finite(s.joint_speed) && all_finite(s.joint_torque) &&
         all_finite(s.impedance_wrench) && all_finite(s.object_inertia) &&
         std::isfinite(s.object_mass) && s.object_mass >= 0.0 &&
         std::isfinite(s.client_time_step) && s.client_time_step >= 0.0 &&
         std::isfinite(s.force_factor) && std::isfinite(s.speed_factor) &&
         all_finite(s.base_frame) && all_finite(s.observation_frame) &&
         unit_quaternion(s.base_frame) && unit_quaternion(s.observation_frame) &&
         all_finite(s.gain_override) && all_finite(s.force_limits) &&
         std::isfinite(s.client_energy_in);  // negative: not reported
}

/// When the client computed the sample, on our clock: the bridge's estimate (protocol timing)
/// when it is plausible (not in the future, not older than its arrival by more than 10 s),
/// otherwise its arrival here.
HAPTICCTRL_RT TimePoint sample_time_of(const shm::VprPayload& s, TimePoint arrival) noexcept {
  constexpr Duration kMaxAge = std::chrono::seconds(10);
  const TimePoint computed = time_point_from_ns(s.sample_time_ns);
  return s.sample_time_ns > 0 && computed <= arrival && arrival - computed <= kMaxAge ? computed
                                                                                      : arrival;
}

/// The coupling loop's delay: cycles from the answer the client echoed to this one (0: none).
HAPTICCTRL_RT Duration loop_delay_of(const shm::VprPayload& s, std::uint64_t cycle,
                                     Duration period) noexcept {
  if (s.echo_cycle == 0 || s.echo_cycle > cycle) {
    return Duration{0};
  }
  return static_cast<std::int64_t>(cycle - s.echo_cycle) * period;
}

/// The law's view of the sample's contacts: the valid ones in their slots (an invalid one is
/// left empty and counted in `rejected`, once per contact frame it came with).
HAPTICCTRL_RT void take_contacts(const shm::VprPayload& s, double max_stiffness, ClientSample& c,
                                 std::uint64_t& rejected) noexcept {
  c.contact_count = std::min<std::uint32_t>(s.contact_count, kMaxClientContacts);
  for (std::size_t i = 0; i < kMaxClientContacts; ++i) {
    const shm::ContactSlot& from = s.contacts[i];
    ClientContact& to = c.contacts[i];
    to = ClientContact{};
    if (i >= c.contact_count || from.stiffness == 0.0) {
      continue;
    }
    if (!contact_valid(from, max_stiffness)) {
      ++rejected;
      continue;
    }
    to.point = from.point;
    to.normal = from.normal;
    to.distance = from.distance;
    to.stiffness = from.stiffness;
    to.damping = from.damping;
    to.friction = from.friction;
    to.object_pose = from.object_pose;
    to.received = time_point_from_ns(from.received_time_ns);
  }
}

/// The law's view of a valid sample (client_sample.hpp): the ABI stops here.
HAPTICCTRL_RT ClientSample client_sample_of(const shm::VprPayload& s) noexcept {
  ClientSample c;
  c.session_id = s.session_id;
  switch (static_cast<shm::CommandType>(s.command_type)) {
    case shm::CommandType::kImpedance:
      c.command = ClientCommand::kImpedance;
      break;
    case shm::CommandType::kVirtmech:
      c.command = ClientCommand::kVirtmech;
      break;
    case shm::CommandType::kArticular:
      c.command = ClientCommand::kArticular;
      break;
    case shm::CommandType::kArticularImpedance:
      c.command = ClientCommand::kArticularImpedance;
      break;
    case shm::CommandType::kNone:
      c.command = ClientCommand::kNone;
      break;
  }
  c.object_attached = (s.flags & shm::vpr_flags::kObjectAttached) != 0;
  c.object_pose = s.object_pose;
  c.object_twist = s.object_twist;
  c.impedance_wrench = s.impedance_wrench;
  c.joint_target = s.joint_target;
  c.joint_speed = s.joint_speed;
  c.joint_torque = s.joint_torque;
  c.object_mass = s.object_mass;
  c.object_inertia = s.object_inertia;
  c.time_step = s.client_time_step;
  c.force_factor = s.force_factor;
  c.speed_factor = s.speed_factor;
  c.base_frame = s.base_frame;
  c.gain_override = s.gain_override;
  c.force_limits = s.force_limits;
  c.energy_in = s.client_energy_in;
  c.local_coupling = (s.flags & shm::vpr_flags::kLocalCoupling) != 0;
  c.joint_command = (s.flags & shm::vpr_flags::kJointCommand) != 0;
  return c;
}

HAPTICCTRL_RT void copy_to(const Vector6d& from, std::array<double, 6>& to) noexcept {
  for (std::size_t i = 0; i < 6; ++i) {
    to[i] = from(static_cast<Eigen::Index>(i));
  }
}

}  // namespace

double ServoTask::max_contact_stiffness(double speed_factor) const noexcept {
  // In the client's units: a surface of K N per client metre is K * speed_factor per our metre.
  return law_.dynamics().model().limits.max_stiffness_linear /
         (speed_factor > 0.0 ? speed_factor : 1.0);
}

void ServoTask::publish_surface(const ClientFrame& frame, shm::VpPayload& vp) const noexcept {
  // In the client's frame and units, as the contacts came.
  const ServoOutputs& o = outputs_;
  const Vector3d point = frame.origin + frame.rotation * (o.surface_point * frame.speed_factor);
  const Vector3d normal = frame.rotation * o.surface_normal;
  vp.surface_point = {point.x(), point.y(), point.z()};
  vp.surface_normal = {normal.x(), normal.y(), normal.z()};
  vp.surface_depth = o.surface_depth * frame.speed_factor;
  vp.surface_force = o.surface_force;
  vp.surface_hidden = o.surface_hidden * frame.speed_factor;
  vp.surface_withheld = o.surface_withheld;
  vp.contact_age_ns = o.contact_age ? to_ns(*o.contact_age) : -1;  // the region's "none"
}

StepResult ServoTask::begin(std::uint64_t cycle, TimePoint now, Duration dt) noexcept {
  if (!gate_->enter(cycle)) {
    return StepResult::kNotGranted;
  }
  gather(cycle, now, dt);
  gate_->leave(cycle);
  law_.compute(inputs_, role_ == TaskRole::kDegraded, outputs_);
  return StepResult::kDone;
}

StepResult ServoTask::finish(std::uint64_t cycle, TimePoint now) noexcept {
  if (!gate_->enter(cycle)) {
    to_clock_->counters.late_discarded.fetch_add(1, std::memory_order_relaxed);
    return StepResult::kDiscarded;
  }
  commit(cycle, now);
  gate_->leave(cycle);
  return StepResult::kDone;
}

StepResult ServoTask::run(std::uint64_t cycle, TimePoint now, Duration dt) noexcept {
  const StepResult begun = begin(cycle, now, dt);
  return begun == StepResult::kDone ? finish(cycle, now) : begun;
}

void ServoTask::gather(std::uint64_t cycle, TimePoint now, Duration dt) noexcept {
  GateOwnedState& s = *state_;
  ServoCounters& counters = to_clock_->counters;
  inputs_.cycle = cycle;
  inputs_.now = now;
  inputs_.dt = dt;
  if (!s.arm->get_measures(inputs_.measures)) {
    counters.arm_faults.fetch_add(1, std::memory_order_relaxed);
  }
  counters.force_rejected.store(inputs_.measures.operator_wrench_rejected,
                                std::memory_order_relaxed);

  // Logical state from ctrl, in each writer's order.
  s.ctrl.drain([&](const shm::CtrlCommand& command) {
    const bool accepted = s.interpreter.apply(command, s.logical);
    (accepted ? counters.ctrl_accepted : counters.ctrl_rejected)
        .fetch_add(1, std::memory_order_relaxed);
    return accepted;
  });
  if (s.logical.stop_requested) {
    to_clock_->stop_requested.store(true, std::memory_order_release);
  }
  ScheduledOverrun& scheduled = s.scheduled_overrun;
  if (scheduled.at_cycle != 0 && cycle >= scheduled.at_cycle && role_ == TaskRole::kMain) {
    s.logical.pending_overrun_cycles = scheduled.cycles;
    scheduled.at_cycle = 0;
  }
  if (s.logical.pending_overrun_cycles > 0 && role_ == TaskRole::kMain) {
    overrun_->request(s.logical.pending_overrun_cycles);
    s.logical.pending_overrun_cycles = 0;
  }
  const bool want_supply = s.logical.powered;
  if (want_supply != s.supply_on) {
    s.arm->set_supply(want_supply);
    s.supply_on = want_supply;
    s.arm->get_measures(inputs_.measures);
  }
  inputs_.logical = s.logical;
  law_.continue_from(s.rendered);
  exchange_client(now);
}

void ServoTask::exchange_client(TimePoint now) noexcept {
  GateOwnedState& s = *state_;
  ServoCounters& counters = to_clock_->counters;
  inputs_.new_sample = false;
  if (s.regions.vpr != nullptr) {
    shm::VprPayload sample;
    const shm::ReadResult r = s.regions.vpr->read(sample);
    if (r.status == shm::ReadStatus::kTorn) {
      counters.vpr_torn.fetch_add(1, std::memory_order_relaxed);
    } else if (r.ok() && r.sequence != s.last_client_sequence) {
      s.last_client_sequence = r.sequence;
      if (client_sample_valid(sample)) {
        // A new object state (or wrench) only when the client's sequence moved: a contact frame
        // republishes VPr with the same sample.
        const bool new_state = !s.client_valid || sample.session_id != s.last_client.session_id ||
                               sample.client_sequence != s.last_client.client_sequence;
        const bool new_contacts = sample.contact_frames != s.last_client.contact_frames;
        if (sample.session_id != s.last_client.session_id) {
          s.contacts_rejected = 0;  // counted per session, as the client sees it
        }
        s.last_client = sample;
        s.client = client_sample_of(sample);
        std::uint64_t rejected = 0;
        take_contacts(sample, max_contact_stiffness(sample.speed_factor), s.client, rejected);
        if (new_contacts && rejected > 0) {
          ++s.contacts_rejected;
        }
        s.client_valid = true;
        if (new_state) {
          s.last_client_arrival = now;
          s.last_client_time = sample_time_of(sample, now);
          inputs_.new_sample = true;
          inputs_.loop_delay = loop_delay_of(sample, inputs_.cycle, inputs_.dt);
        }
      } else {
        counters.vpr_rejected.fetch_add(1, std::memory_order_relaxed);
      }
    }
  }
  inputs_.client = s.client;
  inputs_.client_valid = s.client_valid;
  inputs_.client_age = s.client_valid ? now - s.last_client_time : Duration{0};
  inputs_.client_silence = s.client_valid ? now - s.last_client_arrival : Duration{0};
}

void ServoTask::commit(std::uint64_t cycle, TimePoint now) noexcept {
  GateOwnedState& s = *state_;
  ServoToClock& report = *to_clock_;
  ArmCommands commands = outputs_.commands;
  commands.enable = commands.enable && s.logical.powered && !from_clock_->commands_inhibited();
  if (!commands.enable) {
    commands.torque.setZero();
  }
  s.arm->send_commands(commands, now, inputs_.dt);
  if (outputs_.velocity_fault && commands.enable) {
    report.velocity_fault.store(true, std::memory_order_release);  // the CLOCK fails safe
  }
  s.rendered = commands.enable ? law_.memory() : RenderMemory{};

  std::uint32_t state_word = s.logical.state_word() | from_clock_->state_bits();
  if (role_ == TaskRole::kDegraded) {
    state_word |= shm::state_bits::kDegraded;
  }
  if (outputs_.coupled && commands.enable) {
    state_word |= shm::state_bits::kCoupled;
  }
  if (outputs_.saturated && commands.enable) {
    state_word |= shm::state_bits::kSaturated;
  }
  state_word |= outputs_.joint_bounds;
  if (outputs_.client_stale) {
    state_word |= shm::state_bits::kClientStale;
    report.counters.vpr_stale.fetch_add(1, std::memory_order_relaxed);
  }
  report.committed_state_word.store(state_word, std::memory_order_relaxed);
  report.committed_session.store(s.client_valid ? s.last_client.session_id : 0,
                                 std::memory_order_relaxed);
  const std::uint32_t core_state = from_clock_->core_state();
  const std::uint32_t stop_reason = from_clock_->stop_reason();

  if (s.regions.vp != nullptr) {
    shm::VpPayload vp;
    vp.cycle = cycle;
    vp.echo_client_sequence = s.last_client.client_sequence;
    vp.echo_client_time_ns = s.last_client.client_time_ns;
    vp.state_word = state_word;
    vp.core_state = core_state;
    vp.stop_reason = stop_reason;
    vp.command_type = s.last_client.command_type;
    copy_to(outputs_.object_wrench, vp.object_wrench);
    vp.client_handle_pose = outputs_.client_handle_pose;
    copy_to(outputs_.client_handle_twist, vp.client_handle_twist);
    copy_to(inputs_.measures.position, vp.joint_position);
    copy_to(inputs_.measures.velocity, vp.joint_velocity);
    vp.sample_age_ns = inputs_.client_valid ? to_ns(inputs_.client_age) : 0;
    vp.loop_delay_ns = to_ns(outputs_.loop_delay);
    const CouplingGains& g = outputs_.gains;
    vp.gains = {g.k_linear, g.b_linear, g.k_angular, g.b_angular};
    vp.channel_energy_in = outputs_.channel_energy_in;
    vp.channel_energy_out = outputs_.channel_energy_out;
    const Vector3d normal = client_frame_of(s.client).rotation * outputs_.contact_normal;
    vp.contact_normal = {normal.x(), normal.y(), normal.z()};
    vp.normal_gains = {outputs_.normal_stiffness, outputs_.normal_damping};
    vp.limits = {outputs_.force_limit, outputs_.torque_limit};
    vp.max_contact_stiffness = max_contact_stiffness(s.client.speed_factor);
    vp.contacts = outputs_.contacts;
    vp.contacts_rejected = s.contacts_rejected;
    publish_surface(client_frame_of(s.client), vp);
    s.regions.vp->publish(vp, to_ns(now));  // the UDP bridge blocks on VP: notify
  }
  if (s.regions.position != nullptr) {
    shm::PositionPayload pos;
    pos.cycle = cycle;
    pos.state_word = state_word;
    pos.core_state = core_state;
    copy_to(inputs_.measures.position, pos.joint_position);
    copy_to(inputs_.measures.velocity, pos.joint_velocity);
    copy_to(commands.torque, pos.joint_torque);
    pos.handle_pose = outputs_.handle_pose;
    copy_to(outputs_.handle_twist, pos.handle_twist);
    copy_to(inputs_.measures.operator_wrench, pos.operator_wrench);
    copy_to(outputs_.rendered_wrench, pos.rendered_wrench);
    s.regions.position->publish_quietly(pos, to_ns(now));
  }
  report.commit_cycle.store(cycle, std::memory_order_release);
}

}  // namespace hapticctrl::rt_core
