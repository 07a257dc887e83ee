// Implements client_session.hpp: the client's side of the protocol as a state machine with no
// socket, no thread and no clock of its own: decoded frames come in with the time they arrived,
// frames to send come out for the caller to send. Its control frames are in
// client_session_control.cpp.
#include "client_session.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::client {
namespace {

std::string version_text(std::uint32_t v) {
  return std::to_string(protocol::version_major(v)) + "." +
         std::to_string(protocol::version_minor(v));
}

/// The features a client of `version` knows (an older version advertised for compatibility
/// testing asks only for its own).
std::uint32_t features_of(std::uint32_t version) {
  std::uint32_t f = protocol::kAllFeatures;
  if (version < protocol::make_version(1, 4)) {
    f &= ~static_cast<std::uint32_t>(HCP_FEATURE_JOINT_CONTROL);
  }
  if (version < protocol::make_version(1, 3)) {
    f &= ~static_cast<std::uint32_t>(HCP_FEATURE_LOCAL_COUPLING);
  }
  if (version < protocol::make_version(1, 1)) {
    f &= ~static_cast<std::uint32_t>(HCP_FEATURE_TIMING);
  }
  return f;
}

Vector6 sum(const Vector6& a, const Vector6& b) noexcept {
  Vector6 s{};
  for (std::size_t i = 0; i < 6; ++i) {
    s[i] = a[i] + b[i];
  }
  return s;
}

/// `pose` shifted by a drift (linear, rotation vector), client frame.
Pose7 drifted(const Pose7& pose, const Vector6& drift) noexcept {
  const Eigen::Vector3d turn(drift[3], drift[4], drift[5]);
  Eigen::Quaterniond q(pose[6], pose[3], pose[4], pose[5]);
  if (turn.norm() > 1e-12) {
    q = Eigen::Quaterniond(Eigen::AngleAxisd(turn.norm(), turn.normalized())) * q;
  }
  return {pose[0] + drift[0], pose[1] + drift[1], pose[2] + drift[2], q.x(), q.y(), q.z(), q.w()};
}

}  // namespace

ClientSession::ClientSession(ConnectOptions options, std::string peer_text)
    : options_(std::move(options)), peer_text_(std::move(peer_text)) {}

std::uint32_t ClientSession::version() const noexcept {
  return options_.advertised_version != 0 ? options_.advertised_version : protocol::kVersion;
}

// --- handshake -----------------------------------------------------------------------------

std::optional<hcp_frame> ClientSession::hello_due(TimePoint now) {
  if (open_ || now < next_hello_) {
    return std::nullopt;
  }
  hcp_frame hello = protocol::make_frame(HCP_HELLO, 0, ++hello_sequence_, to_ns(now));
  hello.header.protocol = version();
  hcp_hello& h = hello.body.hcp_body_u.hello;
  h.min_version =
      options_.advertised_min_version != 0 ? options_.advertised_min_version : version();
  h.features = features_of(version());
  h.watchdog_ms = options_.watchdog_ms;
  protocol::set_text(h.client_name, options_.client_name);
  next_hello_ = now + options_.retransmit_after * 2;
  return hello;
}

HandshakeStep ClientSession::on_handshake_frame(const hcp_frame& frame, TimePoint now) {
  HandshakeStep step;
  if (frame.body.type == HCP_REFUSE) {
    const hcp_refuse& refusal = frame.body.hcp_body_u.refuse;
    last_refusal_ = std::string(protocol::text_of(refusal.reason));
    if (refusal.code == HCP_REFUSE_VERSION) {
      step.fail =
          ClientError(ErrorCode::kVersion,
                      "controller at " + peer_text_ + " refused the connection: " + last_refusal_ +
                          " (this client speaks " + version_text(version()) + ", the controller " +
                          version_text(frame.header.protocol) + ")");
    } else if (refusal.code == HCP_REFUSE_BAD_REQUEST) {  // asking again would not help
      step.fail =
          ClientError(ErrorCode::kRejected,
                      "controller at " + peer_text_ + " refused the connection: " + last_refusal_);
    } else {
      last_refusal_code_ =
          refusal.code == HCP_REFUSE_BUSY ? ErrorCode::kBusy : ErrorCode::kNoController;
      // Ask again once the other session may be gone.
      next_hello_ = now + std::max(options_.retransmit_after,
                                   std::chrono::milliseconds(refusal.retry_after_ms));
    }
    return step;
  }
  if (frame.body.type != HCP_WELCOME) {
    return step;
  }
  if (protocol::version_major(frame.header.protocol) != protocol::version_major(version())) {
    std::string reason;
    step.reply = version_refusal(frame, now, reason);
    step.fail =
        ClientError(ErrorCode::kVersion, "connection to " + peer_text_ + " refused: " + reason);
    return step;
  }
  welcome(frame, now);
  step.welcomed = true;
  return step;
}

void ClientSession::welcome(const hcp_frame& frame, TimePoint now) noexcept {
  const hcp_welcome& w = frame.body.hcp_body_u.welcome;
  token_ = frame.header.token;
  features_ = w.features;
  watchdog_ms_ = w.watchdog_ms;
  period_ = Duration(w.period_ns);
  controller_version_ = frame.header.protocol;
  monitor_.set_period(period_);
  last_heard_ = now;
  open_ = true;
}

hcp_frame ClientSession::version_refusal(const hcp_frame& welcome, TimePoint now,
                                         std::string& reason) const {
  reason = "protocol version mismatch: client " + version_text(version()) + ", controller " +
           version_text(welcome.header.protocol);
  hcp_frame refusal = protocol::make_frame(HCP_REFUSE, welcome.header.token, 1, to_ns(now));
  refusal.header.protocol = version();
  refusal.body.hcp_body_u.refuse.code = HCP_REFUSE_VERSION;
  refusal.body.hcp_body_u.refuse.peer_version = welcome.header.protocol;
  protocol::set_text(refusal.body.hcp_body_u.refuse.reason, reason);
  return refusal;
}

ClientError ClientSession::handshake_timeout() const {
  const std::string waited = std::to_string(options_.connect_timeout.count()) + " ms";
  if (last_refusal_.empty()) {
    return {ErrorCode::kTimeout, "no answer from a hapticctrl controller at " + peer_text_ +
                                     " within " + waited + ": is hapticctrl-udp running there?"};
  }
  return {last_refusal_code_, "controller at " + peer_text_ + " refused the connection for " +
                                  waited + ": " + last_refusal_};
}

// --- an open session -----------------------------------------------------------------------

Arrival ClientSession::on_frame(const hcp_frame& frame, TimePoint now) noexcept {
  if (frame.header.token != token_) {
    monitor_.on_invalid();
    return Arrival::kInvalid;
  }
  last_heard_ = now;
  switch (frame.body.type) {
    case HCP_ANSWER:
    case HCP_ANSWER_TIMED:
    case HCP_ANSWER_COUPLED:
      return on_answer(frame, now) ? Arrival::kAnswer : Arrival::kIgnored;
    case HCP_REFUSE:  // the bridge ended the session, and says why
      close(protocol::text_of(frame.body.hcp_body_u.refuse.reason));
      return Arrival::kClosed;
    case HCP_ACK: {
      const hcp_ack& a = frame.body.hcp_body_u.ack;
      ack_ = {a.acked_sequence, AckOutcome{a.status, std::string(protocol::text_of(a.reason))}};
      return Arrival::kAck;
    }
    default:
      return Arrival::kIgnored;
  }
}

bool ClientSession::on_answer(const hcp_frame& frame, TimePoint now) noexcept {
  const auto& u = frame.body.hcp_body_u;
  const bool coupled = frame.body.type == HCP_ANSWER_COUPLED;
  const bool timed = coupled || frame.body.type == HCP_ANSWER_TIMED;
  const hcp_answer& a =
      coupled ? u.answer_coupled.answer : (timed ? u.answer_timed.answer : u.answer);
  if (!monitor_.on_answer(frame.header.sequence, now, a.echo_sequence,
                          time_point_from_ns(a.echo_time_ns), a.control_received)) {
    return false;  // a duplicate or an answer older than the newest
  }
  StateSnapshot s;
  s.valid = true;
  s.cycle = a.cycle;
  s.received_ns = to_ns(now);
  s.state_word = a.state_word;
  s.core_state = a.core_state;
  s.stop_reason = a.stop_reason;
  s.command_type = static_cast<CommandType>(a.command_type);
  protocol::from_wire(a.coupling_wrench, s.coupling_wrench);
  protocol::from_wire(a.handle_pose, s.handle_pose);
  protocol::from_wire(a.handle_twist, s.handle_twist);
  protocol::from_wire(a.joint_position, s.joint_position);
  protocol::from_wire(a.joint_velocity, s.joint_velocity);
  if (timed) {
    report_ = coupled ? u.answer_coupled.coupling : u.answer_timed.coupling;
    passivity_.on_controller_energy(report_.energy_in);
    passivity_.set_loop(report_.loop_delay_s);
  }
  if (coupled) {
    local_ = u.answer_coupled.local;
    terms_ = terms_of(report_, local_);
    controller_wrench_ = s.coupling_wrench;
    passivity_.set_contact_share(
        std::hypot(local_.contact_normal[0], local_.contact_normal[1], local_.contact_normal[2]));
    channel_pose_ = s.handle_pose;  // the channel's flow at this end: the handle image
    channel_twist_ = s.handle_twist;
    latest_ = s;
    close_locally();
    return true;
  }
  if (timed) {
    // Two-port passivity, this end (1.1): the application gets the wrench with the PC's damper.
    s.coupling_wrench = passivity_.render(s.coupling_wrench);
  }
  latest_ = s;
  return true;
}

void ClientSession::close_locally() noexcept {
  // Protocol 1.3: along a contact in force, the object's wrench from its own newest state and
  // the handle as the answer gives it (local_coupling.hpp); in every other direction the
  // controller's. An IMPEDANCE application sees the handle image as the passivity controller
  // lets it give way.
  StateSnapshot& s = latest_;
  if (s.command_type == CommandType::kImpedance) {
    s.handle_pose = drifted(channel_pose_, passivity_.drift());
    s.handle_twist = sum(channel_twist_, passivity_.drift_rate());
    return;
  }
  Vector6 w = controller_wrench_;
  if (s.coupled() && have_object_) {
    const Vector6 local =
        object_wrench(terms_, channel_pose_, channel_twist_, object_pose_, object_twist_,
                      contact_penetration(), speed_factor_, force_factor_);
    w = along_contact(terms_, controller_wrench_, local);
  }
  s.coupling_wrench = passivity_.render(w);
}

double ClientSession::contact_penetration() const noexcept {
  return contacts_.penetration_along(terms_.contact_normal);
}

std::optional<hcp_frame> ClientSession::keepalive_due(TimePoint now) noexcept {
  const Duration quiet = Duration(std::chrono::milliseconds(watchdog_ms_)) / 4;
  if (!options_.keepalive || !open_ || now - last_send_ <= quiet) {
    return std::nullopt;
  }
  return protocol::make_frame(HCP_KEEPALIVE, token_, next_control_sequence(), to_ns(now));
}

bool ClientSession::close_if_silent(TimePoint now) {
  // A session whose bridge sends nothing at all (no answer, no refusal) for the answer timeout
  // is over: the bridge was killed, or lost its controller without a word.
  const Duration limit = options_.answer_timeout;
  if (limit == Duration::zero() || !open_ || now - last_heard_ <= limit) {
    return false;
  }
  close("no answer from the bridge for " + std::to_string(options_.answer_timeout.count()) + " ms");
  return true;
}

void ClientSession::close(std::string_view reason) {
  if (!open_) {
    return;
  }
  open_ = false;
  closed_reason_.assign(reason);
}

// --- reliable frames -----------------------------------------------------------------------

hcp_frame ClientSession::param_frame(const hcp_param& param, const std::string& what) {
  if (const auto problem = protocol::check_param(param)) {
    throw ClientError(ErrorCode::kInvalidArgument, what + ": " + std::string(*problem));
  }
  if (!open_) {
    throw closed_error(what);
  }
  hcp_frame frame = protocol::make_frame(HCP_PARAM, token_, ++reliable_sequence_, 0);
  frame.body.hcp_body_u.param = param;
  return frame;
}

hcp_frame ClientSession::bye_frame(const std::string& what) {
  if (!open_) {
    throw closed_error(what);
  }
  return protocol::make_frame(HCP_BYE, token_, ++reliable_sequence_, 0);
}

std::optional<AckOutcome> ClientSession::take_ack(std::uint32_t sequence) noexcept {
  if (!ack_ || ack_->first != sequence) {
    return std::nullopt;
  }
  std::optional<AckOutcome> outcome = std::move(ack_->second);
  ack_.reset();
  return outcome;
}

void ClientSession::on_param_applied(const hcp_param& param) noexcept {
  const auto& v = param.hcp_param_u;
  switch (param.id) {
    case HCP_P_WATCHDOG:
      watchdog_ms_ = v.watchdog_ms;
      break;
    case HCP_P_TIME_STEP:
      time_step_ = v.time_step;
      break;
    case HCP_P_FORCE_FACTOR:
      force_factor_ = v.force_factor;
      break;
    case HCP_P_SPEED_FACTOR:
      speed_factor_ = v.speed_factor;
      break;
    case HCP_P_OBJECT:
      if (v.object.attached != 0) {
        // The damper acts on every axis: the smallest moment bounds it (J3: with the largest, a
        // slender MuJoCo peg's damper was 5.5 times its integration's bound about its long axis).
        double smallest = 0.0;
        for (const double moment : v.object.inertia) {
          smallest = moment > 0.0 && (smallest == 0.0 || moment < smallest) ? moment : smallest;
        }
        passivity_.set_object(v.object.mass, smallest);
      }
      break;
    default:
      break;
  }
}

ClientError ClientSession::closed_error(const std::string& what) const {
  return {ErrorCode::kClosed, what + ": the session is closed" +
                                  (closed_reason_.empty() ? "" : " (" + closed_reason_ + ")")};
}

// --- what the session knows ----------------------------------------------------------------

LinkStatistics ClientSession::statistics() const noexcept {
  LinkStatistics st = monitor_.statistics(control_sent_);
  const hcp_coupling_report& r = report_;
  st.link_delay_us = r.link_delay_s * 1e6;
  st.link_jitter_us = r.link_jitter_s * 1e6;
  st.link_loss = r.link_loss;
  st.loop_delay_us = r.loop_delay_s * 1e6;
  st.sample_age_us = r.sample_age_s * 1e6;
  protocol::from_wire(r.gains, st.coupling_gains);
  st.channel_energy_in = passivity_.energy_in();
  st.channel_energy_out = passivity_.energy_out();
  st.controller_energy_in = r.energy_in;
  st.passivity_active_steps = passivity_.active_steps();
  st.contacts_in_force = local_.contacts;
  st.contacts_rejected = local_.contacts_rejected;
  st.max_contact_stiffness = local_.max_contact_stiffness;
  return st;
}

}  // namespace hapticctrl::client
