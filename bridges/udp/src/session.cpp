// The UDP bridge's session: the handshake, the session's life (watchdog, close, BYE) and the
// control frames into VPr. Parameters are in session_parameters.cpp, the answer side in
// session_answer.cpp.
#include "hapticctrl/udp_bridge/session.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using protocol::DecodeStatus;
using shm::LinkDrop;

shm::VprPayload fresh_vpr(std::uint64_t session_number) noexcept {
  shm::VprPayload v;
  v.session_id = session_number;
  return v;
}

}  // namespace

LinkDrop drop_reason_of(DecodeStatus status) noexcept {
  switch (status) {
    case DecodeStatus::kBadSize:
      return LinkDrop::kSize;
    case DecodeStatus::kBadMagic:
      return LinkDrop::kMagic;
    case DecodeStatus::kBadCrc:
      return LinkDrop::kCrc;
    case DecodeStatus::kBadVersion:
      return LinkDrop::kVersion;
    case DecodeStatus::kOutOfRange:
      return LinkDrop::kRange;
    case DecodeStatus::kMalformed:
    case DecodeStatus::kOk:
      break;
  }
  return LinkDrop::kMalformed;
}

Session::Session(SessionSettings settings, std::function<std::uint64_t()> random_token)
    : settings_(std::move(settings)),
      random_token_(std::move(random_token)),
      hello_limiter_(settings_.hello_limits) {
  view_.publish_quietly(session_, 0);
}

void Session::set_controller(const ControllerPorts* ports, TimeNs now) noexcept {
  if (session_.token != 0) {
    end_session(now);
  }
  have_controller_ = ports != nullptr && ports->vpr != nullptr;
  ports_ = have_controller_ ? *ports : ControllerPorts{};
}

void Session::on_oversized() noexcept {
  counters_.frames_in.fetch_add(1, std::memory_order_relaxed);
  counters_.drop(LinkDrop::kSize);
}

std::size_t Session::on_datagram(std::span<const std::uint8_t> bytes,
                                 const protocol::Endpoint& from, TimeNs now,
                                 std::span<std::uint8_t> reply) noexcept {
  counters_.frames_in.fetch_add(1, std::memory_order_relaxed);
  const std::uint32_t source = ntohl(from.address.sin_addr.s_addr);
  if (!settings_.allowed_clients.allows(source)) {
    counters_.drop(LinkDrop::kNotAllowed);  // not even decoded
    return 0;
  }
  hcp_frame in;
  const DecodeStatus status = protocol::decode(bytes, in);
  // A PARAM with a bad value from the session is answered (REJECTED), and a HELLO asking for
  // out-of-range values is refused (BAD_REQUEST, as the .x says), not silently dropped.
  const bool out_of_range = status == DecodeStatus::kOutOfRange;
  const bool param_out_of_range = out_of_range && in.body.type == HCP_PARAM;
  const bool hello_out_of_range = out_of_range && in.body.type == HCP_HELLO;
  if (status != DecodeStatus::kOk && !param_out_of_range && !hello_out_of_range) {
    counters_.drop(drop_reason_of(status));
    return 0;
  }
  switch (in.body.type) {
    case HCP_HELLO:
      if (!hello_limiter_.admit(source, now)) {
        counters_.drop(LinkDrop::kRateLimited);
        return 0;
      }
      if (hello_out_of_range) {
        counters_.drop(LinkDrop::kRange);  // no session for it: counted, and told why
        const protocol::Problem why = protocol::check_hello(in.body.hcp_body_u.hello);
        return refuse(HCP_REFUSE_BAD_REQUEST, in.header.protocol, 0,
                      why ? *why : std::string_view("HELLO values out of range"), now, reply);
      }
      return on_hello(in, from, now, reply);
    case HCP_CONTROL_OBJECT:
    case HCP_CONTROL_OBJECT_TIMED:
    case HCP_CONTROL_WRENCH:
    case HCP_CONTROL_WRENCH_TIMED:
    case HCP_CONTROL_CONTACT:
    case HCP_CONTROL_JOINT_TARGET:
    case HCP_CONTROL_JOINT_TORQUE:
    case HCP_KEEPALIVE:
      if (!from_session(in, from) || !negotiated(in.body.type)) {
        counters_.drop(LinkDrop::kToken);
        return 0;
      }
      on_control(in, now);
      return 0;
    case HCP_PARAM:
      if (!from_session(in, from)) {
        counters_.drop(LinkDrop::kToken);
        return 0;
      }
      return on_param(in, !param_out_of_range, now, reply);
    case HCP_BYE:
      if (!from_session(in, from)) {
        counters_.drop(LinkDrop::kToken);
        return 0;
      }
      return on_bye(in, now, reply);
    case HCP_REFUSE:  // the client refuses our WELCOME (no common version): end its session
      if (from_session(in, from)) {
        end_session(now);
      } else {
        counters_.drop(LinkDrop::kToken);
      }
      return 0;
    case HCP_WELCOME:
    case HCP_ANSWER:
    case HCP_ANSWER_TIMED:
    case HCP_ANSWER_COUPLED:
    case HCP_ACK:
      break;
  }
  counters_.drop(LinkDrop::kUnexpected);
  return 0;
}

bool Session::negotiated(hcp_frame_type type) const noexcept {
  switch (type) {
    case HCP_CONTROL_OBJECT_TIMED:
      return (session_.features & HCP_FEATURE_TIMING) != 0;
    case HCP_CONTROL_WRENCH_TIMED:
    case HCP_CONTROL_CONTACT:
      return (session_.features & HCP_FEATURE_LOCAL_COUPLING) != 0;
    case HCP_CONTROL_JOINT_TARGET:
    case HCP_CONTROL_JOINT_TORQUE:
      return (session_.features & HCP_FEATURE_JOINT_CONTROL) != 0;
    default:
      return true;
  }
}

bool Session::from_session(const hcp_frame& in, const protocol::Endpoint& from) const noexcept {
  return session_.token != 0 && in.header.token == session_.token && from == session_.peer;
}

std::size_t Session::on_hello(const hcp_frame& in, const protocol::Endpoint& from, TimeNs now,
                              std::span<std::uint8_t> reply) noexcept {
  const hcp_hello& hello = in.body.hcp_body_u.hello;
  const std::uint32_t theirs = in.header.protocol;
  const std::uint32_t our_major = protocol::version_major(protocol::kVersion);
  if (protocol::version_major(hello.min_version) > our_major ||
      protocol::version_major(theirs) < our_major) {
    counters_.refused_version.fetch_add(1, std::memory_order_relaxed);
    char text[HCP_TEXT_BYTES];  // NOLINT(*-avoid-c-arrays)
    std::snprintf(text, sizeof text,
                  "protocol version mismatch: client %u.%u (oldest %u.%u), controller %u.%u",
                  protocol::version_major(theirs), protocol::version_minor(theirs),
                  protocol::version_major(hello.min_version),
                  protocol::version_minor(hello.min_version), our_major,
                  protocol::version_minor(protocol::kVersion));
    return refuse(HCP_REFUSE_VERSION, theirs, 0, text, now, reply);
  }
  if (session_.token != 0) {
    if (from == session_.peer) {  // our WELCOME was lost: the same client asks again
      last_heard_ = now;
      return welcome(now, reply);
    }
    counters_.refused_busy.fetch_add(1, std::memory_order_relaxed);
    const TimeNs silent_ms = (now - last_heard_) / 1'000'000;
    const auto retry = static_cast<std::uint32_t>(
        std::max<TimeNs>(1, static_cast<TimeNs>(watchdog_ms_) - silent_ms));
    return refuse(HCP_REFUSE_BUSY, theirs, retry,
                  "busy: another client session is active on this controller", now, reply);
  }
  if (!have_controller_) {
    return refuse(HCP_REFUSE_NO_CONTROLLER, theirs, 0,
                  "no controller: hapticctrl-core is not running for this bridge's instance", now,
                  reply);
  }
  open(in, from, now);
  return welcome(now, reply);
}

void Session::open(const hcp_frame& hello, const protocol::Endpoint& from, TimeNs now) noexcept {
  std::uint64_t token = 0;
  while (token == 0) {
    token = random_token_();
  }
  session_.token = token;
  session_.peer = from;
  session_.features = hello.body.hcp_body_u.hello.features & protocol::kAllFeatures;
  if ((session_.features & HCP_FEATURE_TIMING) == 0) {
    session_.features &= ~static_cast<std::uint32_t>(HCP_FEATURE_LOCAL_COUPLING);  // builds on it
  }
  const std::uint32_t asked = hello.body.hcp_body_u.hello.watchdog_ms;
  watchdog_ms_ =
      std::min(asked != 0 ? asked : settings_.default_watchdog_ms, settings_.max_watchdog_ms);
  last_heard_ = now;
  engaged_ = false;
  have_control_seq_ = false;
  have_param_seq_ = false;
  control_seq_high_ = 0;
  control_received_ = 0;
  control_received_shared_.store(0, std::memory_order_relaxed);
  link_.reset();
  link_view_.publish_quietly({}, 0);
  have_energy_ = false;
  energy_in_total_ = 0.0;
  vpr_ = fresh_vpr(++session_number_);
  vpr_.watchdog_timeout_us = watchdog_ms_ * 1000U;
  if ((session_.features & HCP_FEATURE_LOCAL_COUPLING) != 0) {
    vpr_.flags |= shm::vpr_flags::kLocalCoupling;
  }
  publish_vpr(now);
  publish_view();
  counters_.sessions_opened.fetch_add(1, std::memory_order_relaxed);
}

void Session::end_session(TimeNs now) noexcept {
  session_ = SessionView{};
  publish_view();
  vpr_ = fresh_vpr(0);  // session 0: the core renders nothing and ramps any wrench out
  publish_vpr(now);
}

std::size_t Session::close(TimeNs now, std::string_view why, std::span<std::uint8_t> notice,
                           protocol::Endpoint& to) noexcept {
  if (session_.token == 0) {
    return 0;
  }
  to = session_.peer;
  const std::size_t n =
      refuse(HCP_REFUSE_NO_CONTROLLER, protocol::kVersion, 0, why, now, notice, session_.token);
  end_session(now);
  return n;
}

bool Session::check_watchdog(TimeNs now) noexcept {
  // A session that sent nothing since its HELLO is held no longer than the default.
  const std::uint32_t limit_ms =
      engaged_ ? watchdog_ms_ : std::min(watchdog_ms_, settings_.default_watchdog_ms);
  if (session_.token == 0 || now - last_heard_ <= static_cast<TimeNs>(limit_ms) * 1'000'000) {
    return false;
  }
  counters_.watchdog_expiries.fetch_add(1, std::memory_order_relaxed);
  end_session(now);
  return true;
}

void Session::on_control(const hcp_frame& in, TimeNs now) noexcept {
  const std::uint32_t seq = in.header.sequence;
  if (have_control_seq_ && !protocol::sequence_newer(seq, last_control_seq_)) {
    counters_.drop(LinkDrop::kSequence);
    return;
  }
  if (have_control_seq_) {
    const auto step = static_cast<std::uint32_t>(seq - last_control_seq_);
    control_seq_high_ += step;
    link_.add_arrival(step - 1);
  } else {
    control_seq_high_ = seq;
  }
  have_control_seq_ = true;
  last_control_seq_ = seq;
  last_heard_ = now;
  engaged_ = true;
  if (in.body.type == HCP_KEEPALIVE) {
    return;  // feeds the watchdog only: the core keeps judging the freshness of client data
  }
  if (in.body.type == HCP_CONTROL_CONTACT) {
    take_contact(in.body.hcp_body_u.contact, now);  // a contact is not a new object sample
  } else {
    take_sample(in, now);
  }
  publish_vpr(now);
  ++control_received_;
  control_received_shared_.store(control_received_, std::memory_order_relaxed);
  counters_.control_accepted.fetch_add(1, std::memory_order_relaxed);
}

void Session::take_sample(const hcp_frame& in, TimeNs now) noexcept {
  vpr_.sample_time_ns = 0;
  vpr_.echo_cycle = 0;
  const hcp_body& b = in.body;
  switch (b.type) {
    case HCP_CONTROL_OBJECT:
      protocol::from_wire(b.hcp_body_u.object.pose, vpr_.object_pose);
      protocol::from_wire(b.hcp_body_u.object.twist, vpr_.object_twist);
      break;
    case HCP_CONTROL_OBJECT_TIMED:
      take_timed_object(b.hcp_body_u.timed, now);
      break;
    case HCP_CONTROL_WRENCH_TIMED:
      protocol::from_wire(b.hcp_body_u.wrench_timed.wrench, vpr_.impedance_wrench);
      take_timing(b.hcp_body_u.wrench_timed.answer_echo, b.hcp_body_u.wrench_timed.energy_in, now);
      break;
    case HCP_CONTROL_JOINT_TARGET:
      protocol::from_wire(b.hcp_body_u.joint_target.position, vpr_.joint_target);
      protocol::from_wire(b.hcp_body_u.joint_target.speed, vpr_.joint_speed);
      mark_joint_command(shm::CommandType::kArticular);
      break;
    case HCP_CONTROL_JOINT_TORQUE:
      protocol::from_wire(b.hcp_body_u.joint_torque.torque, vpr_.joint_torque);
      mark_joint_command(shm::CommandType::kArticularImpedance);
      break;
    default:  // CONTROL_WRENCH
      protocol::from_wire(b.hcp_body_u.wrench.wrench, vpr_.impedance_wrench);
      break;
  }
  vpr_.link_delay_ns = link_.delay();
  vpr_.link_jitter_ns = link_.jitter();
  vpr_.link_loss_ppm = link_.loss_ppm();
  link_view_.publish_quietly({vpr_.link_delay_ns, vpr_.link_jitter_ns, vpr_.link_loss_ppm, 0}, now);
  vpr_.client_sequence = control_seq_high_;
  vpr_.client_time_ns = in.header.sender_time_ns;
}

void Session::mark_joint_command(shm::CommandType frame_mode) noexcept {
  if (vpr_.command_type == static_cast<std::uint32_t>(frame_mode)) {
    vpr_.flags |= shm::vpr_flags::kJointCommand;
  }
}

void Session::take_contact(const hcp_control_contact& c, TimeNs now) noexcept {
  // The decoder checked the slot word and the values (values.cpp).
  const protocol::ContactSlots slots = protocol::contact_slots(c.slots);
  vpr_.contact_count = slots.count;
  ++vpr_.contact_frames;
  for (std::size_t i = slots.count; i < shm::kMaxContacts; ++i) {
    vpr_.contacts[i] = shm::ContactSlot{};  // slots at and above the count are empty
  }
  if (slots.count == 0) {
    return;
  }
  shm::ContactSlot& to = vpr_.contacts[slots.slot];
  const hcp_contact& from = c.contact;
  protocol::from_wire(from.point, to.point);
  protocol::from_wire(from.normal, to.normal);
  to.distance = static_cast<double>(from.distance);
  to.stiffness = static_cast<double>(from.stiffness);
  to.damping = static_cast<double>(from.damping);
  protocol::from_wire(from.friction, to.friction);
  // An IMPEDANCE client has no object (its surfaces are for the handle's point): the identity.
  to.object_pose = vpr_.command_type == static_cast<std::uint32_t>(shm::CommandType::kImpedance)
                       ? shm::Pose7{0, 0, 0, 0, 0, 0, 1}
                       : vpr_.object_pose;
  to.received_time_ns = now;
  const SampleTiming timing =
      LinkEstimator::time_sample(protocol::unpack_answer_echo(c.answer_echo), answer_log_, now);
  to.sample_time_ns = timing.measured ? timing.sample_time : 0;
}

void Session::take_timed_object(const hcp_control_object_timed& o, TimeNs now) noexcept {
  // The decoder checked the packed rotation (values.cpp): it unpacks.
  const protocol::Quaternion q = protocol::unpack_rotation({o.rotation[0], o.rotation[1]})
                                     .value_or(protocol::Quaternion{0, 0, 0, 1});
  for (std::size_t i = 0; i < 3; ++i) {
    vpr_.object_pose[i] = static_cast<double>(o.position[i]);
    vpr_.object_pose[i + 3] = q[i];
  }
  vpr_.object_pose[6] = q[3];
  protocol::from_wire(o.twist, vpr_.object_twist);
  take_timing(o.answer_echo, o.energy_in, now);
}

void Session::take_timing(std::uint32_t answer_echo, std::uint32_t energy_in_uj,
                          TimeNs now) noexcept {
  // The client's cumulative energy, modulo 2^32 uJ: add up the differences. A difference beyond
  // 4 J in one frame (35 N at 100 m/s for 1 ms is 3.5 J) is not physical: not counted.
  const std::uint32_t step_uj = energy_in_uj - energy_in_last_;
  if (have_energy_ && step_uj <= kMaxEnergyStepUj) {
    energy_in_total_ += static_cast<double>(step_uj) * 1e-6;
  }
  have_energy_ = true;
  energy_in_last_ = energy_in_uj;
  vpr_.client_energy_in = energy_in_total_;
  const SampleTiming timing =
      LinkEstimator::time_sample(protocol::unpack_answer_echo(answer_echo), answer_log_, now);
  link_.add(timing);
  if (timing.measured) {
    vpr_.sample_time_ns = timing.sample_time;
    vpr_.echo_cycle = timing.echo_cycle;
  }
}

std::size_t Session::on_bye(const hcp_frame& in, TimeNs now,
                            std::span<std::uint8_t> reply) noexcept {
  const std::size_t n = ack(LastAck{in.header.sequence, HCP_ACK_OK}, now, reply);  // session token
  counters_.sessions_closed.fetch_add(1, std::memory_order_relaxed);
  end_session(now);
  return n;
}

std::size_t Session::refuse(hcp_refuse_code code, std::uint32_t peer_version,
                            std::uint32_t retry_ms, std::string_view reason, TimeNs now,
                            std::span<std::uint8_t> reply, std::uint64_t token) noexcept {
  hcp_frame out = protocol::make_frame(HCP_REFUSE, token, ++reply_sequence_, now);
  hcp_refuse& r = out.body.hcp_body_u.refuse;
  r.code = code;
  r.peer_version = peer_version;
  r.retry_after_ms = retry_ms;
  protocol::set_text(r.reason, reason);
  return protocol::encode(out, reply);
}

std::size_t Session::welcome(TimeNs now, std::span<std::uint8_t> reply) noexcept {
  hcp_frame out = protocol::make_frame(HCP_WELCOME, session_.token, ++reply_sequence_, now);
  hcp_welcome& w = out.body.hcp_body_u.welcome;
  w.features = session_.features;
  w.watchdog_ms = watchdog_ms_;
  w.period_ns = ports_.period_ns;
  w.cycle = ports_.heartbeat_cycle != nullptr
                ? ports_.heartbeat_cycle->load(std::memory_order_acquire)
                : 0;
  return protocol::encode(out, reply);
}

void Session::publish_vpr(TimeNs now) noexcept {
  if (ports_.vpr != nullptr) {
    vpr_.received_time_ns = now;
    ports_.vpr->publish_quietly(vpr_, now);  // the core polls VPr once per cycle
  }
}

void Session::publish_view() noexcept {
  view_.publish_quietly(session_, 0);
}

}  // namespace hapticctrl::udp_bridge
